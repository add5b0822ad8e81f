#!/usr/bin/env bash
# Installs the Debian packages rcdem needs (only those missing) and builds a Release binary in
# build/ with its tests, benchmarks and Python module, or only the targets given
# (`setup.sh rcdem`). Safe to run again: it does nothing that is already done.
set -euo pipefail
cd "$(dirname "$0")/.."

# What building and running the program needs (the quick start installs only these)...
PACKAGES=(build-essential cmake ninja-build pkg-config git
          voro++-dev libeigen3-dev libtomlplusplus-dev libcli11-dev libfmt-dev nlohmann-json3-dev
          libhdf5-dev python3-matplotlib python3-meshio)
# ...and what the tests, benchmarks, Python module and package need besides.
[ $# -eq 0 ] && PACKAGES+=(libgtest-dev libgmock-dev libbenchmark-dev libmetis-dev
          python3 python3-dev python3-numpy python3-scipy
          python3-pytest python3-h5py hdf5-tools pybind11-dev help2man)
# The distributed run's build (CMakePresets.json "mpi"; the test command builds it): Open MPI,
# and the HDF5 library built with it.
[ "${RCDEM_SETUP_MPI:-0}" = 1 ] && PACKAGES+=(libopenmpi-dev openmpi-bin libhdf5-openmpi-dev)

BUILD_DIR=${BUILD_DIR:-build}
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}" >&2
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# The portable reference build (CMakePresets.json "release"); RCDEM_NATIVE=ON for -march=native.
# A build of every target builds the tests, benchmarks and module; a first build of named targets
# configures without them (their packages may be missing), as a unity build (the library in half
# the time, the same bits); a later full build turns them on and keeps the library as it is.
if [ $# -eq 0 ]; then
  PARTS=(-DRCDEM_BUILD_TESTS=ON -DRCDEM_BUILD_BENCH=ON -DRCDEM_PYTHON=ON)
elif [ ! -f "$BUILD_DIR/CMakeCache.txt" ]; then
  PARTS=(-DRCDEM_BUILD_TESTS=OFF -DRCDEM_BUILD_BENCH=OFF -DRCDEM_PYTHON=OFF -DRCDEM_UNITY_BUILD=ON)
else
  PARTS=()
fi
cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Release -DRCDEM_NATIVE="${RCDEM_NATIVE:-OFF}" \
      ${RCDEM_WERROR:+-DRCDEM_WERROR=$RCDEM_WERROR} "${PARTS[@]}" >/dev/null
# Arguments name the targets to build (the quick start needs only `rcdem`); none builds all.
cmake --build "$BUILD_DIR" -j "$(nproc)" ${1:+--target "$@"}
