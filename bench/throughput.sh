#!/usr/bin/env bash
# Throughput and memory bandwidth of the step, with a STREAM-triad figure from the same run and
# YADE's concrete model side by side (issue: benchmarks in bench/).
#
# Usage:
#   bash bench/throughput.sh [STEPS=500] [BUILD_DIR=build]
#     1. header: date, nproc, CPU model;
#     2. rcdem_step_bench, STEPS timed steps after 50 warm-up ones (best of REPEATS), on the 160 mm
#        cube (examples/uniaxial/compression.toml, used as is: the step bench ignores stop rules)
#        and on the AN4 NL-B beam (examples/three_point_bending/study/AN4_NL-B.toml, in place: it
#        includes a file by a relative path), at 1 and 2 threads, ROUNDS times each, every time
#        right after a STREAM triad (build/bench/rcdem_stream) at the same thread count:
#        particle-, contact-, local-point-steps/s, counted bytes per step (the "# bytes:" line),
#        achieved GB/s, and fraction_of_stream per round, then its median over the rounds;
#     3. YADE CpmMat (bench/yade_cpm.py) on as many spheres as the cube has particles, STEPS steps,
#        ROUNDS times in one YADE process, each followed by rcdem's cube (best of REPEATS) at
#        THREADS threads: one ratio per round, and the best-against-best ratio in a comment;
#     4. a summary, one comment line per target of the issue (the step loop at >= 50% of STREAM
#        on each specimen at THREADS threads, >= 10x YADE), with the median and whether it is met;
#     5. last line: ratio_contact_steps_vs_yade=<the median of the rounds' ratios of rcdem's cube
#        contact-steps/s to YADE's>, both at THREADS threads.
#     Why rounds: this machine's speed and bandwidth drift by 2-3x over minutes (bench/RESULTS.md,
#     session 11), so only figures taken seconds apart can be compared.
#   bash bench/throughput.sh --cracked [STEPS=200] [BUILD_DIR=build]
#     rcdem against YADE per particle-step, intact and cracked (issue 43): the 160 mm tension cube
#     (examples/uniaxial/tension.toml) intact and from its checkpoint at step 12,000, past the
#     peak (CHECKPOINT, made here with rcdem_step_bench --save-checkpoint if not given), against
#     YADE's cube intact and pulled past its peak to 0.8 of it (bench/yade_cpm.py ... cracked);
#     each state in one YADE process of ROUNDS rounds, every YADE timing followed by rcdem's
#     (best of REPEATS) at THREADS threads. One ratio per round; the medians; last lines
#     ratio_particle_steps_vs_yade_intact=<median> and ..._cracked=<median>. HOLD=0: rcdem's
#     cracked cube with solver.hold_unloading_contacts = false (on by default since 2026-11-28).
#     The checkpoint is made with the scenario as it is (the held contacts in it, format 6).
#     REFERENCE_BUILD: another commit's build directory, timed the same way right after rcdem in
#     every round (its own ratio per round, its medians ratio_reference_..._intact/_cracked), so
#     that the targets set on another machine can be read against that commit on this one; with
#     REFERENCE_CUBE (its version of the cube's scenario, default the cube) and
#     REFERENCE_CHECKPOINT (its cracked cube at step 12,000, required).
#   bash bench/throughput.sh --scaling [STEPS=200] [BUILD_DIR=build]
#     rcdem_step_bench on cubes of SCALING_SIZES (default 0.07 0.11 0.16 m: about 0.9k, 3.4k and
#     10.3k particles, 12x) at THREADS threads; one line per size with the time per step per
#     particle.
# Environment (all optional): THREADS (2: the YADE comparison and the scaling runs), RCDEM_THREADS
# ("1 2"), STREAM_N (4e7 elements per array: 3 x 320 MB), YADE_N (the cube's particle count),
# YADE_STEPS (STEPS), REPEATS (3: rcdem's fastest of 3 back-to-back timings within a round),
# ROUNDS (3), SKIP_BEAM=1, SCALING_SIZES. A quick end-to-end check:
#   STREAM_N=1e7 RCDEM_THREADS=1 THREADS=1 SKIP_BEAM=1 YADE_N=2000 bash bench/throughput.sh 20
# Build first: ninja -C build rcdem_stream rcdem_step_bench. YADE: Debian's yade (/usr/bin/yade).
set -euo pipefail
cd "$(dirname "$0")/.."

SCALING=0
CRACKED=0
if [[ "${1:-}" == "--scaling" ]]; then
  SCALING=1
  shift
elif [[ "${1:-}" == "--cracked" ]]; then
  CRACKED=1
  shift
