#!/usr/bin/python3
"""Initial stiffness of the unreinforced three-point bending beam (AN0) as a 3D linear-elastic
continuum with its three rigid plates: the measure docs/case-study.md compares rcdem's K0 with,
in place of a bracket from beam theory (which leaves out the beam's width, the plates' 20 mm and
where the supports touch).

The model: a quarter of the beam (symmetry planes at midspan and mid-width), triquadratic
27-node hexahedra on a tensor-product mesh graded towards the plates' edges, the plates rigid and
flat. Plates are frictionless and unilateral by default, as rcdem's beam plates are
(docs/model.md, "Plates"): a node under a plate is held at the plate's plane while it presses on
it and released where it would pull (an active set, re-solved until no node pulls and no released
node passes through the plate). `--plates glued` holds every node under a plate in all three
directions (an upper bound). Loading is displacement control; K = P / delta.

Defaults: the study's beam and the concrete's elastic pair (tools/study_report.py).

usage: continuum_beam_k0.py [--E PA] [--nu NU] [--plates frictionless|glued]
                            [--levels 1,2,3] [--span M] [--length M] [--width M] [--depth M]
                            [--plate-width M]
Prints K per mesh level and the extrapolated value (Richardson on the two finest levels, with the
observed convergence order). SI units in, kN/mm out.
"""
import argparse
import itertools
import sys
import time

import os

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import study_report as sr  # noqa: E402  (the beam's sizes and the concrete's elastic pair)

GAUSS = (np.array([-np.sqrt(0.6), 0.0, np.sqrt(0.6)]), np.array([5.0, 8.0, 5.0]) / 9.0)


def lagrange2(xi):
    """1D quadratic Lagrange shape functions at nodes -1, 0, 1 and their derivatives."""
    n = np.array([xi * (xi - 1) / 2, 1 - xi * xi, xi * (xi + 1) / 2])
    dn = np.array([xi - 0.5, -2 * xi, xi + 0.5])
    return n, dn


def reference_gradients():
    """d N_a / d xi_k at the 27 Gauss points, shape (27 points, 27 nodes, 3) and the weights.
    Node a = (i, j, k) in {0, 1, 2}^3 flattened as i + 3 j + 9 k, like the global grid."""
    pts, wts = GAUSS
    grads, weights = [], []
    for (p, wp), (q, wq), (r, wr) in itertools.product(zip(pts, wts), repeat=3):
        nx, dx = lagrange2(p)
        ny, dy = lagrange2(q)
        nz, dz = lagrange2(r)
        g = np.empty((27, 3))
        for k, j, i in itertools.product(range(3), repeat=3):
            a = i + 3 * j + 9 * k
            g[a] = (dx[i] * ny[j] * nz[k], nx[i] * dy[j] * nz[k], nx[i] * ny[j] * dz[k])
        grads.append(g)
        weights.append(wp * wq * wr)
    return np.array(grads), np.array(weights)


def elasticity(E, nu):
    lam = E * nu / ((1 + nu) * (1 - 2 * nu))
    mu = E / (2 * (1 + nu))
    d = np.zeros((6, 6))
    d[:3, :3] = lam
    d[np.arange(3), np.arange(3)] += 2 * mu
    d[np.arange(3, 6), np.arange(3, 6)] = mu
    return d


def box_stiffness(size, d, grads, weights):
    """81 x 81 stiffness of a box element of edge lengths `size` (Voigt: xx yy zz yz xz xy)."""
    scale = 2.0 / np.asarray(size)
    detj = np.prod(size) / 8.0
    ke = np.zeros((81, 81))
    for g, w in zip(grads, weights):
        dn = g * scale
        b = np.zeros((6, 81))
        b[0, 0::3], b[1, 1::3], b[2, 2::3] = dn[:, 0], dn[:, 1], dn[:, 2]
        b[3, 1::3], b[3, 2::3] = dn[:, 2], dn[:, 1]
        b[4, 0::3], b[4, 2::3] = dn[:, 2], dn[:, 0]
        b[5, 0::3], b[5, 1::3] = dn[:, 1], dn[:, 0]
        ke += b.T @ d @ b * (w * detj)
    return ke


