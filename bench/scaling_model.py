#!/usr/bin/env python3
"""Weak-scaling model of exasph (issue 23, docs/scaling.md): the time of one step on P nodes with
a fixed number of particles per node, from quantities measured on this machine and a stated
network model, as a table and a PNG beside the SPH-EXA paper's measured 67 % at 2,048 nodes.

    /usr/bin/python3 bench/scaling_model.py RUN_1 RUN_2 ... [-o scaling_model.png]

RUN_k: the --out folders of runs with fixed particles per rank on 1, 2, 4, ... ranks made with
--comm-report, each with its output in RUN_k.log beside the folder (docs/scaling.md has the
commands).
They give the halo ratio H (halo / owned particles) and the halo bytes per halo particle and
step; H is fitted to the surface-to-volume law H = c n^(-1/3) at the largest rank count (the
most three-dimensional decomposition) and extrapolated to the node's particle count.

Per step and node the model adds:
  compute   n / rate                                   (rate: particle-steps/s of one node)
  halos     peers x exchanges x latency + H n b_halo / bandwidth
  sync      the global tree's leaves: L = N / bucket (bucket fixed, or grown to N / 2^20 as
            exasph does since issue 23); every rank reduces 16 B per leaf
            (ring allreduce 2 x 16 L / bandwidth + 2 log2(P) latency) and walks them
            (L x t_leaf, measured)
  2 more collectives (time step, conservation sums): 2 x 2 log2(P) x latency
Efficiency = T(1) / T(P). The assumptions are arguments (defaults: the paper's machine, a Cray
XC50 with Aries, one NVIDIA GPU per node; the rate is exasph's measured H200 figure).
"""
import argparse
import math
import re
import sys
from pathlib import Path

try:
    import numpy as np
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError as exc:  # pragma: no cover
    sys.exit(f"scaling_model.py: needs numpy and matplotlib ({exc})")

COMM = re.compile(r"^communication: halo peers per rank mean ([\d.]+) max (\d+); halo ratio mean "
                  r"([\d.]+) max ([\d.]+) \(last step\); MB sent per step: halos per rank mean "
                  r"([\d.e+-]+) max ([\d.e+-]+)")
PARTICLES = re.compile(r"(\d+) particles")


def measured(run):
    """(ranks, particles per rank, peers mean, halo ratio mean, halo bytes per halo particle)."""
    log = Path(str(run).rstrip("/") + ".log")
    if not log.exists():
        sys.exit(f"scaling_model.py: {log}: no such file (the run's output)")
    text = log.read_text()
    ranks = int(re.search(r"(\d+) ranks? x", text).group(1))
    n = int(PARTICLES.search(text).group(1)) / ranks
    m = next((COMM.match(ln) for ln in text.splitlines() if COMM.match(ln)), None)
    if ranks == 1 or m is None:
        return ranks, n, 0.0, 0.0, 0.0
    peers, halo, mb = float(m.group(1)), float(m.group(3)), float(m.group(5))
    return ranks, n, peers, halo, mb * 1e6 / (halo * n)


def step_time(p, a, c, b_halo, peers):
    """Seconds of one step on p nodes (model above) and its parts."""
    n = a.particles_per_node
    total = n * p
    h = c * n ** (-1.0 / 3.0) if p > 1 else 0.0
    lat, bw = a.latency, a.bandwidth
    compute = n / a.rate
    halos = (min(peers, p - 1) * a.exchanges * lat + h * n * b_halo / bw) if p > 1 else 0.0
    bucket = max(a.bucket, total / 2 ** 20) if a.grow_bucket else a.bucket
    leaves = total / bucket
    hops = 2 * math.log2(p) * lat if p > 1 else 0.0
    sync = leaves * a.t_leaf + ((2 * 16 * leaves / bw + hops) if p > 1 else 0.0)
    collectives = 2 * hops
    return compute + halos + sync + collectives, (compute, halos, sync, collectives, h)


def efficiency_table(nodes, a, c, b_halo, peers):
    """Prints the model's table for a.bucket; returns the efficiencies T(1) / T(P)."""
    t1, _ = step_time(1, a, c, b_halo, peers)
    print(f"\nmodel: {a.particles_per_node:.3g} particles per node, {a.rate:.3g} particle-steps/s "
          f"per node, latency {a.latency:.2g} s, bandwidth {a.bandwidth:.3g} B/s, "
          f"global bucket {a.bucket:g}{' grown to N / 2^20' if a.grow_bucket else ''}")
    print(" nodes  s/step  compute  halos   sync  collectives  halo ratio  efficiency")
    eff = []
    for p in nodes:
        t, (cp, hl, sy, co, h) = step_time(p, a, c, b_halo, peers)
        eff.append(t1 / t)
        print(f" {p:5d}  {t:6.3f}  {cp:7.3f}  {hl:5.3f}  {sy:6.3f}  {co:11.2e}  {h:10.3f}  "
              f"{100 * t1 / t:9.1f} %")
    return eff


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("runs", nargs="+", help="--comm-report runs at fixed particles per rank")
    ap.add_argument("-o", "--output", default="scaling_model.png")
    ap.add_argument("--particles-per-node", type=float, default=32e6)
    ap.add_argument("--rate", type=float, default=4.7e6,
                    help="particle-steps/s of one node (exasph on one H200: 4.7e6)")
    ap.add_argument("--latency", type=float, default=1.5e-6, help="s per message (Aries)")
    ap.add_argument("--bandwidth", type=float, default=10e9, help="B/s per node (Aries)")
    ap.add_argument("--exchanges", type=int, default=3, help="halo exchanges per step")
    ap.add_argument("--bucket", type=float, default=128, help="--global-bucket")
    ap.add_argument("--t-leaf", type=float, default=0.5e-6,
                    help="s per global leaf and step on one rank (sync's count, sort, assignment)")
    a = ap.parse_args()
    rows = sorted(measured(r) for r in a.runs)
    print("measured (fixed particles per rank):")
    print(" ranks  particles/rank  peers  halo ratio  B per halo particle and step")
    for r in rows:
        print(f" {r[0]:5d}  {r[1]:14.0f}  {r[2]:5.1f}  {r[3]:10.3f}  {r[4]:8.0f}")
    big = rows[-1]
    if big[0] < 2:
        sys.exit("scaling_model.py: needs a run on several ranks")
    c = big[3] * big[1] ** (1.0 / 3.0)
    b_halo, peers = big[4], 26.0
    print(f"surface-to-volume fit at {big[0]} ranks: H = {c:.1f} n^(-1/3); "
          f"{b_halo:.0f} B per halo particle and step; peers at scale 26")
    fig, ax = plt.subplots(figsize=(6.5, 4))
    nodes = [1, 2, 4, 8, 16, 32, 64, 128, 256, 512, 1024, 2048]
    for grow, label in ((False, f"bucket fixed at {a.bucket:g} (before)"),
                        (True, f"bucket max({a.bucket:g}, N / 2^20) (exasph now)")):
        a.grow_bucket = grow
        eff = efficiency_table(nodes, a, c, b_halo, peers)
        ax.semilogx(nodes, [100 * e for e in eff], "o-", base=2, label=f"model, {label}")
    ax.semilogx([2048], [67], "s", color="tab:red", label="SPH-EXA paper, measured (67 %)")
    ax.set_xlabel(f"nodes ({a.particles_per_node:.3g} particles each)")
    ax.set_ylabel("weak-scaling efficiency (%)")
    ax.set_ylim(0, 105)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(a.output, dpi=120)
    print(f"wrote {a.output}")


if __name__ == "__main__":
    main()
