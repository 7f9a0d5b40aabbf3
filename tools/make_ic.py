#!/usr/bin/env python3
"""Write an exasph initial-conditions file (layout: docs/file-format.md).

Example: a periodic box of ideal gas on a perturbed lattice with a hot spot in the middle (a
small Sedov-like blast). Run it, then start exasph from the file:

    /usr/bin/python3 tools/make_ic.py -n 20 -o blast.h5
    build/exasph --init blast.h5 -s 50 -w 10 --out blast
"""
import argparse
import sys

try:
    import h5py
    import numpy as np
except ImportError as exc:  # pragma: no cover
    print(f"make_ic.py: needs numpy and h5py ({exc}); on Debian: "
          "apt-get install python3-numpy python3-h5py", file=sys.stderr)
    sys.exit(2)


def main():
    ap = argparse.ArgumentParser(description="Write an exasph initial-conditions HDF5 file.")
    ap.add_argument("-n", type=int, default=20, help="particles per axis (default 20)")
    ap.add_argument("-o", "--output", default="ic.h5", help="output file (default ic.h5)")
    ap.add_argument("--ng0", type=float, default=100.0, help="target neighbour count")
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args()
    if args.n < 8:
        ap.error("-n must be at least 8 (2h must stay below half the periodic box)")

    n = args.n
    dx = 1.0 / n
    grid = (np.arange(n) + 0.5) * dx - 0.5
    x, y, z = (a.ravel() for a in np.meshgrid(grid, grid, grid, indexing="ij"))
    rng = np.random.default_rng(args.seed)
    x, y, z = ((c + rng.uniform(-0.05, 0.05, c.size) * dx + 0.5) % 1.0 - 0.5 for c in (x, y, z))
    count = x.size
    r2 = x * x + y * y + z * z
    u = 1e-6 + np.exp(-r2 / (2 * 0.05 ** 2))  # hot spot
    u *= 1.0 / (u.sum() / count)  # total internal energy 1 (unit mass)
    with h5py.File(args.output, "w") as f:
        f.attrs["box_lo"] = [-0.5, -0.5, -0.5]
        f.attrs["box_hi"] = [0.5, 0.5, 0.5]
        f.attrs["periodic"] = [1, 1, 1]
        f.attrs["gamma"] = 5.0 / 3.0
        f.attrs["dt0"] = 1e-4
        f.attrs["units"] = "code units"
        f["x"], f["y"], f["z"] = x, y, z
        for name in ("vx", "vy", "vz"):
            f[name] = np.zeros(count)
        f["m"] = np.full(count, 1.0 / count)
        f["h"] = np.full(count, 0.5 * dx * (3 * args.ng0 / (4 * np.pi)) ** (1 / 3))
        f["u"] = u
        f["id"] = np.arange(count, dtype=np.uint64)
    print(f"wrote {args.output}: {count} particles")
    return 0


if __name__ == "__main__":
    sys.exit(main())