def graded(a, b, n, toward):
    """n element edges from a to b, squeezed quadratically towards the ends in `toward`: one
    fixed map of a uniform parameter, so a finer level is a uniform refinement of that parameter
    (the convergence order below is then an order in h)."""
    s = np.linspace(0.0, 1.0, n + 1)
    if len(toward) == 2:
        g = np.where(s < 0.5, 2 * s * s, 1 - 2 * (1 - s) ** 2)
    elif toward and toward[0] == a:
        g = s * s
    elif toward:
        g = 1 - (1 - s) ** 2
    else:
        g = s
    return a + (b - a) * g


def axis(breaks, counts, singular):
    """Element edges along one axis: each interval [breaks[i], breaks[i+1]] gets counts[i]
    elements, graded towards the breaks that are in `singular` (plate edges)."""
    out = [breaks[0]]
    for a, b, n in zip(breaks[:-1], breaks[1:], counts):
        toward = [p for p in (a, b) if any(abs(p - s) < 1e-12 for s in singular)]
        out.extend(graded(a, b, n, toward)[1:])
    return np.array(out)


class Beam:
    def __init__(self, args, level):
        half_len = args.length / 2
        sup = (args.length - args.span) / 2
        w = args.plate_width
        xb = [0.0, sup - w / 2, sup + w / 2, half_len - w / 2, half_len]
        base = [2, 2, 6, 1]
        self.x = axis(xb, [c * level for c in base], singular=xb[1:4])
        self.y = np.linspace(0.0, args.width / 2, 2 * level + 1)
        self.z = axis([0.0, args.depth], [5 * level], singular=[0.0, args.depth])
        self.args = args

    def nodes(self):
        """Node coordinates of the quadratic grid (element edges plus midpoints) per axis."""
        def fill(e):
            return np.sort(np.concatenate([e, (e[:-1] + e[1:]) / 2]))
        return fill(self.x), fill(self.y), fill(self.z)


def assemble(beam, d):
    grads, weights = reference_gradients()
    nx, ny, nz = len(beam.x) - 1, len(beam.y) - 1, len(beam.z) - 1
    gx, gy = 2 * nx + 1, 2 * ny + 1
    dx, dy, dz = np.diff(beam.x), np.diff(beam.y), np.diff(beam.z)
    ei, ej, ek = np.meshgrid(np.arange(nx), np.arange(ny), np.arange(nz), indexing="ij")
    ei, ej, ek = ei.ravel(), ej.ravel(), ek.ravel()
    local = np.array([(i, j, k) for k in range(3) for j in range(3) for i in range(3)])
    node = ((2 * ek[:, None] + local[None, :, 2]) * gy + 2 * ej[:, None] + local[None, :, 1]) * gx \
        + 2 * ei[:, None] + local[None, :, 0]
    dofs = (3 * node[:, :, None] + np.arange(3)[None, None, :]).reshape(len(ei), 81)
    sizes = np.stack([dx[ei], dy[ej], dz[ek]], axis=1)
    keys, inverse = np.unique(np.round(sizes, 15), axis=0, return_inverse=True)
    kes = np.array([box_stiffness(s, d, grads, weights) for s in keys])
    rows = np.repeat(dofs, 81, axis=1).ravel()
    cols = np.tile(dofs, (1, 81)).ravel()
    vals = kes[inverse.ravel()].reshape(len(ei), -1).ravel()
    n = 3 * gx * gy * (2 * nz + 1)
    return sp.csr_matrix((vals, (rows, cols)), shape=(n, n))


