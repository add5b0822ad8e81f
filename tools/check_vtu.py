#!/usr/bin/python3
"""Check a .vtu file written by rcdem with an independent reader (meshio).

  check_vtu.py FILE [--points N] [--cells N] [--point-fields a,b] [--cell-fields x,y]
               [--same-as OTHER] [--dump]

Prints one OK line, or the first failure on stderr and exits 1. --same-as asserts that OTHER
(e.g. the binary twin of an ascii file) decodes to exactly the same points, cells and fields.
"""
import argparse
import sys

import meshio
import numpy as np


def fields(text):
    return [name for name in text.split(",") if name] if text else []


def num_cells(mesh):
    # meshio splits cells into blocks by type (and polygons by size); count over all of them.
    return sum(len(block.data) for block in mesh.cells)


def dump(path, mesh):
    print(f"{path}: {len(mesh.points)} points, {num_cells(mesh)} cells")
    for block in mesh.cells:
        print(f"  cell block {block.type}: {len(block.data)}")
    for name, values in mesh.point_data.items():
        print(f"  point field {name}: {values.dtype} {values.shape}")
    for name, blocks in mesh.cell_data.items():
        print(f"  cell field {name}: {blocks[0].dtype if blocks else '?'} "
              f"{sum(len(b) for b in blocks)} values")


def differences(mesh, other):
    # Exact comparison: ascii is written with 17 significant digits, which round-trips doubles.
    if not np.array_equal(mesh.points, other.points):
        yield "points differ"
    if [(b.type, b.data.tolist()) for b in mesh.cells] != \
            [(b.type, b.data.tolist()) for b in other.cells]:
        yield "cells differ"
    for kind, mine, theirs in (("point", mesh.point_data, other.point_data),
                               ("cell", mesh.cell_data, other.cell_data)):
        if sorted(mine) != sorted(theirs):
            yield f"{kind} fields differ: {sorted(mine)} vs {sorted(theirs)}"
            continue
        for name in mine:
            a = mine[name] if kind == "point" else np.concatenate(mine[name])
            b = theirs[name] if kind == "point" else np.concatenate(theirs[name])
            if a.dtype != b.dtype or not np.array_equal(a, b):
                yield f"{kind} field '{name}' differs"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("file")
    parser.add_argument("--points", type=int, help="expected number of points")
    parser.add_argument("--cells", type=int, help="expected number of cells (all types)")
    parser.add_argument("--point-fields", type=fields, default=[], help="comma-separated names")
    parser.add_argument("--cell-fields", type=fields, default=[], help="comma-separated names")
    parser.add_argument("--same-as", metavar="OTHER", help="a file that must hold the same data")
    parser.add_argument("--dump", action="store_true", help="print counts and field names")
    args = parser.parse_args()

    def read(path):
        # meshio.vtu.read, not meshio.read: the latter prints and calls sys.exit on a bad file.
        try:
            return meshio.vtu.read(path)
        except Exception as e:  # meshio raises many types; all mean "unreadable"
            hint = ""
            try:
                with open(path, "rb") as f:
                    if b'NumberOfCells="0"' in f.read(4096):
                        hint = " (meshio 5 cannot read any grid with zero cells)"
            except OSError:
                pass
            sys.exit(f"check_vtu: {path}: meshio cannot read it{hint}: {type(e).__name__}: {e}")

    mesh = read(args.file)
    if args.dump:
        dump(args.file, mesh)

    failures = []
    if args.points is not None and len(mesh.points) != args.points:
        failures.append(f"{len(mesh.points)} points, expected {args.points}")
    if args.cells is not None and num_cells(mesh) != args.cells:
        failures.append(f"{num_cells(mesh)} cells, expected {args.cells}")
    failures += [f"no point field '{n}' (has {sorted(mesh.point_data)})"
                 for n in args.point_fields if n not in mesh.point_data]
    failures += [f"no cell field '{n}' (has {sorted(mesh.cell_data)})"
                 for n in args.cell_fields if n not in mesh.cell_data]
    if args.same_as:
        failures += [f"{d} from {args.same_as}" for d in differences(mesh, read(args.same_as))]
    if failures:
        sys.exit(f"check_vtu: {args.file}: " + "; ".join(failures))

    print(f"check_vtu: OK {args.file}: {len(mesh.points)} points, {num_cells(mesh)} cells, "
          f"point fields [{','.join(mesh.point_data)}], cell fields [{','.join(mesh.cell_data)}]"
          + (f", same as {args.same_as}" if args.same_as else ""))


if __name__ == "__main__":
    main()
