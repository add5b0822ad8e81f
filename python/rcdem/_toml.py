"""Python values as TOML text, for Scenario.set and Scenario.from_dict (Python's tomllib reads
TOML but does not write it, and Debian has no TOML writer that every machine carries)."""
import math
import re

_BARE_KEY = re.compile(r"^[A-Za-z0-9_-]+$")


def _key(k):
    return k if _BARE_KEY.match(k) else '"' + k.replace("\\", "\\\\").replace('"', '\\"') + '"'


def toml_value(v):
    """One value: bool, int, float (finite), str, or a list of them."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if not math.isfinite(v):
            raise ValueError(f"{v!r}: a scenario value must be finite")
        return repr(v)
    if isinstance(v, str):
        return '"' + v.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n") + '"'
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    if hasattr(v, "tolist"):  # numpy scalars and arrays
        return toml_value(v.tolist())
    raise TypeError(f"{v!r} ({type(v).__name__}): expected a number, string, bool or list")


def toml_document(d, prefix=""):
    """Nested dicts as a TOML document: each dict a [table], its plain values first."""
    lines, tables = [], []
    for k, v in d.items():
        if isinstance(v, dict):
            tables.append((k, v))
        else:
            lines.append(f"{_key(k)} = {toml_value(v)}")
    out = ""
    if lines:
        out += (f"[{prefix}]\n" if prefix else "") + "\n".join(lines) + "\n"
    for k, v in tables:
        out += toml_document(v, f"{prefix}.{_key(k)}" if prefix else _key(k))
    return out