fi
K=${1:-$([[ $SCALING == 1 || $CRACKED == 1 ]] && echo 200 || echo 500)}
BUILD=${2:-build}
THREADS=${THREADS:-2}
RCDEM_THREADS=${RCDEM_THREADS:-"1 2"}
REPEATS=${REPEATS:-3}
ROUNDS=${ROUNDS:-3}
STREAM_N=${STREAM_N:-4e7}
STEP_BENCH="$BUILD/bench/rcdem_step_bench"
STREAM="$BUILD/bench/rcdem_stream"
YADE=${YADE:-yade}
PY=/usr/bin/python3
# YADE is the peer of the comparison: Debian's package, installed here if missing (as root).
if [[ $SCALING == 0 ]] && ! command -v "$YADE" >/dev/null; then
  if [[ $(id -u) == 0 ]]; then
    echo "installing Debian's yade (the peer of the comparison)..." >&2
    DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends yade >/dev/null
  else
    echo "yade not found: install Debian's package (apt-get install yade) or set YADE=" >&2; exit 1
  fi
fi

for exe in "$STEP_BENCH" "$STREAM"; do
  [[ -x "$exe" ]] || { echo "missing $exe: build with ninja -C $BUILD rcdem_stream rcdem_step_bench" >&2; exit 1; }
done

# The value of key=... in a line of key=value pairs.
kv() { tr ' ' '\n' <<<"$2" | sed -n "s/^$1=//p" | head -n1; }
# Floating-point arithmetic.
calc() { awk "BEGIN { printf \"%.4g\", $1 }"; }

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

echo "date: $(date -u +%F)  nproc: $(nproc)  cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')  steps: $K  repeats: $REPEATS (best of each)"

if [[ $SCALING == 1 ]]; then
  echo "scaling: rcdem_step_bench on cubes, $THREADS thread(s), $K steps each"
  for s in ${SCALING_SIZES:-0.07 0.11 0.16}; do
    sed -e "s/^size = .*/size = [$s, $s, $s]/" examples/uniaxial/compression.toml > "$tmp/cube_$s.toml"
    line=$(OMP_NUM_THREADS=$THREADS "$STEP_BENCH" "$tmp/cube_$s.toml" "$K" 50 "$REPEATS" | grep -v '^#')
    bodies=$(kv bodies "$line")
    secs=$(kv seconds "$line")
    echo "size_m=$s bodies=$bodies contacts=$(kv contacts "$line") local_points=$(kv local_points "$line")" \
         "steps_per_s=$(kv steps_per_s "$line") ns_per_particle_step=$(calc "$secs / $K / $bodies * 1e9")" \
         "achieved_GBps=$(kv achieved_GBps "$line")"
  done
  exit 0
fi

# The median of numbers (one per argument).
median() { printf '%s\n' "$@" | sort -g | awk '{ v[NR] = $1 } END { m = (NR % 2) ? v[(NR + 1) / 2] : 0.5 * (v[NR / 2] + v[NR / 2 + 1]); printf "%.4g", m }'; }

