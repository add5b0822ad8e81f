#!/usr/bin/python3
"""The source folders' layers (docs/architecture.md, "Layers"): every #include "rcdem/..." in
src/rcdem goes to a folder on the same layer or below, never above. Folders on one layer may
include each other (the model's folders share types both ways).

usage: check_layers.py SOURCE_DIR
"""
import os
import re
import sys

# Bottom to top.
LAYERS = [
    ("core", "mpi"),
    ("config",),
    ("specimens", "packing", "tessellation", "state", "contact", "reinforcement"),
    ("io",),
    ("solver",),
    ("run",),
    ("calibration", "study"),
]
LEVEL = {folder: level for level, folders in enumerate(LAYERS) for folder in folders}
INCLUDE = re.compile(r'^\s*#\s*include\s+"rcdem/([a-z_]+)/')


def main(root):
    src = os.path.join(root, "src", "rcdem")
    problems, arrows = [], 0
    for folder in sorted(os.listdir(src)):
        if not os.path.isdir(os.path.join(src, folder)):
            continue
        if folder not in LEVEL:
            problems.append(f"src/rcdem/{folder}: a folder with no layer (add it to LAYERS and to "
                            "docs/architecture.md)")
            continue
        for dirpath, _, names in os.walk(os.path.join(src, folder)):
            for name in sorted(names):
                if not name.endswith((".hpp", ".cpp")):
                    continue
                path = os.path.join(dirpath, name)
                for number, line in enumerate(open(path, encoding="utf-8"), 1):
                    m = INCLUDE.match(line)
                    if not m:
                        continue
                    arrows += 1
                    target = m.group(1)
                    if target not in LEVEL:
                        problems.append(f"{os.path.relpath(path, root)}:{number}: includes "
                                        f"unknown folder {target}")
                    elif LEVEL[target] > LEVEL[folder]:
                        problems.append(f"{os.path.relpath(path, root)}:{number}: {folder} "
                                        f"(layer {LEVEL[folder]}) includes {target} (layer "
                                        f"{LEVEL[target]}), above it")
    print("\n".join(problems) if problems else
          f"ok: {arrows} includes, none upward across {len(LAYERS)} layers")
    return 1 if problems else 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1]))
