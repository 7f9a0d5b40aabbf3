#!/usr/bin/env python3
"""Compare the particle fields of two exasph HDF5 files (checkpoints or snapshots), matching
particles by their persistent id.

    h5compare.py A.h5 B.h5 [--rtol R]

Prints the largest difference of every common field (absolute, and relative to the field's
largest magnitude; the components of a vector share the magnitude of the vector) and exits 0 when all are within --rtol (default 0: bitwise equal), 1 when
not, 2 on a missing or malformed file.
"""
import argparse
import sys
from pathlib import Path


def fail(msg, code=2):
    print(f"h5compare: {msg}", file=sys.stderr)
    sys.exit(code)


try:
    import h5py
    import numpy as np
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "python"))
    import exasph
except ImportError as exc:  # pragma: no cover - depends on the machine
    fail(f"needs numpy and h5py ({exc}); on Debian: apt-get install python3-numpy python3-h5py")


# Components of one vector: a round-off difference in a component that is zero in exact
# arithmetic (v_z of the square patch) is measured against the whole vector.
VECTORS = {}
for _group in (("x", "y", "z"), ("x_m1", "y_m1", "z_m1"), ("vx", "vy", "vz"), ("ax", "ay", "az")):
    for _name in _group:
        VECTORS[_name] = _group


def load(path):
    """Ids and fields (exasph's names) of a snapshot (either format version), checkpoint or
    initial-conditions file, in id order."""
    try:
        s = exasph.load_snapshot(path)
    except exasph.ExasphFileError as exc:
        fail(str(exc))
    if s.id is None:
        fail(f"{path}: no particle ids")
    order = np.argsort(s.id)
    return s.id[order], {k: v[order] for k, v in s.fields.items()}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("a")
    ap.add_argument("b")
    ap.add_argument("--rtol", type=float, default=0.0,
                    help="tolerance relative to each field's largest magnitude (default 0)")
    args = ap.parse_args()
    ids_a, a = load(args.a)
    ids_b, b = load(args.b)
    if len(ids_a) != len(ids_b) or not np.array_equal(ids_a, ids_b):
        print(f"particle ids differ ({len(ids_a)} vs {len(ids_b)} particles)")
        return 1
    worst = 0.0
    for name in sorted(set(a) & set(b)):
        diff = np.abs(a[name] - b[name])
        group = VECTORS.get(name, (name,))
        scale = max(np.abs(d[g]).max(initial=0.0) for d in (a, b) for g in group if g in d)
        rel = diff.max(initial=0.0) / scale if scale > 0 else diff.max(initial=0.0)
        worst = max(worst, rel)
        print(f"{name:10s} max |diff| {diff.max(initial=0.0):.3e}  relative {rel:.3e}")
    ok = worst <= args.rtol
    print(f"{len(ids_a)} particles, worst relative difference {worst:.3e}: "
          f"{'equal' if ok else 'DIFFERENT'} (rtol {args.rtol:g})")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
