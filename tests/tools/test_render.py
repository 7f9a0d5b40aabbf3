#!/usr/bin/env python3
"""`exasph render` (issue 22) on a Sedov snapshot: a slice and a projection of rho as PNG, HDF5
grid and XDMF; 1 and 2 ranks draw the same image; the slice's densest ring lies at the exact
solution's shock radius; a field the snapshot lacks is one line and exit 2.
Run by CTest as  test_render.py --exe build/exasph --mpirun "mpirun ..."."""
import argparse
import shlex
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET
from pathlib import Path

import h5py
import matplotlib.image
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "python"))
import exasph  # noqa: E402


def render(cmd, snap, prefix, *extra):
    p = subprocess.run(cmd + ["render", str(snap), "--resolution", "128", "--out", str(prefix),
                              *extra], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    png = Path(f"{prefix}.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n", png[:8]
    picture = matplotlib.image.imread(f"{prefix}.png")  # another decoder reads it
    assert picture.shape[0] == 128 and picture.shape[1] > 128, picture.shape
    assert len(np.unique(picture.reshape(-1, picture.shape[2]), axis=0)) > 50, "few colours"
    root = ET.parse(f"{prefix}.xdmf").getroot()
    assert root.find(".//Topology").get("Dimensions") == "1 128 128"  # z, y, x (axis z)
    with h5py.File(f"{prefix}.h5", "r") as f:
        return f["image"][()], dict(f.attrs)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--exe", required=True)
    ap.add_argument("--mpirun", required=True)
    a = ap.parse_args()
    one = [a.exe]
    two = shlex.split(a.mpirun) + ["-np", "2", a.exe]
    with tempfile.TemporaryDirectory() as w:
        w = Path(w)
        subprocess.run([a.exe, "--init", "sedov", "-n", "30", "--lattice", "--t-end", "0.02",
                        "-w", "0.02", "--out", str(w / "run")], check=True, capture_output=True)
        snap = sorted((w / "run").glob("snapshot_*.h5"))[-1]
        s = exasph.load_snapshot(snap)
        img, attrs = render(one, snap, w / "slice")
        img2, _ = render(two, snap, w / "slice2")
        assert attrs["mode"] == "slice" and attrs["field"] == "rho" and attrs["axis"] == "z"
        assert np.nanmax(np.abs(img2 - img)) <= 1e-12 * np.nanmax(img), "1 and 2 ranks differ"
        # The densest ring of the slice through the centre against the exact shock radius.
        n = img.shape[0]
        c = (np.arange(n) + 0.5) / n - 0.5
        r = np.hypot(*np.meshgrid(c, c, indexing="xy")).ravel()
        centres, ring, _ = exasph.radial_profile(r, img.ravel(), bins=40, rmax=0.5)
        ex = exasph.exact_solution("sedov", s.time, gamma=s.gamma, exasph=a.exe)
        r_shock = ex["r"][np.argmax(ex["rho"])]
        r_peak = centres[np.nanargmax(ring)]
        assert abs(r_peak - r_shock) < 0.1 * r_shock, (r_peak, r_shock)
        col, cattrs = render(one, snap, w / "column", "--project", "--log")
        assert cattrs["mode"] == "projection"
        # The column of mass over the periodic unit box: its mean is the total mass.
        mass = s.fields["m"].sum()
        assert abs(col.mean() / mass - 1) < 1e-3, (col.mean(), mass)
        p = subprocess.run(one + ["render", str(snap), "--field", "nosuch"], capture_output=True,
                           text=True)
        assert p.returncode == 2 and "nosuch" in p.stderr and p.stderr.count("\n") == 1, p.stderr
        print(f"render: slice peak at r = {r_peak:.3f} (exact shock {r_shock:.3f}), column mean "
              f"{col.mean():.6f} (mass {mass:.6f}), 1 vs 2 ranks equal")
    return 0


if __name__ == "__main__":
    sys.exit(main())
