#!/usr/bin/env python3
"""The Evrard collapse against its reference data (tests/data/evrard: a converged 1D
spherical computation and profiles digitised from Evrard 1988 / Steinmetz & Mueller 1993).

    /usr/bin/python3 tools/evrard.py RUN_DIR [RUN_DIR ...] [--label A ...] [-o evrard]
        [--reference DIR]

RUN_DIR holds an `exasph --init evrard` run's diagnostics.csv and snapshots (-w). Writes
PREFIX_energies.png (E_kin, E_int, E_pot, E_tot against time beside the 1D curves) and
PREFIX_profiles.png (binned rho, v_r, P of the snapshots nearest t = 0.77, 1.29, 2.58 beside the
1D profiles and the digitised points), and prints per run the numbers of the resolution study:
peak E_kin, minimum E_pot, peak E_int, the worst |E_tot - E_tot(0)| / |E_pot(0)|, and at
t = 0.77 the shock radius (where the binned v_r first rises above half its minimum, inwards
of the minimum: the same rule on the 1D profile gives its value) and the core density (mean of
rho / rho_1D(r) over the particles in 0.02 < r < 0.1). Exits 2 with one line on a missing or
malformed input.
"""
import argparse
import sys
from pathlib import Path

from case_plots import fail, read_snapshot  # puts python/ (the exasph package) on the path

import exasph

import numpy as np
import matplotlib.pyplot as plt

TIMES = (0.77, 1.29, 2.58)
# The digitised points are in units of rho_norm = 3 M / (4 pi R^3) (p: rho_norm G M / R).
NORM = {"rho": 3 / (4 * np.pi), "p": 3 / (4 * np.pi), "v_r": 1.0}


def read_csv(path):
    """A CSV with a header line after any '#' comment lines."""
    if not Path(path).exists():
        fail(f"{path}: no such file")
    lines = [ln for ln in Path(path).read_text().splitlines() if not ln.startswith("#")]
    try:
        return np.genfromtxt(lines, delimiter=",", names=True, dtype=None, encoding="utf-8")
    except ValueError as exc:
        fail(f"{path}: malformed CSV ({str(exc).splitlines()[0]})")


def radial(d):
    r = np.sqrt(d["x"] ** 2 + d["y"] ** 2 + d["z"] ** 2)
    vr = (d["x"] * d["vx"] + d["y"] * d["vy"] + d["z"] * d["vz"]) / np.maximum(r, 1e-300)
    return r, {"rho": d["rho"], "v_r": vr, "p": d["p"]}


def binned(r, q, edges):
    return exasph.binned_mean(r, q, edges)[0]


def shock_radius(r, vr):
    """Inwards of the most negative v_r, where v_r first rises above half of it."""
    k = int(np.nanargmin(vr))
    for j in range(k, 0, -1):
        if vr[j - 1] > 0.5 * vr[k]:
            f = (0.5 * vr[k] - vr[j]) / (vr[j - 1] - vr[j])
            return r[j] + f * (r[j - 1] - r[j])
    return float("nan")


def energies(run):
    try:
        d = exasph.load_diagnostics(run, need=("time", "ekin", "eint", "epot", "etot"))
    except exasph.ExasphFileError as exc:
        fail(str(exc))
    return d["time"], d["ekin"], d["eint"], d["epot"], d["etot"]


