"""The mutations of fuzz_scenarios.py: each takes a parsed scenario (a dict from tomllib) and a
seeded random.Random, and changes it in place; `mutate` applies one or two and writes the text."""
from __future__ import annotations

import copy
import json
import math
import os
import random
import re
from pathlib import Path

SOURCE = Path(__file__).resolve().parents[2]
BARE = re.compile(r"^[A-Za-z0-9_-]+$")


def toml_key(k: str) -> str:
    return k if BARE.match(k) else json.dumps(k)


def toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, list):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{toml_key(k)} = {toml_value(x)}" for k, x in v.items()) + "}"
    raise TypeError(type(v))


def dumps(doc: dict) -> str:
    lines = [f"{toml_key(k)} = {toml_value(v)}" for k, v in doc.items() if not isinstance(v, dict)]

    def table(prefix: str, d: dict) -> None:
        scalars = {k: v for k, v in d.items() if not isinstance(v, dict)}
        subs = {k: v for k, v in d.items() if isinstance(v, dict)}
        if scalars or not subs:
            lines.append(f"[{prefix}]")
            lines.extend(f"{toml_key(k)} = {toml_value(v)}" for k, v in scalars.items())
        for k, v in subs.items():
            table(f"{prefix}.{toml_key(k)}", v)

    for k, v in doc.items():
        if isinstance(v, dict):
            table(toml_key(k), v)
    return "\n".join(lines) + "\n"


def leaves(d: dict, path=()):
    """(container, key, path) of every value that is not a table."""
    for k, v in d.items():
        if isinstance(v, dict):
            yield from leaves(v, path + (k,))
        else:
            yield d, k, path + (k,)


def tables(d: dict, path=()):
    yield d, path
    for k, v in d.items():
        if isinstance(v, dict):
            yield from tables(v, path + (k,))


def m_type(doc, rng, case):
    items = list(leaves(doc))
    if items:
        d, k, _ = rng.choice(items)
        d[k] = rng.choice(["x", "", True, 7, -3, [1.0, 2.0], [], {"a": 1}, 1e308, "0.05",
                           [[0.1]], ["a", "b", "c"]])


def m_magnitude(doc, rng, case):
    nums = [(d, k) for d, k, _ in leaves(doc) if isinstance(d[k], (int, float))
            and not isinstance(d[k], bool)]
    arrays = [(d[k], i) for d, k, _ in leaves(doc) if isinstance(d[k], list)
              for i in range(len(d[k])) if isinstance(d[k][i], (int, float))]
    pool = nums + arrays
    if not pool:
        return
    d, k = rng.choice(pool)
    x = d[k]
    how = rng.choice(["scale", "scale", "scale", "neg", "zero", "nan", "inf", "-inf", "int"])
    if how == "scale":
        e = rng.choice([-320, -310, -30, -9, -3, -1, 1, 3, 9, 30, 300])
        try:
            d[k] = float(x) * 10.0 ** e if e > -300 else float(x) * 1e-300 * 10.0 ** (e + 300)
        except OverflowError:
            d[k] = math.inf
    elif how == "neg":
        d[k] = -x
    elif how == "zero":
        d[k] = 0 if isinstance(x, int) else 0.0
    elif how == "int":
        d[k] = rng.choice([2**63 - 1, -(2**63), 0, 1, 10**12])
    else:
        d[k] = float(how)


def m_structure(doc, rng, case):
    how = rng.choice(["delete_key", "delete_section", "unknown", "duplicate", "rename"])
    if how == "delete_key":
        items = list(leaves(doc))
        if items:
            d, k, _ = rng.choice(items)
            del d[k]
    elif how == "delete_section" and doc:
        del doc[rng.choice(list(doc))]
    elif how == "unknown":
        d, _ = rng.choice(list(tables(doc)))
        d[rng.choice(["colour", "E", "size", "plates", "seed2", "ß"])] = 1.0
    elif how == "duplicate":
        for sec in ("plates", "bars"):
            if isinstance(doc.get(sec), dict) and doc[sec]:
                name = rng.choice(list(doc[sec]))
                doc[sec][name + "_copy"] = copy.deepcopy(doc[sec][name])
                return
    elif how == "rename" and doc:
        k = rng.choice(list(doc))
        doc[k + rng.choice(["s", "_", ""])] = doc.pop(k)


