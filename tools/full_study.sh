#!/bin/bash
# The three-point bending study of docs/case-study.md (issue 27), by one command:
#   full size: every case on packing 1; AN2 and AN4 with all interfaces, AN0 and AN1 NL-B (the
#              brittle side of the transition) on packings 2 and 3 as well; one report over both
#              study directories (tools/study_report.py -o);
#   quick:     every case on packings 1-5;
# then what docs keeps of each (tools/publish_study.py). Resumable: run it again after an
# interruption; finished runs are kept.
#
# usage: tools/full_study.sh [STUDY_DIR [DOCS_DIR]]
#   STUDY_DIR  default results/study_full (seed1/, more/, report/ and quick5/ under it)
#   DOCS_DIR   where DOCS_DIR/full and DOCS_DIR/quick5 get the tables and figures; default none
#   RCDEM      the binary (default build/rcdem); MORE_CASES the cases run on packings 2 and 3
#              (default as above; "all" for all 13)
set -euo pipefail
cd "$(dirname "$0")/.."
RCDEM=${RCDEM:-build/rcdem}
D=${1:-results/study_full}
DOCS=${2:-}
MORE=${MORE_CASES:-AN0,AN1_NL-B,AN2_EL,AN2_NL-A,AN2_NL-B,AN4_EL,AN4_NL-A,AN4_NL-B}
JOBS=$(nproc)
"$RCDEM" study three_point_bending -o "$D/seed1" --seeds 1 -j "$JOBS"
if [ "$MORE" = all ]; then
  "$RCDEM" study three_point_bending -o "$D/more" --seeds 2,3 -j "$JOBS"
else
  "$RCDEM" study three_point_bending -o "$D/more" --seeds 2,3 -j "$JOBS" --cases "$MORE"
fi
"$RCDEM" study three_point_bending --quick -o "$D/quick5" --seeds 1,2,3,4,5 -j "$JOBS"
/usr/bin/python3 tools/study_report.py -o "$D/report" "$D/seed1" "$D/more"
if [ -n "$DOCS" ]; then
  /usr/bin/python3 tools/publish_study.py "$D/report" "$DOCS/full"
  /usr/bin/python3 tools/publish_study.py "$D/quick5" "$DOCS/quick5"
fi
