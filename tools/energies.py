#!/usr/bin/env python3
"""Energy curves of one or more exasph runs from their diagnostics.csv: kinetic, internal,
potential and total energy against time, as a PNG (e.g. the Evrard collapse, physics.md §9.4).

    /usr/bin/python3 tools/energies.py RUN/diagnostics.csv [RUN2/diagnostics.csv ...] \
        [-o energies.png] [--label NAME ...] [--title TEXT] [--reference CURVES.csv]

--reference overlays published curves given as a CSV with a header line: a `time` column and
any of ekin, eint, epot, etot (e.g. digitised from a paper), drawn as markers.

Prints, per run, the largest drift of the total energy relative to |E_pot| at the first row and
the time of the kinetic-energy maximum. Exits 2 with one line on a missing or malformed file.
"""
import argparse
import sys
from pathlib import Path


def fail(msg, code=2):
    print(f"energies.py: {msg}", file=sys.stderr)
    sys.exit(code)


try:
    import numpy as np
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "python"))
    import exasph
except ImportError as exc:  # pragma: no cover
    fail(f"needs numpy and matplotlib ({exc}); on Debian: apt-get install python3-numpy "
         "python3-matplotlib (and run /usr/bin/python3)")

COLUMNS = ["time", "ekin", "eint", "epot", "etot"]


def read_run(path):
    try:
        data = exasph.load_diagnostics(path, need=COLUMNS)
    except exasph.ExasphFileError as exc:
        fail(str(exc))
    if data.size < 2:
        fail(f"{path}: fewer than two rows")
    return data


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("csv", nargs="+", help="diagnostics.csv of a run")
    ap.add_argument("-o", "--output", default="energies.png", help="PNG to write")
    ap.add_argument("--label", action="append", help="legend label per run (in order)")
    ap.add_argument("--title", default="", help="figure title")
    ap.add_argument("--reference", help="CSV of published curves (time + ekin/eint/epot/etot)")
    ap.add_argument("--reference-label", default="reference", help="legend label of --reference")
    args = ap.parse_args()
    labels = args.label or []
    fig, ax = plt.subplots(figsize=(9.5, 4.5))
    styles = ["-", "--", ":", "-."]
    colours = {"ekin": "tab:red", "eint": "tab:blue", "epot": "tab:green", "etot": "black"}
    names = {"ekin": "kinetic", "eint": "internal", "epot": "potential", "etot": "total"}
    for k, path in enumerate(args.csv):
        d = read_run(path)
        label = labels[k] if k < len(labels) else Path(path).parent.name
        ls = styles[k % len(styles)]
        for key in ["ekin", "eint", "epot", "etot"]:
            ax.plot(d["time"], d[key], ls, color=colours[key], lw=1.3,
                    label=f"{names[key]} ({label})")
        drift = np.max(np.abs(d["etot"] - d["etot"][0]))
        scale = abs(d["epot"][0]) if d["epot"][0] != 0 else abs(d["etot"][0])
        imax = int(np.argmax(d["ekin"]))
        print(f"{path}: {d.size} rows to t = {d['time'][-1]:.4g}; worst total-energy drift "
              f"{drift:.3e} ({100 * drift / scale:.2f} % of |E_pot(0)|); E_kin max "
              f"{d['ekin'][imax]:.4f} at t = {d['time'][imax]:.3f}; E_pot min {d['epot'].min():.4f}")
    if args.reference:
        if not Path(args.reference).exists():
            fail(f"{args.reference}: no such file")
        try:
            ref = np.atleast_1d(np.genfromtxt(args.reference, delimiter=",", names=True))
        except (ValueError, OSError) as exc:
            fail(f"{args.reference}: not a CSV ({exc})")
        if ref.dtype.names is None or "time" not in ref.dtype.names:
            fail(f"{args.reference}: needs a header line with a time column")
        for key in ["ekin", "eint", "epot", "etot"]:
            if key in ref.dtype.names:
                ax.plot(ref["time"], ref[key], "o", ms=3, mfc="none", color=colours[key],
                        label=f"{names[key]} ({args.reference_label})")
    ax.set_xlabel("t")
    ax.set_ylabel("energy")
    ax.axhline(0, color="grey", lw=0.5)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    if args.title:
        ax.set_title(args.title)
    fig.tight_layout()
    fig.savefig(args.output, dpi=120)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
