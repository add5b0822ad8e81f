#!/bin/bash
# Issue 43's softening clock (77b61c3), 1 thread, in sequence (log: the .txt beside it).
# A = bd1a70a's build/bench/rcdem_step_bench (softening holds without the clock; built in a
# worktree at /tmp/a45), B = 77b61c3's. "soft": the scenario with
# `[solver] hold_softening_contacts = true` added (a copy in results/s45/, include made absolute);
# "off": the scenario as it is (B's default step, nothing softening held).
# Checkpoints: CK8 the tension cube at step 12,000 written by A (format 8: B reads it with every
# clock 0); CK9 the same written by B (format 9); CKA the AN4 NL-B beam at step 112,000 written by
# A from 551b674's checkpoint (`rcdem_step_bench AN4 1 ... --checkpoint OLD --save-checkpoint DIR`).
# The figure regeneration (nice 19) was paused with SIGSTOP during each comparison.
cd "$(dirname "$0")/../.."
date -u; nproc; grep -m1 "model name" /proc/cpuinfo
S=results/s45; mkdir -p $S/bin
soft() { sed -e 's|^\[solver\]|[solver]\nhold_softening_contacts = true|' \
             -e "s|include = \[\"../../calibrated_contact.toml\"\]|include = [\"$PWD/examples/calibrated_contact.toml\"]|" \
             "$1" > "$S/$(basename "${1%.toml}")_soft.toml"; }
soft examples/uniaxial/tension.toml; soft examples/three_point_bending/study/AN4_NL-B.toml
wrap() {  # wrap NAME BINARY: rcdem_step_bench on the scenario's softening variant
  printf '#!/bin/bash\ns=$1; shift\nexec %s %s/$(basename "${s%%.toml}")_soft.toml "$@"\n' \
         "$2" "$PWD/$S" > "$S/bin/$1"; chmod +x "$S/bin/$1"; }
wrap soft_A /tmp/a45/build/bench/rcdem_step_bench; wrap soft_B "$PWD/build/bench/rcdem_step_bench"
printf '#!/bin/bash\nexec %s "$@"\n' "$PWD/build/bench/rcdem_step_bench" > $S/bin/off_B
chmod +x $S/bin/off_B
CUBE=examples/uniaxial/tension.toml; AN4=examples/three_point_bending/study/AN4_NL-B.toml
CK8=$S/ck_cube8/checkpoint_000000012000.h5; CK9=$S/ck_cube/checkpoint_000000012000.h5
CKA=$S/ck_an4/checkpoint_000000112000.h5
ab() { OMP_NUM_THREADS=1 /usr/bin/python3 bench/ab_compare.py "$@"; }
echo "== cube: off B vs soft B (B's checkpoint)"
ab 6 $S/bin/off_B $S/bin/soft_B $CUBE 300 20 1 --checkpoint $CK9
echo "== cube (A's checkpoint, format 8): soft A (77b61c3^) vs soft B (clock)"
ab 8 $S/bin/soft_A $S/bin/soft_B $CUBE 300 20 1 --checkpoint $CK8
echo "== AN4 NL-B at step 112,000 (A's checkpoint): soft A (77b61c3^) vs soft B (clock)"
ab 6 $S/bin/soft_A $S/bin/soft_B $AN4 100 50 1 --checkpoint $CKA
echo "== AN4: off B vs soft B"
ab 6 $S/bin/off_B $S/bin/soft_B $AN4 100 50 1 --checkpoint $CKA
echo "== AN4 NL-B at step 112,000, 300 steps after 200: soft A (77b61c3^) vs soft B (clock)"
ab 6 $S/bin/soft_A $S/bin/soft_B $AN4 300 200 1 --checkpoint $CKA
echo "== AN4, 300 after 200: off B vs soft B"
ab 6 $S/bin/off_B $S/bin/soft_B $AN4 300 200 1 --checkpoint $CKA
date -u
