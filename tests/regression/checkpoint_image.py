"""A checkpoint's binary image (docs/checkpoint.md's byte layout) rebuilt from its HDF5 file by
h5py alone, as the page describes: the regression scripts read checkpoints with it,
independently of rcdem."""
import os
import re
import struct

import h5py
import numpy as np


def written_order(g):
    """The names in group `g` in the order they were written (h5py lists the root's by name)."""
    names = []
    g.id.links.iterate(lambda n: names.append(n.decode()), idx_type=h5py.h5.INDEX_CRT_ORDER)
    return names


def _payload(g):
    count = int(g.attrs["count"])
    if g.attrs["kind"] != "words":
        data = g["text"][()] if g.attrs["kind"] == "text" else g["bytes"][()].tobytes()
        return 2, 1, count, data
    width = int(g.attrs["width"])
    words = np.zeros((count, width), dtype="<u8")
    at = 0
    for col in written_order(g):
        ds = g[col]
        n = 1 if ds.ndim == 1 else ds.shape[1]
        if count:
            v = np.asarray(ds[()], dtype="<f8" if ds.dtype.kind == "f" else "<i8")
            words[:, at:at + n] = v.reshape(count, n).view("<u8")
        at += n
    return 1, width, count, words.tobytes()


def binary_image(path):
    """The image of the HDF5 checkpoint `path`, its last four bytes the file's stored CRC-32
    (attribute 'crc32'), so that checking the image checks the file."""
    with h5py.File(path, "r") as f:
        a = f.attrs
        body = b""
        names = written_order(f)
        for name in names:
            kind, width, count, payload = _payload(f[name])
            body += (struct.pack("<I", len(name)) + name.encode() +
                     struct.pack("<IIQ", kind, width, count) + payload)
        writer = a["writer"].encode()
        size = 64 + len(writer) + len(body) + 4
        head = b"RCDEMCKP" + struct.pack("<IIQqdQQII", int(a["version"]), 0x01020304, size,
                                         int(a["step"]), float(a["time"]), int(a["scenario_hash"]),
                                         int(a["specimen_fingerprint"]), len(names), len(writer))
        return head + writer + body + struct.pack("<I", int(a["crc32"]))


# Where docs/checkpoint.md states the format version it describes.
_VERSION_STATED = [r"sections' layout is version (\d+)", r"binary image \(format version (\d+)\)",
                   r"`u32` format version = (\d+)", r"older than this rcdem reads \(\d+ to (\d+)\)"]


def documented_version(source):
    """The checkpoint format version docs/checkpoint.md describes, or None where its statements
    of it are missing or disagree (the page then needs mending with the format)."""
    text = open(os.path.join(source, "docs", "checkpoint.md")).read()
    found = {int(m.group(1)) for pattern in _VERSION_STATED for m in re.finditer(pattern, text)}
    stated = all(re.search(pattern, text) for pattern in _VERSION_STATED)
    return found.pop() if stated and len(found) == 1 else None
