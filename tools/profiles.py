#!/usr/bin/env python3
"""Radial profiles of density, radial velocity, pressure and internal energy from an exasph
snapshot, binned in radius and plotted against the exact solution (Sedov or Noh), as a PNG.

    /usr/bin/python3 tools/profiles.py OUT/snapshot_000137.h5 [-o profile.png] [--bins 100]

The problem (sedov or noh) and gamma are read from the snapshot's attributes; the exact
solution comes from `exasph exact` (found next to this script in build/, on PATH, or given with
--exasph). Exits 2 with one line on a missing or malformed snapshot.
"""
import argparse
import os
import shutil
import subprocess
import sys
from pathlib import Path


def fail(msg, code=2):
    print(f"profiles.py: {msg}", file=sys.stderr)
    sys.exit(code)


try:
    import h5py
    import numpy as np
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError as exc:  # pragma: no cover
    fail(f"needs numpy, h5py and matplotlib ({exc}); on Debian: apt-get install "
         "python3-numpy python3-h5py python3-matplotlib (and run /usr/bin/python3)")


def find_exasph(given):
    if given:
        return given
    here = Path(__file__).resolve().parent.parent / "build" / "exasph"
    if here.exists():
        return str(here)
    found = shutil.which("exasph")
    if found:
        return found
    fail("cannot find the exasph binary (build it, or pass --exasph PATH)")


def read_snapshot(path):
    if not Path(path).exists():
        fail(f"{path}: no such file")
    try:
        f = h5py.File(path, "r")
    except OSError as exc:
        fail(f"{path}: not a readable HDF5 file ({exc})")
    steps = [k for k in f.keys() if k.startswith("Step#")]
    if not steps:
        fail(f"{path}: no Step#N group (not an exasph snapshot)")
    g = f[max(steps, key=lambda k: int(k[5:]))]
    need = ["x", "y", "z", "vx", "vy", "vz", "rho", "p", "u"]
    missing = [k for k in need if k not in g]
    if missing:
        fail(f"{path}: snapshot lacks the fields {', '.join(missing)} (write them with -f)")
    if "time" not in g.attrs:
        fail(f"{path}: group {g.name} lacks the attribute 'time'")
    data = {k: np.asarray(g[k][()], dtype=float) for k in need}
    init = f.attrs.get("param:init", "")
    gamma = float(f.attrs.get("gamma", 5.0 / 3.0))
    return data, float(g.attrs["time"]), str(init), gamma


def exact_profile(exasph, problem, t, gamma, rmax):
    cmd = [exasph, "exact", problem, "--t", repr(t), "--gamma", repr(gamma), "--rmax",
           repr(rmax), "--points", "2000"]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        fail(f"'{' '.join(cmd)}' failed: {p.stderr.strip()}")
    rows = [list(map(float, ln.split())) for ln in p.stdout.splitlines() if not ln.startswith("#")]
    return np.array(rows)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("snapshot")
    ap.add_argument("-o", "--output", help="PNG file (default: SNAPSHOT with .png)")
    ap.add_argument("--bins", type=int, default=100)
    ap.add_argument("--rmax", type=float, help="largest radius (default: sedov 0.5, noh 0.5)")
    ap.add_argument("--exasph", help="path to the exasph binary")
    args = ap.parse_args()

    d, t, init, gamma = read_snapshot(args.snapshot)
    problem = init if init in ("sedov", "noh") else None
    rmax = args.rmax or 0.5
    r = np.sqrt(d["x"] ** 2 + d["y"] ** 2 + d["z"] ** 2)
    vr = np.where(r > 0, (d["x"] * d["vx"] + d["y"] * d["vy"] + d["z"] * d["vz"]) / np.maximum(r, 1e-300), 0)
    edges = np.linspace(0, rmax, args.bins + 1)
    centre = 0.5 * (edges[1:] + edges[:-1])
    idx = np.digitize(r, edges) - 1
    ok = (idx >= 0) & (idx < args.bins)

    def binned(q):
        s = np.bincount(idx[ok], weights=q[ok], minlength=args.bins)
        c = np.bincount(idx[ok], minlength=args.bins)
        return np.where(c > 0, s / np.maximum(c, 1), np.nan)

    panels = [("density", d["rho"], 1), ("radial velocity", vr, 2), ("pressure", d["p"], 3),
              ("internal energy", d["u"], 4)]
    ex = exact_profile(find_exasph(args.exasph), problem, t, gamma, rmax) if problem else None
    fig, axes = plt.subplots(2, 2, figsize=(10, 7.5))
    for ax, (name, q, col) in zip(axes.ravel(), panels):
        ax.plot(r, q, ",", color="0.75", label="particles")
        ax.plot(centre, binned(q), "o", ms=3, color="C0", label="exasph (binned)")
        if ex is not None:
            ax.plot(ex[:, 0], ex[:, col], "-", color="C3", label=f"exact {problem}")
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
