#!/bin/bash
# The README's main job on a bare machine: a minimal Debian 12 root made by debootstrap (no
# compiler, no Python, none of rcdem's libraries), a clone of this repository in it, then
# `bash scripts/quickstart.sh` timed from the clone as a new user would run it (installing the
# packages, building, running the quick AN0 beam). Needs root, debootstrap and Debian's package
# registry. The root is made before the clock starts: a fresh machine has its base system.
#
# usage: sudo bash tools/quickstart_on_clean_debian.sh [ROOT_DIR]
set -euo pipefail
repo=$(realpath "$(dirname "$0")/..")
root=${1:-/tmp/rcdem_quickstart_root}
command -v debootstrap > /dev/null || apt-get install -y -q debootstrap
[ -e "$root" ] && { echo "error: $root exists; give a new directory (this script makes its own root)" >&2; exit 1; }
debootstrap --variant=minbase bookworm "$root" http://deb.debian.org/debian > "$root.debootstrap.log" 2>&1
trap 'umount "$root/proc" 2> /dev/null || true' EXIT
git clone -q "$repo" "$root/root/rcdem"
cp /etc/resolv.conf "$root/etc/resolv.conf"
mount -t proc proc "$root/proc"
# A machine with a clone has git: installed before the clock starts.
chroot "$root" /bin/bash -c 'apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends git' > "$root.git.log" 2>&1
echo "clean root: $(chroot "$root" /bin/bash -c 'which c++ cmake python3 rcdem || true' | wc -l) of c++, cmake, python3, rcdem found; git $(chroot "$root" git --version | cut -d' ' -f3)"
echo "machine: nproc $(nproc), $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), commit $(git -C "$repo" rev-parse --short HEAD), $(date -u '+%F %H:%M UTC')"
start=$(date +%s)
# Each line of the log starts with the seconds since the start.
chroot "$root" /bin/bash -c 'cd /root/rcdem && bash scripts/quickstart.sh' 2>&1 |
  while IFS= read -r line; do echo "$(( $(date +%s) - start )) $line"; done > "$root.quickstart.log"
end=$(date +%s)
tail -4 "$root.quickstart.log"
grep -m1 "^| AN0 " "$root/root/rcdem/results/quick_study/table3.md" || true  # its Table 3 row
echo "quickstart on a clean root: $((end - start)) s (log $root.quickstart.log)"
