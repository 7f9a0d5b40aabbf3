#!/usr/bin/env python3
"""The communication matrix of an exasph run (the SPH-EXA paper's figure): which rank sends how
many bytes per step to which, from the run's comm_matrix.csv (exasph --comm-report), as a PNG.

    /usr/bin/python3 tools/comm_matrix.py RUN [-o comm_matrix.png] [--traffic halo|migration|gravity]

Prints the ranks, the peers per rank (mean / max) and the bytes per step of the kind drawn.
Exits 2 with one line on a missing or malformed file.
"""
import argparse
import sys
from pathlib import Path


def fail(msg, code=2):
    print(f"comm_matrix.py: {msg}", file=sys.stderr)
    sys.exit(code)


try:
    import numpy as np
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import LogNorm
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "python"))
    import exasph
except ImportError as exc:  # pragma: no cover
    fail(f"needs numpy and matplotlib ({exc}); on Debian: apt-get install python3-numpy "
         "python3-matplotlib (and run /usr/bin/python3)")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("run", help="the run's folder or its comm_matrix.csv")
    ap.add_argument("-o", "--output", default="comm_matrix.png", help="PNG to write")
    ap.add_argument("--traffic", default="halo", choices=exasph.comm_matrix.TRAFFIC)
    args = ap.parse_args()
    try:
        m = exasph.load_comm_matrix(args.run, args.traffic)
    except exasph.ExasphFileError as exc:
        fail(str(exc))
    n = m.shape[0]
    peers = ((m > 0) | (m.T > 0)).sum(axis=1)
    fig, ax = plt.subplots(figsize=(5.5, 4.6))
    shown = np.where(m > 0, m, np.nan)
    norm = LogNorm(vmin=np.nanmin(shown), vmax=np.nanmax(shown)) if np.any(m > 0) else None
    img = ax.imshow(shown, origin="upper", cmap="viridis", norm=norm, interpolation="nearest")
    fig.colorbar(img, ax=ax, label=f"{args.traffic} bytes sent per step")
    ax.set_xlabel("receiving rank")
    ax.set_ylabel("sending rank")
    ax.set_title(f"{n} ranks: {args.traffic} peers per rank mean {peers.mean():.1f}, "
                 f"max {peers.max()}", fontsize=9)
    fig.tight_layout()
    fig.savefig(args.output, dpi=120)
    print(f"{n} ranks, {args.traffic} peers per rank mean {peers.mean():.2f} max {peers.max()}, "
          f"{m.sum():.4g} bytes per step in all; wrote {args.output}")


if __name__ == "__main__":
    main()
