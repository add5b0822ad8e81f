#!/usr/bin/env bash
# Two builds of the same source give the same bits (issue "Trustworthy numbers"): the reference
# build (CMakePresets.json "release": -O3, portable, -ffp-contract=off) and "release-o2" (-O2 and
# -fno-inline-functions: other inlining, the same IEEE arithmetic) each run the quick AN0 beam;
# their history.csv files must be byte-identical. Takes one extra build (about 5 minutes on 2
# cores); not part of CI for that reason. Usage: bash tests/reproducibility/two_builds.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
cmake --preset release >/dev/null && cmake --build --preset release --target rcdem >/dev/null
cmake --preset release-o2 >/dev/null && cmake --build --preset release-o2 --target rcdem >/dev/null
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for b in build build-o2; do
  echo "$b: $("$b/rcdem" --version)"
  OMP_WAIT_POLICY=passive "$b/rcdem" -q run examples/three_point_bending/study/quick/AN0.toml -o "$out/$b"
done
if cmp "$out/build/history.csv" "$out/build-o2/history.csv"; then
  echo "identical: quick AN0 history.csv ($(wc -l < "$out/build/history.csv") lines) from -O3 and -O2 -fno-inline-functions"
else
  echo "DIFFERENT: quick AN0 history.csv from -O3 and -O2 -fno-inline-functions" >&2
  exit 1
fi
