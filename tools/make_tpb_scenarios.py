#!/usr/bin/python3
"""Writes the three-point bending scenarios of the paper's study (SPEC 10, Table 3):
examples/three_point_bending/study/AN{0..4}[_{EL,NL-A,NL-B}].toml, 13 cases, from one template,
so that they differ only in the bars; all with the calibrated contact parameters
(examples/calibrated_contact.toml). The same 13 for `rcdem study --quick` in study/quick/:
particles twice as coarse with their own contact set, selective mass scaling, a shorter run
(docs/case-study.md says why each). (examples/three_point_bending/AN0.toml, with Table 2's
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


# Full study: the paper's particles; quick: twice the diameters (8x fewer particles, a 2x longer
# step). Loading speeds: the rate study of docs/case-study.md. Full size also stops 1 mm past the
# peak (issue 5's "peak plus a defined post-peak"): it cuts only a plateau after the peak (AN1
# then stops at 1.17 mm, AN2 at 1.6 mm), never a load that is still rising (AN3, AN4 run to 2 mm).
# Full size at the rates of SPEC 6's half-rate check (docs/case-study.md, "Full size: the study's
# rates against the other"): 0.025 m/s (AN2 NL-B: 0.025 vs 0.0125 m/s moved the plate's peak 1.5%,
# the supports' 0.4%); AN4 at 0.0125 m/s (0.025 m/s moved both peaks 7%).
FULL = dict(velocity=-0.025, by_model={"AN4": -0.0125}, ramp=4.0e-3, stop=0.002, post_peak=0.001, snapshots=10, coarsen=None, sub="",
            contact="calibrated_contact.toml")
# Quick (2026-11-27, docs/case-study.md "The quick study's rate"): 0.0125 m/s, where halving the
# rate moved AN0's peak by 0.6%, AN4 NL-B's by 0.1%, and the plate's peak is within 1% of the
# supports'; 1% of selective mass scaling, since the bars' cylinders (Φ4: 6.5e-7 s) would set
# the step (AN1 NL-B: the same peak to 0.01%, half the steps).
QUICK = dict(velocity=-0.0125, ramp=4.0e-3, stop=0.0012, post_peak=None, snapshots=4, coarsen=2.0, sub="quick",
             contact="calibrated_contact_quick.toml", added_mass=0.01)
D_AGG, D_MORTAR = (0.008, 0.012), (0.008, 0.009)  # diameters of the schema's defaults (SPEC 2)


def plate(name, face, x_centre, velocity=None, ramp=None, width=PLATE, digits=3):
    """A plate's section: across the beam's width, `width` long along x (also
    tools/make_size_series.py's)."""
    lines = [f"[plates.{name}]", f'face = "{face}"',
             f"extent = [{x_centre - width / 2:.{digits}f}, {x_centre + width / 2:.{digits}f}, 0.0, {B}]   # x, y [m]"]
    if velocity is not None:
        lines += [f"velocity = {velocity}          # m/s, downwards", f"ramp_time = {ramp:g}       # s"]
    return "\n".join(lines) + "\n"


def coarse_particles(k):
    """The generation's diameters k times the paper's ("" for None; also make_size_series.py's)."""
    if not k:
        return ""
    return (f"# Quick: particles {k:g}x coarser than the paper's.\n"
            f"[generation.aggregate]\nd_min = {k * D_AGG[0]:g}\nd_max = {k * D_AGG[1]:g}\n\n"
            f"[generation.mortar]\nd_min = {k * D_MORTAR[0]:g}\nd_max = {k * D_MORTAR[1]:g}\n\n")


def loading_tail(mode, has_bars, stop, post_peak, post_peak_note="or 1 mm past the peak's deflection"):
    """[loading], [solver], [stop] and [output] of a bending scenario (also make_size_series.py's)."""
    return ("\n[loading]\ncontrol_plate = \"load\"\n\n"
            "[solver]\ntime_step_estimate = \"assembled\"   # 2 / omega_max of the whole beam (docs/model.md 6)\n"
            "dt_safety = 0.7        # of the damped critical step: an unchanged answer (docs/case-study.md)\n"
            "damping = 0.3          # 0.7 lifts the cracking load with the rate (docs/case-study.md)\n"
            "particle_rotational_inertia_scaling = 2.5   # their rotation no longer sets the step\n"
            + (f"added_mass_limit = {mode['added_mass']:g}   # selective mass scaling: the bars' cylinders no longer set the step\n"
               if mode.get("added_mass") else "")
            + ("bar_rotational_inertia_scaling = 30   # the bars' rotation no longer sets the step\n" if has_bars else "")
            + "\n"
            f"[stop]\ndisplacement = {stop:g}   # m of midspan deflection\n"
            "load_drop = 0.2        # or the load below 20% of its peak after it\n"
            + (f"post_peak_displacement = {post_peak:g}   # {post_peak_note}\n" if post_peak else "")
            + "\n"
            f"[output]\nsnapshots = {mode['snapshots']}\n")


def scenario(model, interface, mode):
    n, d, fy, p_exp = MODELS[model]
    up = "../" if mode["sub"] else ""
    head = (f"# {model}{'' if n == 0 else ' ' + interface}: three-point bending of the paper's beam "
            f"(SPEC 10, Table 3: P_exp = {p_exp / 1e3:.1f} kN){' - quick variant' if mode['sub'] else ''}.\n"
            f"# Written by tools/make_tpb_scenarios.py; SI units.\n"
            f'include = ["{up}../../{mode["contact"]}"]\n\n'
            f"[specimen]\nshape = \"beam\"\nsize = [{L}, {B}, {H}]   # length x, width y, depth z [m]\n\n"
            f"[generation]\nseed = 1\n\n")
    head += coarse_particles(mode["coarsen"])
    bars = ""
    ys = [B / 2] if n == 1 else [B / 4, 3 * B / 4] if n == 2 else []
    for k, y in enumerate(ys):
        bars += (f"[bars.bar{k + 1}]\nstart = [{COVER_END}, {y:.4f}, {AXIS_Z}]\nend = [{L - COVER_END:.3f}, {y:.4f}, {AXIS_Z}]\n"
                 f"diameter = {d}\nf_y = {fy:.4g}\ninterface = \"{interface}\"\n\n")
    x0 = (L - SPAN) / 2
    plates = (plate("support_left", "z-", x0) + "\n" + plate("support_right", "z-", L - x0) + "\n"
              + plate("load", "z+", L / 2, velocity=mode.get("by_model", {}).get(model, mode["velocity"]),
                      ramp=mode["ramp"]))
    tail = loading_tail(mode, n > 0, mode["stop"], mode["post_peak"])
    return head + bars + plates + tail


def main():
    for mode in (FULL, QUICK):
        out = os.path.join("examples", "three_point_bending", "study", mode["sub"])
        os.makedirs(out, exist_ok=True)
        for model in MODELS:
            for interface in (["EL"] if model == "AN0" else ["EL", "NL-A", "NL-B"]):
                name = model if model == "AN0" else f"{model}_{interface}"
                with open(os.path.join(out, f"{name}.toml"), "w") as f:
                    f.write(scenario(model, interface, mode))
                print(os.path.join(out, f"{name}.toml"))


if __name__ == "__main__":
    main()
