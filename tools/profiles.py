#!/usr/bin/env python3
"""Radial profiles of density, radial velocity, pressure and internal energy from an exasph
snapshot, binned in radius and plotted against the exact solution (Sedov or Noh), as a PNG.

    /usr/bin/python3 tools/profiles.py OUT/snapshot_000137.h5 [-o profile.png] [--bins 100]

The problem (sedov or noh) and gamma are read from the snapshot's attributes; the exact
solution comes from `exasph exact` (found next to this script in build/, on PATH, or given with
--exasph). Exits 2 with one line on a missing or malformed snapshot.
"""
import argparse
import sys
from pathlib import Path


def fail(msg, code=2):
    print(f"profiles.py: {msg}", file=sys.stderr)
    sys.exit(code)


try:
    import numpy as np
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "python"))
    import exasph
except ImportError as exc:  # pragma: no cover
    fail(f"needs numpy, h5py and matplotlib ({exc}); on Debian: apt-get install "
         "python3-numpy python3-h5py python3-matplotlib (and run /usr/bin/python3)")

NEED = ["x", "y", "z", "vx", "vy", "vz", "rho", "p", "u"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("snapshot")
    ap.add_argument("-o", "--output", help="PNG file (default: SNAPSHOT with .png)")
    ap.add_argument("--bins", type=int, default=100)
    ap.add_argument("--rmax", type=float, help="largest radius (default: sedov 0.5, noh 0.5)")
    ap.add_argument("--exasph", help="path to the exasph binary")
    args = ap.parse_args()

    try:
        snap = exasph.load_snapshot(args.snapshot).require(*NEED)
    except exasph.ExasphFileError as exc:
        fail(str(exc))
    d, t, init, gamma = snap.fields, snap.time, snap.case, snap.gamma
    problem = init if init in ("sedov", "noh") else None
    rmax = args.rmax or 0.5
    r, vr = snap.radius(), snap.radial_velocity()
    edges = np.linspace(0, rmax, args.bins + 1)
    centre = 0.5 * (edges[1:] + edges[:-1])

    def binned(q):
        return exasph.binned_mean(r, q, edges)[0]

    panels = [("density", d["rho"], 1), ("radial velocity", vr, 2), ("pressure", d["p"], 3),
              ("internal energy", d["u"], 4)]
    try:
        ex = exasph.exact_solution(problem, t, gamma, rmax, exasph=args.exasph) if problem else None
    except exasph.ExasphFileError as exc:
        fail(str(exc))
    fig, axes = plt.subplots(2, 2, figsize=(10, 7.5))
    for ax, (name, q, col) in zip(axes.ravel(), panels):
        ax.plot(r, q, ",", color="0.75", label="particles")
        ax.plot(centre, binned(q), "o", ms=3, color="C0", label="exasph (binned)")
        if ex is not None:
            ax.plot(ex["r"], ex[exasph.exact.COLUMNS[col]], "-", color="C3",
                    label=f"exact {problem}")
        ax.set_xlabel("r")
        ax.set_ylabel(name)
        ax.set_xlim(0, rmax)
        if name == "internal energy" and problem == "sedov":
            ax.set_yscale("log")
        if name == "density":
            ax.legend(loc="best", fontsize=8)
    fig.suptitle(f"{Path(args.snapshot).name}: {init or 'unknown case'}, t = {t:.4g}, "
                 f"{len(r)} particles")
    fig.tight_layout()
    out = args.output or str(Path(args.snapshot).with_suffix(".png"))
    fig.savefig(out, dpi=110)
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
