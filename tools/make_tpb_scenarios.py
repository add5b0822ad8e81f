#!/usr/bin/python3
"""Writes the three-point bending scenarios of the paper's study (SPEC 10, Table 3):
examples/three_point_bending/study/AN{0..4}[_{EL,NL-A,NL-B}].toml, 13 cases, from one template,
so that they differ only in the bars; all with the calibrated contact parameters
(examples/calibrated_contact.toml). (examples/three_point_bending/AN0.toml, with Table 2's
parameters, is the generation example.) Run from the repository root: tools/make_tpb_scenarios.py
"""
import os

L, B, H = 0.700, 0.150, 0.100          # beam length, width, depth [m] (SPEC 10)
SPAN, PLATE = 0.600, 0.020             # support span and plate width [m]
COVER_END, AXIS_Z = 0.010, H / 10      # bar end cover; bar axis height = h/10 [m]

MODELS = {  # name: (bars, diameter [m], f_y [Pa], P_exp [N]) from Table 3
    "AN0": (0, 0.0, 0.0, 11.8e3),
    "AN1": (1, 0.004, 637e6, 11.9e3),
    "AN2": (2, 0.005, 569e6, 15.2e3),
    "AN3": (2, 0.008, 441e6, 27.9e3),
    "AN4": (2, 0.010, 456e6, 48.7e3),
}


def plate(name, face, x_centre, velocity=None):
    lines = [f"[plates.{name}]", f'face = "{face}"',
             f"extent = [{x_centre - PLATE / 2:.3f}, {x_centre + PLATE / 2:.3f}, 0.0, {B}]   # x, y [m]"]
    if velocity is not None:
        lines += [f"velocity = {velocity}          # m/s, downwards", "ramp_time = 1.0e-3       # s"]
    return "\n".join(lines) + "\n"


def scenario(model, interface):
    n, d, fy, p_exp = MODELS[model]
    head = (f"# {model}{'' if n == 0 else ' ' + interface}: three-point bending of the paper's beam "
            f"(SPEC 10, Table 3: P_exp = {p_exp / 1e3:.1f} kN).\n"
            f"# Written by tools/make_tpb_scenarios.py; SI units.\n"
            f'include = ["../../calibrated_contact.toml"]\n\n'
            f"[specimen]\nshape = \"beam\"\nsize = [{L}, {B}, {H}]   # length x, width y, depth z [m]\n\n"
            f"[generation]\nseed = 1\n\n")
    bars = ""
    ys = [B / 2] if n == 1 else [B / 4, 3 * B / 4] if n == 2 else []
    for k, y in enumerate(ys):
        bars += (f"[bars.bar{k + 1}]\nstart = [{COVER_END}, {y:.4f}, {AXIS_Z}]\nend = [{L - COVER_END:.3f}, {y:.4f}, {AXIS_Z}]\n"
                 f"diameter = {d}\nf_y = {fy:.4g}\ninterface = \"{interface}\"\n\n")
    x0 = (L - SPAN) / 2
    plates = (plate("support_left", "z-", x0) + "\n" + plate("support_right", "z-", L - x0) + "\n"
              + plate("load", "z+", L / 2, velocity=-0.05))
    tail = ("\n[loading]\ncontrol_plate = \"load\"\n\n[stop]\ndisplacement = 0.002   # m of midspan deflection\n"
            "load_drop = 0.2        # or the load below 20% of its peak after it\n\n[output]\nsnapshots = 10\n")
    return head + bars + plates + tail


out = os.path.join("examples", "three_point_bending", "study")
os.makedirs(out, exist_ok=True)
for model in MODELS:
    for interface in (["EL"] if model == "AN0" else ["EL", "NL-A", "NL-B"]):
        name = model if model == "AN0" else f"{model}_{interface}"
        with open(os.path.join(out, f"{name}.toml"), "w") as f:
            f.write(scenario(model, interface))
        print(os.path.join(out, f"{name}.toml"))