def m_include(doc, rng, case):
    choice = rng.choice(["missing", "directory", "empty_name", "dev_zero", "fifo", "empty",
                         "garbage", "fragment", "self", "nested", "deep", "dot"])
    path = {"missing": str(case / "nope.toml"), "directory": str(case), "empty_name": "",
            "dev_zero": "/dev/zero", "dot": ".", "self": str(case / "scenario.toml"),
            "fragment": str(SOURCE / "examples/calibrated_contact.toml")}.get(choice)
    if choice == "fifo":
        path = str(case / "fifo.toml")
        os.mkfifo(path)
    elif choice in ("empty", "garbage", "nested", "deep"):
        path = str(case / f"{choice}.toml")
        body = {"empty": b"", "garbage": bytes(rng.randrange(256) for _ in range(200)),
                "nested": b'include = "other.toml"\n',
                "deep": (".".join(["a"] * 20000) + " = 1\n").encode()}[choice]
        Path(path).write_bytes(body)
    doc["include"] = path if rng.random() < 0.7 else [path]


def bar(start, end, d=0.008):
    return {"start": start, "end": end, "diameter": d, "f_y": 5e8}


def m_geometry(doc, rng, case):
    spec = doc.get("specimen") if isinstance(doc.get("specimen"), dict) else {}
    size = spec.get("size") if isinstance(spec.get("size"), list) and len(spec["size"]) == 3 \
        else [0.05, 0.05, 0.05]
    try:
        lx, ly, lz = (float(s) for s in size)
    except (TypeError, ValueError):
        return
    bars = doc.setdefault("bars", {}) if isinstance(doc.get("bars", {}), dict) else {}
    how = rng.choice(["cross", "identical", "notch", "plates_stacked", "plate_away",
                      "missing_control", "bar_outside", "many_plates"])
    if how == "cross":
        bars["f1"] = bar([0.0, ly / 2, lz / 2], [lx, ly / 2, lz / 2])
        bars["f2"] = bar([lx / 2, 0.0, lz / 2], [lx / 2, ly, lz / 2])
    elif how == "identical":
        bars["f1"] = bar([0.0, ly / 2, lz / 2], [lx, ly / 2, lz / 2])
        bars["f2"] = copy.deepcopy(bars["f1"])
    elif how == "notch":
        spec["notch_depth"] = lz / 3
        bars["f1"] = bar([0.0, ly / 2, lz / 6], [lx, ly / 2, lz / 6])
    elif how == "bar_outside":
        bars["f1"] = bar([-lx, ly / 2, lz / 2], [2 * lx, ly / 2, lz / 2])
    elif how == "plates_stacked":
        doc.setdefault("plates", {})["f_stack"] = {"face": "z-"}
        doc["plates"]["f_stack2"] = {"face": "z-"}
    elif how == "many_plates":
        doc["plates"] = {f"p{i}": {"face": "z-", "extent": [i * lx / 100, (i + 1) * lx / 100,
                                                             0.0, ly]} for i in range(100)}
    elif how == "plate_away" and isinstance(doc.get("plates"), dict):
        for p in doc["plates"].values():
            if isinstance(p, dict) and isinstance(p.get("velocity"), (int, float)):
                p["velocity"] = -p["velocity"]
    elif how == "missing_control":
        doc.setdefault("loading", {})["control_plate"] = "nowhere"


def m_text(text: bytes, rng) -> bytes:
    how = rng.choice(["truncate", "byte", "deep", "nul", "dup_line"])
    if how == "truncate" and text:
        return text[: rng.randrange(len(text))]
    if how == "byte" and text:
        i = rng.randrange(len(text))
        return text[:i] + bytes([rng.randrange(256)]) + text[i + 1:]
    if how == "deep":
        return text + ("[" + ".".join(["q"] * 30000) + "]\n").encode()
    if how == "nul" and text:
        i = rng.randrange(len(text))
        return text[:i] + b"\x00" + text[i:]
    lines = text.split(b"\n")
    i = rng.randrange(len(lines))
    return b"\n".join(lines[: i + 1] + [lines[i]] + lines[i + 1:])


STRUCTURED = {"type": m_type, "magnitude": m_magnitude, "structure": m_structure,
              "include": m_include, "geometry": m_geometry}


def mutate(base: dict, rng: random.Random, case: Path) -> tuple[bytes, list[str], list[str]]:
    """The mutated scenario's bytes, the mutations applied, and files an error may name."""
    doc = copy.deepcopy(base)
    kinds = []
    for _ in range(1 if rng.random() < 0.7 else 2):
        kind = rng.choice(list(STRUCTURED) + ["magnitude", "text"])
        kinds.append(kind)
        if kind != "text":
            STRUCTURED[kind](doc, rng, case)
    text = dumps(doc).encode()
    if "text" in kinds:
        text = m_text(text, rng)
    names = []
    inc = doc.get("include")
    for p in inc if isinstance(inc, list) else [inc]:
        if isinstance(p, str):
            names += [p, Path(p).name]
    return text, kinds, [n for n in names if n]
