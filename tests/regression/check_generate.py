#!/usr/bin/python3
"""End-to-end check of `rcdem generate` (issue 2 acceptance):
same seed -> byte-identical VTU and summary.json (apart from the wall-clock `seconds` line),
another seed -> a different packing with counts within 1%, VTU files read back with meshio,
and an existing non-empty output directory is refused without --force.

usage: check_generate.py RCDEM_BINARY SOURCE_DIR
"""
import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checklist import Checklist  # noqa: E402

rcdem, source = sys.argv[1], sys.argv[2]
checks = Checklist()
check = checks.check
scenario = os.path.join(source, "tests", "regression", "small_cube.toml")
check_vtu = os.path.join(source, "tools", "check_vtu.py")



def generate(scen, out, *extra):
    return subprocess.run([rcdem, "--quiet", "generate", scen, "-o", out, *extra],
                          capture_output=True, text=True, timeout=300)


def without_seconds(path):
    with open(path, "rb") as f:
        return b"".join(line for line in f if not line.lstrip().startswith(b'"seconds"'))


with tempfile.TemporaryDirectory() as tmp:
    a, b, c = (os.path.join(tmp, n) for n in "abc")
    other_seed = os.path.join(tmp, "seed2.toml")
    with open(scenario) as f:
        text = f.read()
    with open(other_seed, "w") as f:
        f.write(text.replace("seed = 1", "seed = 2"))

    for out, scen in ((a, scenario), (b, scenario), (c, other_seed)):
        r = generate(scen, out)
        check(r.returncode == 0, f"generate {os.path.basename(scen)} -> {os.path.basename(out)} "
                                 f"exits 0 ({r.stderr.strip()})")

    for name in ("particles.vtu", "facets.vtu"):
        with open(os.path.join(a, name), "rb") as f1, open(os.path.join(b, name), "rb") as f2:
            check(f1.read() == f2.read(), f"same seed: {name} byte-identical")
        with open(os.path.join(a, name), "rb") as f1, open(os.path.join(c, name), "rb") as f3:
            check(f1.read() != f3.read(), f"other seed: {name} differs")
    check(without_seconds(os.path.join(a, "summary.json")) ==
          without_seconds(os.path.join(b, "summary.json")),
          "same seed: summary.json byte-identical apart from the wall-clock 'seconds' line")

    sa = json.load(open(os.path.join(a, "summary.json")))
    sc = json.load(open(os.path.join(c, "summary.json")))
    for key in ("aggregate", "mortar", "total"):
        x, y = sa["particles"][key], sc["particles"][key]
        check(abs(x - y) <= 0.01 * x, f"other seed: particles.{key} {x} vs {y} within 1%")
    for key in ("contacts", "local_points"):
        x, y = sa[key], sc[key]
        check(abs(x - y) <= 0.01 * x, f"other seed: {key} {x} vs {y} within 1%")
    check(abs(sa["porosity"] - 0.10) <= 0.005, f"porosity {sa['porosity']:.4f} = 0.100 +- 0.005")
    check(abs(sa["cell_volume_sum"] / sa["specimen_volume"] - 1) < 1e-9,
          "cell volumes sum to the specimen volume")
    for key in ("particles", "contacts", "local_points", "porosity", "specimen_volume",
                "cell_volume_sum", "seconds"):
        check(key in sa, f"summary.json has '{key}'")
    check(all(k in sa["particles"] for k in ("aggregate", "mortar", "steel")),
          "summary.json has particles.aggregate/mortar/steel")

    # Read back with a real reader (meshio): counts and field names.
    n = sa["particles"]["total"]
    r = subprocess.run(["/usr/bin/python3", check_vtu, os.path.join(a, "particles.vtu"),
                        "--points", str(n), "--cells", str(n),
                        "--point-fields", "radius,kind,cell_volume,id"], capture_output=True, text=True)
    check(r.returncode == 0, f"meshio reads particles.vtu: {r.stdout.strip()} {r.stderr.strip()}")
    points_on_facets = sa["local_points"] - sa["contacts"]  # local points less the centroids
    r = subprocess.run(["/usr/bin/python3", check_vtu, os.path.join(a, "facets.vtu"),
                        "--points", str(points_on_facets), "--cells", str(sa["contacts"]),
                        "--cell-fields", "area,local_points,particle_a,particle_b,contact"],
                       capture_output=True, text=True)
    check(r.returncode == 0, f"meshio reads facets.vtu: {r.stdout.strip()} {r.stderr.strip()}")
    # One cell block per vertex count (the facets written by count), and `contact` gives every
    # contact's index once.
    r = subprocess.run(["/usr/bin/python3", "-c", (
        "import meshio, sys, numpy\n"
        "m = meshio.read(sys.argv[1])\n"
        "sizes = [b.data.shape[1] for b in m.cells]\n"
        "contact = numpy.concatenate(m.cell_data['contact'])\n"
        "print(len(sizes), int(sizes == sorted(set(sizes))),"
        " int(sorted(contact.tolist()) == list(range(len(contact)))))"),
        os.path.join(a, "facets.vtu")], capture_output=True, text=True)
    blocks, one_per_count, permutation = (r.stdout.split() + ["0", "0", "0"])[:3]
    check(r.returncode == 0 and one_per_count == "1" and permutation == "1",
          f"facets.vtu: one meshio block per vertex count ({blocks} blocks), `contact` a "
          f"permutation of the contacts ({r.stderr.strip()[-200:]})")

    # Never overwrite results without being asked.
    before = open(os.path.join(a, "particles.vtu"), "rb").read()
    r = generate(other_seed, a)
    check(r.returncode == 1 and "--force" in r.stderr, f"non-empty output refused: {r.stderr.strip()}")
    check(open(os.path.join(a, "particles.vtu"), "rb").read() == before, "earlier results untouched")
    r = generate(other_seed, a, "--force")
    check(r.returncode == 0, "--force overwrites")
    check(not [f for f in os.listdir(a) if ".tmp." in f], "no temporary files left behind")

checks.finish()