def plate_nodes(beam):
    """Node ids on the support (bottom) and under the loading plate (top) in the quarter."""
    a = beam.args
    xs, ys, zs = beam.nodes()
    gx, gy = len(xs), len(ys)
    sup = (a.length - a.span) / 2
    half = a.length / 2
    tol = 1e-9
    ix_sup = np.where((xs >= sup - a.plate_width / 2 - tol) & (xs <= sup + a.plate_width / 2 + tol))[0]
    ix_load = np.where(xs >= half - a.plate_width / 2 - tol)[0]

    def ids(ix, kz):
        i, j = np.meshgrid(ix, np.arange(gy), indexing="ij")
        return (kz * gy + j.ravel()) * gx + i.ravel()
    return ids(ix_sup, 0), ids(ix_load, len(zs) - 1), (xs, ys, zs)


def solve(beam, d, glued):
    """Displacement control with delta = 1 m; returns K = P / delta for the whole beam.

    The supports' vertical DOFs stay free and carry contact reactions r found by a small
    complementarity problem on their compliance: w = w0 + A r >= 0, r >= 0, r w = 0 (one
    factorisation, A from one solve per support DOF). The loading plate's nodes are held at the
    plate; an outer loop releases those that pull on it and takes back those that pass through it
    (refactorising), which happens only with narrow plates on coarse meshes."""
    k = assemble(beam, d)
    support, load, (xs, ys, zs) = plate_nodes(beam)
    gx, gy, gz = len(xs), len(ys), len(zs)
    all_nodes = np.arange(gx * gy * gz)
    ix, iy = all_nodes % gx, (all_nodes // gx) % gy
    symmetry = {dof: 0.0 for dof in 3 * all_nodes[ix == gx - 1]}
    symmetry.update({dof: 0.0 for dof in 3 * all_nodes[iy == gy - 1] + 1})
    contact = 3 * support + 2
    pressing = np.ones(len(load), bool)
    for _ in range(50):
        fixed = dict(symmetry)
        for n in load[pressing]:
            fixed[3 * n + 2] = -1.0
            if glued:
                fixed[3 * n], fixed[3 * n + 1] = 0.0, 0.0
        if glued:
            for n in support:
                fixed[3 * n], fixed[3 * n + 1], fixed[3 * n + 2] = 0.0, 0.0, 0.0
        u, reactions, touching = solve_with_supports(k, fixed, None if glued else contact)
        f = k @ u
        fz, w = f[3 * load + 2], u[3 * load + 2]
        pulls = pressing & (fz > 1e-9 * np.abs(fz).max())
        passes = ~pressing & (w > -1.0 + 1e-12)
        if glued or not (pulls.any() or passes.any()):
            break
        pressing[pulls], pressing[passes] = False, True
    else:
        raise RuntimeError("the loading plate's contact did not settle in 50 sweeps")
    load_total = -4.0 * fz[pressing].sum()
    support_total = 4.0 * (f[contact].sum() if glued else reactions.sum())
    share = 1.0 if glued else touching.mean()
    return load_total, support_total, k.shape[0], share


def solve_with_supports(k, fixed, contact):
    """u with the DOFs in `fixed` prescribed and, unless contact is None, the DOFs in `contact`
    resting on a frictionless plane at 0 (unilateral)."""
    c = np.array(sorted(fixed))
    uc = np.array([fixed[i] for i in c])
    free = np.setdiff1d(np.arange(k.shape[0]), c)
    lu = spla.splu(k[free][:, free].tocsc(), permc_spec="COLAMD")
    u = np.zeros(k.shape[0])
    u[c] = uc
    u[free] = lu.solve(-(k[free][:, c] @ uc))
    if contact is None:
        return u, None, None
    where = np.searchsorted(free, contact)
    unit = np.zeros((len(free), len(contact)))
    unit[where, np.arange(len(contact))] = 1.0
    g = lu.solve(unit)
    reactions, touching = contact_reactions(u[contact], g[where])
    u[free] += g @ reactions
    return u, reactions, touching


def contact_reactions(w0, a):
    """Reactions r >= 0 with w = w0 + a r >= 0 and r w = 0 (a symmetric positive definite):
    an active set that starts with every node in contact, drops those that pull and takes back
    those that pass through the plate, until neither happens."""
    active = np.ones(len(w0), bool)
    for _ in range(200):
        r = np.zeros(len(w0))
        idx = np.where(active)[0]
        r[idx] = np.linalg.solve(a[np.ix_(idx, idx)], -w0[idx])
        w = w0 + a @ r
        pulls = active & (r < 0)
        passes = ~active & (w < -1e-12)
        if not pulls.any() and not passes.any():
            return r, active
        active[pulls] = False
        active[passes] = True
    raise RuntimeError("support contact did not settle in 200 sweeps")


def extrapolate(results):
    """Richardson on three levels with K(h) = K* + C h^p, h = 1 / level: p from the ratio of the
    two differences (bisection), then K*. None when the levels do not converge monotonically."""
    (l1, k1), (l2, k2), (l3, k3) = results
    h1, h2, h3 = 1.0 / l1, 1.0 / l2, 1.0 / l3
    if (k2 - k1) * (k3 - k2) <= 0:
        return None
    target = (k2 - k1) / (k3 - k2)

    def ratio(p):
        return (h1 ** p - h2 ** p) / (h2 ** p - h3 ** p)
    lo, hi = 0.05, 8.0
    if not (ratio(lo) - target) * (ratio(hi) - target) < 0:
        return None
    for _ in range(200):
        mid = (lo + hi) / 2
        if (ratio(lo) - target) * (ratio(mid) - target) <= 0:
            hi = mid
        else:
            lo = mid
    p = (lo + hi) / 2
    c = (k3 - k2) / (h3 ** p - h2 ** p)
    return k3 - c * h3 ** p, p


def parser():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--E", type=float, default=sr.E_CONCRETE, help="Young's modulus [Pa]")
    p.add_argument("--nu", type=float, default=sr.NU_CONCRETE, help="Poisson's ratio")
    p.add_argument("--plates", choices=("frictionless", "glued"), default="frictionless")
    p.add_argument("--levels", default="1,2,3", help="mesh refinement levels, coarse to fine")
    p.add_argument("--span", type=float, default=sr.SPAN)
    p.add_argument("--length", type=float, default=sr.LENGTH)
    p.add_argument("--width", type=float, default=sr.B)
    p.add_argument("--depth", type=float, default=sr.H)
    p.add_argument("--plate-width", type=float, default=0.020)
    return p


def main(argv):
    a = parser().parse_args(argv)
    d = elasticity(a.E, a.nu)
    results = []
    for level in [int(s) for s in a.levels.split(",")]:
        t = time.time()
        beam = Beam(a, level)
        kval, ksup, ndof, share = solve(beam, d, a.plates == "glued")
        results.append((level, kval))
        print(f"level {level}: {ndof} dof, K = {kval / 1e6:.3f} kN/mm (supports {ksup / 1e6:.3f}), "
              f"support nodes in contact {100 * share:.0f}%, {time.time() - t:.1f} s", flush=True)
    if len(results) >= 3:
        estimate = extrapolate(results[-3:])
        if estimate:
            print(f"extrapolated: K = {estimate[0] / 1e6:.3f} kN/mm "
                  f"(observed order {estimate[1]:.2f} in h)")
    print(f"E = {a.E / 1e9:.2f} GPa, nu = {a.nu:.4f}, plates {a.plates}, span {a.span * 1e3:.0f} mm, "
          f"{a.length * 1e3:.0f} x {a.width * 1e3:.0f} x {a.depth * 1e3:.0f} mm, plates "
          f"{a.plate_width * 1e3:.0f} mm")


if __name__ == "__main__":
    main(sys.argv[1:])