def snapshots_near(run):
    found = {}
    for p in sorted(Path(run).glob("snapshot_*.h5")):
        t = read_snapshot(p, [])["time"]
        for target in TIMES:
            if abs(t - target) <= 0.02 * target and (
                    target not in found or abs(t - target) < abs(found[target][0] - target)):
                found[target] = (t, p)
    return found


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--label", action="append")
    ap.add_argument("-o", "--output", default="evrard", help="prefix of the two PNG files")
    ap.add_argument("--reference", default=str(Path(__file__).resolve().parents[1] / "tests" /
                                                "data" / "evrard"))
    args = ap.parse_args()
    labels = args.label or [Path(r).name for r in args.runs]
    if len(labels) != len(args.runs):
        fail(f"{len(args.runs)} runs but {len(labels)} --label")
    ref = Path(args.reference)
    e1d = read_csv(ref / "lagrangian1d_energies.csv")
    digit = read_csv(ref / "digitised_profiles.csv")
    prof1d = {t: read_csv(ref / f"lagrangian1d_profile_t{t:.3f}.csv") for t in TIMES}

    fig_e, ax_e = plt.subplots(figsize=(7, 4.5))
    for key, name in (("ekin", "E_kin"), ("eint", "E_int"), ("epot", "E_pot"), ("etot", "E_tot")):
        ax_e.plot(e1d["time"], e1d[key], "k-", lw=0.8)
        ax_e.text(e1d["time"][-1], e1d[key][-1], " " + name, va="center", fontsize=8)
    fig_p, axes = plt.subplots(3, len(TIMES), figsize=(4 * len(TIMES), 9), squeeze=False)
    edges = np.logspace(-2.5, 0.2, 40)
    centres = np.sqrt(edges[1:] * edges[:-1])
    r1 = prof1d[0.77]["r"]
    print(f"1D: E_kin peak {e1d['ekin'].max():.3f}, E_pot min {e1d['epot'].min():.3f}, E_int "
          f"peak {e1d['eint'].max():.3f}, shock at t = 0.77: "
          f"{shock_radius(r1, prof1d[0.77]['v_r']):.3f}")
    for n, (run, label) in enumerate(zip(args.runs, labels)):
        t, ek, ei, ep, et = energies(run)
        c = f"C{n}"
        for q in (ek, ei, ep, et):
            ax_e.plot(t, q, color=c, lw=1.2, label=label if q is ek else None)
        drift = np.max(np.abs(et - et[0])) / abs(ep[0])
        line = (f"{label}: E_kin peak {ek.max():.3f} (t = {t[np.argmax(ek)]:.3f}), E_pot min "
                f"{ep.min():.3f}, E_int peak {ei.max():.3f}, worst |dE_tot|/|E_pot(0)| "
                f"{100 * drift:.2f} % to t = {t[-1]:.2f}")
        for col, target in enumerate(TIMES):
            if target not in (near := snapshots_near(run)):
                continue
            ts, path = near[target]
            r, q = radial(read_snapshot(path, ["x", "y", "z", "vx", "vy", "vz", "rho", "p"]))
            for row, key in enumerate(("rho", "v_r", "p")):
                axes[row][col].plot(centres, binned(r, q[key], edges), "o-", ms=2.5, color=c,
                                    label=f"{label} (t = {ts:.3f})")
            if target == 0.77:
                rs = shock_radius(centres, binned(r, q["v_r"], edges))
                core = (r > 0.02) & (r < 0.1)
                rho1 = np.exp(np.interp(np.log(r[core]), np.log(r1), np.log(prof1d[0.77]["rho"])))
                line += (f"; t = {ts:.3f}: shock {rs:.3f}, core rho/rho_1D "
                         f"{np.mean(q['rho'][core] / rho1):.2f}")
        print(line)
    ax_e.set(xlabel="t", ylabel="energy", title="Evrard collapse: exasph (colour) and 1D (black)")
    ax_e.legend(loc="lower left")
    fig_e.tight_layout()
    fig_e.savefig(f"{args.output}_energies.png", dpi=110)
    for col, target in enumerate(TIMES):
        p1 = prof1d[target]
        for row, key in enumerate(("rho", "v_r", "p")):
            ax = axes[row][col]
            ax.plot(p1["r"], p1[key], "k-", lw=0.8, label="1D")
            dig = digit[(np.abs(digit["t"] - target) < 1e-6) & (digit["quantity"] == key)]
            ax.plot(dig["r"], dig["value"] * NORM[key], "kx", ms=4, label="digitised")
            ax.set_xscale("log")
            if key != "v_r":
                ax.set_yscale("log")
            ax.set(xlim=(3e-3, 1.5), xlabel="r", ylabel=key, title=f"t = {target}")
            if row == 0:
                ax.legend(fontsize=7)
    fig_p.tight_layout()
    fig_p.savefig(f"{args.output}_profiles.png", dpi=110)
    return 0


if __name__ == "__main__":
    sys.exit(main())
