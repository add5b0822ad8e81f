#!/usr/bin/env bash
# Packs what the distributed run needs on a machine that has no Open MPI and cannot install it
# (the lent many-core machine): the `mpi` build of rcdem, Open MPI's launcher, its components and
# help files, and every shared library they load, into .devcarry/ (git-ignored through
# .git/info/exclude), about 20 MB. Open MPI is relocated with OPAL_PREFIX; only the shared-memory
# transports are kept (self, vader), so the network stacks (UCX, libfabric, PSM2, verbs) stay behind.
#
# Usage: bash bench/device_bundle.sh        (after: cmake --preset mpi && ninja -C build-mpi rcdem)
# Prints the environment to set on the other machine before bench/device_mpi_scaling.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
[[ -x build-mpi/rcdem ]] || { echo "missing build-mpi/rcdem: cmake --preset mpi && ninja -C build-mpi rcdem" >&2; exit 1; }
command -v orterun > /dev/null || { echo "missing Open MPI: apt-get install openmpi-bin libopenmpi-dev" >&2; exit 1; }
grep -qx '/.devcarry/' .git/info/exclude 2>/dev/null || echo '/.devcarry/' >> .git/info/exclude
rm -rf .devcarry
B=.devcarry/ompi
OMPI_LIB=$(dirname "$(readlink -f "$(ompi_info --path libdir --parsable | cut -d: -f3-)/libmpi.so")")
OMPI_LIBDIR=$(ompi_info --path libdir --parsable | cut -d: -f3-)
PKGLIB=$(ompi_info --path pkglibdir --parsable | cut -d: -f3-)
PKGDATA=$(ompi_info --path pkgdatadir --parsable | cut -d: -f3-)
PREFIX=$(ompi_info --path prefix --parsable | cut -d: -f3-)
mkdir -p "$B/lib" "$B$PREFIX/bin" "$B$OMPI_LIBDIR" "$(dirname "$B$PKGDATA")"
cp "$(readlink -f "$(command -v orterun)")" "$B$PREFIX/bin/orterun"
cp "$(command -v orted)" "$B$PREFIX/bin/"
cp -a "$PKGLIB" "$B$OMPI_LIBDIR/"
cp -a "$PKGDATA" "$B$PKGDATA"
for f in "$OMPI_LIBDIR"/*.so*; do [[ -f $f ]] && cp -L "$f" "$B$OMPI_LIBDIR/"; done
# What the network transports and the Fortran, Java and OpenSHMEM layers need: not carried.
drop='libuc[pstm]|libfabric|libpsm|libnl-|libibverbs|librdmacm|liboshmem|libmpi_mpifh|libmpi_java|libgfortran|libquadmath|libmpi_usempi|libmca_common_(ucx|ofi|verbs)'
for c in "$B$OMPI_LIBDIR"/*.so* "$B$OMPI_LIBDIR/$(basename "$PKGLIB")"/*.so; do
  if ldd "$c" | grep -qE "$drop" || basename "$c" | grep -qE "$drop|oshmem|mca_(spml|sshmem|memheap|scoll|atomic)_"; then rm "$c"; fi
done
ldd build-mpi/rcdem "$B$PREFIX/bin/orterun" "$B$PREFIX/bin/orted" "$B$OMPI_LIBDIR"/*.so* \
    "$B$OMPI_LIBDIR/$(basename "$PKGLIB")"/*.so 2>/dev/null | awk '/=>/ {print $3}' | sort -u |
  grep -vE 'libc\.so|libm\.so|libpthread|libdl\.so|librt\.so|ld-linux' | grep -vE "$drop" |
  while read -r lib; do cp -L "$lib" "$B/lib/"; done
cp build-mpi/rcdem .devcarry/rcdem
echo "packed .devcarry ($(du -sh .devcarry | cut -f1)); Open MPI from $OMPI_LIB. On the other machine, from the repository root:"
cat << EOF
B=\$PWD/$B; export OPAL_PREFIX=\$B$PREFIX PATH=\$B$PREFIX/bin:\$PATH LD_LIBRARY_PATH=\$B/lib:\$B$OMPI_LIBDIR \\
  OMPI_MCA_btl=self,vader OMPI_MCA_pml=ob1 OMPI_MCA_plm_rsh_agent=false OMPI_MCA_btl_vader_backing_directory=/tmp \\
  OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
bash bench/device_mpi_scaling.sh \$OUT .devcarry/rcdem \$B$PREFIX/bin/orterun
EOF