if [[ $CRACKED == 1 ]]; then
  cube=examples/uniaxial/tension.toml
  ckpt=${CHECKPOINT:-}
  if [[ -z "$ckpt" ]]; then
    mkdir -p results/bench_ckpt_tension
    ckpt=results/bench_ckpt_tension/checkpoint_000000012000.h5
    if [[ ! -f "$ckpt" ]]; then
      echo "making the cracked cube's checkpoint (12,000 steps)..." >&2
      OMP_NUM_THREADS=$THREADS "$STEP_BENCH" "$cube" 1 12000 1 \
        --save-checkpoint results/bench_ckpt_tension > /dev/null
    fi
  fi
  cracked_cube=$cube
  if [[ "${HOLD:-1}" == 0 ]]; then
    cracked_cube="$tmp/tension_visit.toml"
    awk '{ print } /^\[solver\]/ { print "hold_unloading_contacts = false" }' "$cube" > "$cracked_cube"
  fi
  ref=${REFERENCE_BUILD:-}
  if [[ -n "$ref" ]]; then
    [[ -x "$ref/bench/rcdem_step_bench" ]] || { echo "REFERENCE_BUILD: no $ref/bench/rcdem_step_bench" >&2; exit 1; }
    [[ -f "${REFERENCE_CHECKPOINT:-}" ]] || { echo "REFERENCE_CHECKPOINT: the reference's cracked cube checkpoint (a file) is required with REFERENCE_BUILD" >&2; exit 1; }
    ref_cube=${REFERENCE_CUBE:-$cube}
    echo "reference: $ref (git $(git -C "$ref/.." rev-parse --short HEAD 2>/dev/null || echo '?')), $ref_cube, from $REFERENCE_CHECKPOINT"
  fi
  echo "cracked: rcdem $cube intact and from $ckpt (HOLD=${HOLD:-1}); YADE ${YADE_N:-10335} spheres; $THREADS thread(s), $ROUNDS rounds"
  # The step bench's command: BINARY SCENARIO WARMUP [CHECKPOINT], its result line only.
  step_cmd() { echo "OMP_NUM_THREADS=$THREADS $1 $2 $K $3 $REPEATS ${4:+--checkpoint $4} | grep -v '^#'"; }
  for state in intact cracked; do
    if [[ $state == intact ]]; then
      between=$(step_cmd "$STEP_BENCH" "$cube" 50)
      ref_between=$([[ -z "$ref" ]] || step_cmd "$ref/bench/rcdem_step_bench" "$ref_cube" 50)
    else
      between=$(step_cmd "$STEP_BENCH" "$cracked_cube" 20 "$ckpt")
      ref_between=$([[ -z "$ref" ]] || step_cmd "$ref/bench/rcdem_step_bench" "$ref_cube" 20 "$REFERENCE_CHECKPOINT")
    fi
    [[ -z "$ref" ]] || between+="; $ref_between | sed 's/^scenario=/reference scenario=/'"
    if ! YADE_BETWEEN="$between" "$YADE" -n -x -j "$THREADS" bench/yade_cpm.py "${YADE_N:-10335}" \
        "$K" "$ROUNDS" "$state" > "$tmp/yade_$state.log" 2>&1; then
      cat "$tmp/yade_$state.log" >&2
      echo "yade failed ($state)" >&2
      exit 1
    fi
    grep '^# yade_cpm' "$tmp/yade_$state.log" || true
    spheres=$(kv yade_spheres "$(grep '^yade_threads=' "$tmp/yade_$state.log" | tail -n1)")
    ratios=()
    ref_ratios=()
    ysteps=""
    yref=""
    while IFS= read -r l; do
      case "$l" in
        yade_round=*) ysteps=$(calc "$K / $(kv yade_seconds "$l")"); yref=$ysteps ;;
        "reference scenario="*)
          [[ -n "$yref" ]] || continue
          l=${l#reference }
          ref_ratios+=("$(calc "$(kv steps_per_s "$l") * $(kv bodies "$l") / ($yref * $spheres)")")
          echo "$state round=${#ref_ratios[@]} reference_steps_per_s=$(kv steps_per_s "$l") reference_bodies=$(kv bodies "$l") reference_ratio_particle_steps=${ref_ratios[-1]}"
          yref=""
          ;;
        scenario=*)
          [[ -n "$ysteps" ]] || continue
          rps=$(calc "$(kv steps_per_s "$l") * $(kv bodies "$l")")
          yps=$(calc "$ysteps * $spheres")
          ratios+=("$(calc "$rps / $yps")")
          echo "$state round=${#ratios[@]} threads=$THREADS yade_steps_per_s=$ysteps yade_spheres=$spheres rcdem_steps_per_s=$(kv steps_per_s "$l") rcdem_bodies=$(kv bodies "$l") held_contacts=$(kv held_contacts "$l") ratio_particle_steps=${ratios[-1]}"
          ysteps=""
          ;;
      esac
    done < "$tmp/yade_$state.log"
    [[ ${#ratios[@]} -gt 0 ]] || { cat "$tmp/yade_$state.log" >&2; echo "no paired rounds ($state)" >&2; exit 1; }
    echo "ratio_particle_steps_vs_yade_$state=$(median "${ratios[@]}")"
    if [[ -n "$ref" ]]; then
      [[ ${#ref_ratios[@]} -gt 0 ]] || { cat "$tmp/yade_$state.log" >&2; echo "no reference rounds ($state)" >&2; exit 1; }
      echo "ratio_reference_particle_steps_vs_yade_$state=$(median "${ref_ratios[@]}")"
    fi
  done
  exit 0
fi

# One line of the closing summary: the issue's target, the median measured, met or not.
verdict() { awk -v what="$1" -v x="$2" -v goal="$3" 'BEGIN { printf "# target %s: median %s, %s\n", what, x, (x >= goal) ? "met" : "NOT met" }'; }
summary=()

# rcdem: ROUNDS rounds per scenario and thread count, each a STREAM triad at that thread count
# and right after it the step bench (best of REPEATS): the fraction of a round compares two figures
# taken seconds apart, and the median over the rounds is the result (this machine's bandwidth
# drifts by 2x over minutes: a STREAM figure from the start of the run says little about a timing
# ten minutes later).
scenarios=("cube=examples/uniaxial/compression.toml")
[[ "${SKIP_BEAM:-0}" == 1 ]] || scenarios+=("AN4_NL-B=examples/three_point_bending/study/AN4_NL-B.toml")
cube_bodies=""
cube_points_per_contact=""
for entry in "${scenarios[@]}"; do
  name=${entry%%=*}
  file=${entry#*=}
  # The YADE comparison's thread count always runs for the cube.
  list=$RCDEM_THREADS
  [[ $name == cube && " $list " != *" $THREADS "* ]] && list="$list $THREADS"
  for t in $list; do
    fractions=()
    for ((r = 1; r <= ROUNDS; r++)); do
      sline=$(OMP_NUM_THREADS=$t "$STREAM" "$STREAM_N")
      echo "$sline"
      sgbps=$(kv stream_triad_GBps "$sline")
      out=$(OMP_NUM_THREADS=$t "$STEP_BENCH" "$file" "$K" 50 "$REPEATS")
      echo "$out"
      line=$(grep -v '^#' <<<"$out")
      gbps=$(kv achieved_GBps "$line")
      f=$(calc "$gbps / $sgbps")
      fractions+=("$f")
      echo "$name threads=$t round=$r achieved_GBps=$gbps stream_triad_GBps=$sgbps fraction_of_stream=$f"
      if [[ $name == cube ]]; then
        cube_bodies=$(kv bodies "$line")
        cube_points_per_contact=$(calc "$(kv local_points "$line") / $(kv contacts "$line")")
      fi
    done
    fmed=$(median "${fractions[@]}")
    echo "$name threads=$t rounds=$ROUNDS fraction_of_stream_median=$fmed fraction_of_stream_rounds=$(IFS=,; echo "${fractions[*]}")"
    [[ $t == "$THREADS" ]] && summary+=("$(verdict "step loop >= 50% of STREAM, $name, $t threads" "$fmed" 0.5)")
  done
done

# YADE: ROUNDS repetitions in one YADE process (its packing takes a while), each followed by
# rcdem's cube at the same thread count (bench/yade_cpm.py, YADE_BETWEEN): one ratio per round.
N=${YADE_N:-$cube_bodies}
between="OMP_NUM_THREADS=$THREADS $STEP_BENCH examples/uniaxial/compression.toml $K 50 $REPEATS | grep -v '^#'"
echo "yade: $YADE -n -x -j $THREADS bench/yade_cpm.py $N ${YADE_STEPS:-$K} $ROUNDS, each round followed by: $between"
if ! YADE_BETWEEN="$between" "$YADE" -n -x -j "$THREADS" bench/yade_cpm.py "$N" "${YADE_STEPS:-$K}" "$ROUNDS" > "$tmp/yade.log" 2>&1; then
  cat "$tmp/yade.log" >&2
  echo "yade failed" >&2
  exit 1
fi
grep '^# yade_cpm' "$tmp/yade.log" || true
ratios=()
ybest=0
rbest=0
ycs=""
round=0
while IFS= read -r l; do
  case "$l" in
    yade_round=*)
      ycs=$(kv yade_contact_steps_per_s "$l")
      round=$(kv yade_round "$l")
      ybest=$(awk -v a="$ybest" -v b="$ycs" 'BEGIN { print (b > a) ? b : a }')
      ;;
    scenario=*)
      [[ -n "$ycs" ]] || continue
      rcs=$(kv contact_steps_per_s "$l")
      rbest=$(awk -v a="$rbest" -v b="$rcs" 'BEGIN { print (b > a) ? b : a }')
      ratio=$(calc "$rcs / $ycs")
      ratios+=("$ratio")
      echo "round=$round threads=$THREADS yade_contact_steps_per_s=$ycs rcdem_cube_contact_steps_per_s=$rcs steps_per_s=$(kv steps_per_s "$l") ratio=$ratio"
      ycs=""
      ;;
  esac
done < "$tmp/yade.log"
yline=$(grep '^yade_threads=' "$tmp/yade.log" | tail -n1)
[[ -n "$yline" && ${#ratios[@]} -gt 0 ]] || { cat "$tmp/yade.log" >&2; echo "no result line from yade" >&2; exit 1; }
echo "$yline"
echo "# rcdem cube ($THREADS threads): best $rbest contact-steps/s, $cube_points_per_contact local points per" \
     "contact; YADE: best $ybest contact-steps/s, one force point per bond; best against best $(calc "$rbest / $ybest");" \
     "ratios of the $ROUNDS paired rounds: $(IFS=,; echo "${ratios[*]}")"
ratio=$(median "${ratios[@]}")
summary+=("$(verdict "contact-steps/s >= 10x YADE CpmMat's, $THREADS threads" "$ratio" 10)")
printf '%s\n' "${summary[@]}"
echo "ratio_contact_steps_vs_yade=$ratio"
