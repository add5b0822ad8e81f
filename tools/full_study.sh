#!/bin/bash
# The three-point bending study of docs/case-study.md (issue 27), by one command:
#   full size: every case on packing 1 (STUDY_DIR/seed1); AN2 and AN4 with all interfaces, AN0
#              and AN1 NL-B (the brittle side of the transition) and AN3 NL-B (so that every
#              beam's NL-B peak has a mean and sd) on packings 2 and 3 as well
#              (STUDY_DIR/more); one report over both (tools/study_report.py -o STUDY_DIR/report);
#   quick:     every case on packings 1-5 (STUDY_DIR/quick5);
# then what docs keeps of each (tools/publish_study.py). Resumable: run it again after an
# interruption; finished runs are kept.
#
# usage: tools/full_study.sh [STUDY_DIR [DOCS_DIR]]
#        tools/full_study.sh --save STUDY_DIR DOCS_DIR
#   STUDY_DIR  default results/study_full
#   DOCS_DIR   where DOCS_DIR/full and DOCS_DIR/quick5 get the tables and figures; default none.
#              The full-size part is longer than a working session on 2 cores: --save packs the
#              finished runs of seed1/ and more/ into DOCS_DIR/full/runs/*.tar.xz
#              (tools/study_archive.py; to be committed), and a later call on a machine without
#              STUDY_DIR/seed1 (or more) unpacks them there first and runs only the rest.
#   RCDEM      the binary (default build/rcdem); it must be the commit that made the finished
#              runs (their manifests' git_hash), or the study would mix binaries: refused unless
#              MIXED_COMMITS=1. MORE_CASES: the cases run on packings 2 and 3 (default as above;
#              "all" for all 13). FULL_JOBS: full-size runs at a time (default 1: on 2 cores one
#              run with both threads beat two of one thread each, bench/RESULTS.md session 25);
#              the quick study runs nproc at a time.
set -euo pipefail
cd "$(dirname "$0")/.."
RCDEM=${RCDEM:-build/rcdem}
PY=/usr/bin/python3
PARTS="seed1 more"

if [ "${1:-}" = --save ]; then
  [ $# -eq 3 ] || { echo "usage: tools/full_study.sh --save STUDY_DIR DOCS_DIR" >&2; exit 2; }
  mkdir -p "$3/full/runs"
  for part in $PARTS; do
    [ -f "$2/$part/cases.csv" ] || continue
    rm -f "$3/full/runs/$part.tar.xz"   # the earlier archive of this part is in git's history
    $PY tools/study_archive.py pack "$2/$part" "$3/full/runs/$part.tar.xz"
  done
  exit 0
fi

D=${1:-results/study_full}
DOCS=${2:-}
MORE=${MORE_CASES:-AN0,AN1_NL-B,AN2_EL,AN2_NL-A,AN2_NL-B,AN3_NL-B,AN4_EL,AN4_NL-A,AN4_NL-B}
JOBS=$(nproc)
FULL_JOBS=${FULL_JOBS:-1}

for part in $PARTS; do
  if [ -n "$DOCS" ] && [ -f "$DOCS/full/runs/$part.tar.xz" ] && [ ! -e "$D/$part" ]; then
    $PY tools/study_archive.py unpack "$DOCS/full/runs/$part.tar.xz" "$D/$part"
  fi
done
# "0.1.0 (d5fc951, portable Release GNU 12.2.0)" -> d5fc951
commit=$("$RCDEM" --version | sed -n 's/^[^(]*(\([^,]*\),.*/\1/p')
made=$(cat "$D"/*/cases/*/manifest.json 2>/dev/null | sed -n 's/^  "git_hash": "\(.*\)",$/\1/p' | sort -u)
for c in $made; do
  if [ "$c" != "$commit" ] && [ "${MIXED_COMMITS:-0}" != 1 ]; then
    echo "full_study.sh: $D holds runs made by commit $c, and $RCDEM is $commit: build $c" \
         "(git worktree add --detach DIR $c; scripts/setup.sh there) and set RCDEM, or set" \
         "MIXED_COMMITS=1 to mix binaries in one study" >&2
    exit 1
  fi
done

"$RCDEM" study three_point_bending -o "$D/seed1" --seeds 1 -j "$FULL_JOBS"
if [ "$MORE" = all ]; then
  "$RCDEM" study three_point_bending -o "$D/more" --seeds 2,3 -j "$FULL_JOBS"
else
  "$RCDEM" study three_point_bending -o "$D/more" --seeds 2,3 -j "$FULL_JOBS" --cases "$MORE"
fi
"$RCDEM" study three_point_bending --quick -o "$D/quick5" --seeds 1,2,3,4,5 -j "$JOBS"
$PY tools/study_report.py -o "$D/report" "$D/seed1" "$D/more"
if [ -n "$DOCS" ]; then
  $PY tools/publish_study.py "$D/report" "$DOCS/full"
  $PY tools/publish_study.py "$D/quick5" "$DOCS/quick5"
fi
