#!/bin/bash
# The .deb on a clean machine (issue 45, item 4): a minimal Debian 12 root made by debootstrap
# (no Python, no rcdem, none of its libraries), the package installed there by apt with its
# dependencies, then, from a fresh directory in that root: rcdem --version, the man page, an
# installed example run by the CLI, and the same example stepped through `import rcdem`, whose
# load must equal the CLI's. Needs root, debootstrap and Debian's package registry; run it after
# a build (it packs build/ with cpack).
#
# usage: sudo bash tools/deb_on_clean_debian.sh [BUILD_DIR] [ROOT_DIR]
set -euo pipefail
build=$(realpath "${1:-build}")
root=${2:-/tmp/rcdem_clean_debian}
command -v debootstrap > /dev/null || apt-get install -y -q debootstrap
if [ ! -x "$root/bin/bash" ]; then
  debootstrap --variant=minbase bookworm "$root" http://deb.debian.org/debian
fi
pkg=$(mktemp -d)
trap 'umount "$root/proc" 2> /dev/null || true; rm -rf "$pkg"' EXIT
cpack -G DEB -B "$pkg" --config "$build/CPackConfig.cmake" > /dev/null
cp "$pkg"/rcdem_*.deb "$root/tmp/rcdem.deb"
cp /etc/resolv.conf "$root/etc/resolv.conf"
mountpoint -q "$root/proc" || mount -t proc proc "$root/proc"
cat > "$root/tmp/try_rcdem.sh" <<'INNER'
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive
apt-get update -q > /dev/null 2>&1
apt-get install -y -q --reinstall /tmp/rcdem.deb > /tmp/apt_install.log
grep "^Setting up rcdem" /tmp/apt_install.log
work=$(mktemp -d) && cd "$work"
echo "\$ rcdem --version"; rcdem --version
echo "\$ ls /usr/share/man/man1/rcdem.1"; ls /usr/share/man/man1/rcdem.1
example=/usr/share/rcdem/examples/uniaxial/tension.toml
echo "\$ rcdem -q run $example -o tension --set stop.steps=400"
rcdem -q run "$example" -o tension --set stop.steps=400
ls tension
cat > api.py <<'PY'
import sys
import rcdem
sc = rcdem.Scenario.load(sys.argv[1]).set("stop.steps", 400)
sim = rcdem.Simulation(sc)
sim.step(400)
h = rcdem.load_run("tension").history
print("import rcdem from", rcdem.__file__)
print(f"steps {sim.steps}, load {sim.load:.6g} N; the CLI's last row {h['load_N'][-1]:.6g} N")
sys.exit(0 if abs(sim.load - h["load_N"][-1]) <= 1e-9 * abs(sim.load) else 1)  # the CSV keeps 10 digits
PY
echo "\$ python3 api.py $example"; python3 api.py "$example"
INNER
chroot "$root" /bin/bash /tmp/try_rcdem.sh
echo "ok: the package installs and works on a clean Debian root ($root)"
