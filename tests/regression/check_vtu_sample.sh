#!/bin/bash
# check_vtu_sample.sh VTU_SAMPLE: runs the vtu_sample program (its path, or the directory holding
# it) and reads both files back with meshio, so a writer bug that ParaView would choke on fails
# here. The binary file must decode to exactly the data of the ascii one.
set -euo pipefail

if [[ $# -ne 1 ]]; then
  echo "usage: $0 VTU_SAMPLE_EXECUTABLE_OR_DIR" >&2
  exit 2
fi
sample=$1
[[ -d $sample ]] && sample=$sample/vtu_sample
check=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)/tools/check_vtu.py

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$sample" "$out"

for file in sample_ascii.vtu sample_binary.vtu; do
  /usr/bin/python3 "$check" "$out/$file" --points 4 --cells 7 \
    --point-fields radius,kind,displacement,id --cell-fields area,family \
    --same-as "$out/sample_ascii.vtu"
done
grep -q 'file="sample_binary.vtu"' "$out/sample.pvd"
echo "check_vtu_sample: OK"
