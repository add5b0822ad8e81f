#!/bin/bash
cd /work/main
for r in 1 2; do
  for v in hold visit; do
    [ $r = 2 ] && v=$([ $v = hold ] && echo visit || echo hold)
    out=results/s41/run_$v$r; rm -rf $out
    build/rcdem run results/s41/tension_$v.toml --threads 1 -q -o $out > /dev/null 2>&1
    python3 -c "import json; s=json.load(open('$out/summary.json')); print('$v', $r, s.get('steps'), s.get('loop_seconds'), s.get('peak_load_N', s.get('peak_load')))"
  done
done
