#!/usr/bin/python3
"""Figures and a Markdown table from bench/partition_model's tables (docs/parallel.md).

Strong scaling: each table's speed-up and parallel efficiency against P, ideal drawn. Weak
scaling, from the same partitions: a rank that keeps the part size of P_ref parts of the
specimen keeps its compute (with its cut contacts' copies), ghosts and neighbours as the job
grows (its part sees the same surroundings), and only the global sums' latency grows, as
2 ceil(log2 P) latencies; its efficiency at P is the serial time of its share, t_1 / P_ref, over
t_compute + t_exchange + t_allreduce(P). Needs each table's P = 1 row.

usage: partition_report.py OUT_DIR LABEL=TABLE.csv ... [--steps LABEL=N ...] [--ranks P]
                           [--weak P1,P2] [--latency A]
  --steps: a run's step count, for the projected wall time at P = --ranks (default 64)
  --weak: weak scaling for the part sizes of these P (default 64,1024)
"""
import argparse
import csv
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    if not rows:
        raise SystemExit(f"partition_report: {path} has no rows")
    return rows


def weak_efficiency(row, serial, p, latency):
    """A rank with the part `row` among p ranks: the serial time of its share of the points
    (serial / row's P) over its step (its compute with the cut contacts' copies, its exchange,
    the global sums at p)."""
    t_c, t_x = float(row["t_compute_s"]), float(row["t_exchange_s"])
    t_red = 2 * math.ceil(math.log2(p)) * latency
    return serial / int(row["P"]) / (t_c + t_x + t_red)


def table(tables):
    out = ["| specimen, rate | P | points, largest rank | imbalance | duplicated | ghosts "
           "(bytes/step) | neighbours | step (ms) | speed-up | efficiency |",
           "|---|---|---|---|---|---|---|---|---|---|"]
    for label, rows in tables.items():
        for r in rows:
            out.append(f"| {label} | {r['P']} | {int(r['max_points']):,} | {float(r['imbalance']):.3f} "
                       f"| {100 * float(r['duplicated_share']):.1f}% | {int(r['max_ghosts']):,} "
                       f"({int(float(r['max_bytes_per_step'])):,}) | {r['max_neighbours']} "
                       f"| {1e3 * float(r['t_step_s']):.3f} | {float(r['speedup']):.1f} "
                       f"| {float(r['efficiency']):.2f} |")
    return "\n".join(out)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("tables", nargs="+", help="LABEL=TABLE.csv")
    ap.add_argument("--steps", action="append", default=[], help="LABEL=N")
    ap.add_argument("--ranks", type=int, default=64)
    ap.add_argument("--latency", type=float, default=2e-6, help="as given to the model [s]")
    ap.add_argument("--weak", type=lambda t: [int(x) for x in t.split(",")], default=[64, 1024],
                    help="the part sizes of weak scaling, as the P that cut the specimen so")
    a = ap.parse_args()
    tables = {}
    for item in a.tables:
        label, _, path = item.partition("=")
        tables[label] = read(path)
    os.makedirs(a.out, exist_ok=True)
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    for label, rows in tables.items():
        p = [int(r["P"]) for r in rows]
        ax[0].loglog(p, [float(r["speedup"]) for r in rows], "o-", label=label)
        ps = [2 ** k for k in range(1, 21)]
        serial = float(rows[0]["t_step_s"]) if int(rows[0]["P"]) == 1 else None
        for part in (r for r in rows if serial and int(r["P"]) in a.weak):
            ax[1].semilogx(ps, [weak_efficiency(part, serial, q, a.latency) for q in ps], "-",
                           label=f"{label}: parts of P = {part['P']} "
                                 f"({int(part['max_points']):,} points)")
    pmax = max(int(r["P"]) for rows in tables.values() for r in rows)
    ax[0].loglog([1, pmax], [1, pmax], "k:", label="ideal")
    ax[0].set(xlabel="ranks P", ylabel="speed-up (projected)", title="strong scaling")
    ax[1].set(xlabel="ranks P", ylabel="efficiency (projected)", title="weak scaling",
              ylim=(0, 1.05))
    for x in ax:
        x.grid(True, which="both", alpha=0.3)
        x.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "scaling.png"), dpi=120)
    lines = [table(tables)]
    for item in a.steps:
        label, _, n = item.partition("=")
        row = next((r for r in tables[label] if int(r["P"]) == a.ranks), None)
        if row is None:
            raise SystemExit(f"partition_report: {label} has no row for P = {a.ranks}")
        t = float(row["t_step_s"]) * float(n)
        lines.append(f"- {label}: {int(float(n)):,} steps on {a.ranks} ranks: {t / 3600:.2f} h "
                     f"({float(row['t_step_s']) * 1e3:.3f} ms a step)")
    with open(os.path.join(a.out, "partition.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
