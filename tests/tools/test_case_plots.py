#!/usr/bin/env python3
"""tools/case_plots.py makes its six figures from short runs of their cases, prints the
numbers they plot (the Gresho-Chan L1 of an untouched vortex is 0), and exits 2 with one line
on a missing snapshot."""
import argparse
import re
import subprocess
import sys
import tempfile
from pathlib import Path

PLOTS = Path(__file__).resolve().parents[2] / "tools" / "case_plots.py"


def run_case(exe, case, side, out, steps):
    subprocess.run([exe, "--init", case, "-n", str(side), "--lattice", "-s", str(steps), "-w",
                    str(steps), "--out", out], check=True, capture_output=True)
    return sorted(Path(out).glob("snapshot_*.h5"))


def plot(command, snaps, png, *extra):
    p = subprocess.run([sys.executable, PLOTS, command, *map(str, snaps), "-o", str(png), *extra],
                       capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    assert png.exists() and png.stat().st_size > 15000, (command, png.stat().st_size)
    last = (p.stdout.strip().splitlines() or [""])[-1]
    print(f"{command}: PNG {png.stat().st_size} bytes; {last}")
    return p.stdout


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--exe", required=True)
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as w:
        w = Path(w)
        out = plot("gresho", run_case(args.exe, "gresho-chan", 16, w / "g", 2), w / "g.png")
        l1 = float(re.search(r"L1\(v_phi\)/v0 = ([0-9.e-]+)", out).group(1))
        assert l1 < 0.01, f"two steps of the vortex: L1 {l1}"
        plot("kh", run_case(args.exe, "kelvin-helmholtz", 16, w / "k", 2), w / "k.png")
        plot("slice", run_case(args.exe, "isobaric-cube", 8, w / "c", 2), w / "c.png")
        out = plot("wind", run_case(args.exe, "wind-cloud", 8, w / "w", 2), w / "w.png")
        assert "surviving fraction 1.000" in out, out  # two steps: the cloud is intact
        out = plot("turb", run_case(args.exe, "turbulence", 12, w / "t", 40), w / "t.png")
        mach = float(re.search(r"Mach_rms ([0-9.]+) at t", out).group(1))
        assert 0 < mach < 0.1, f"40 steps of stirring from rest: Mach {mach}"
        assert re.search(r"E\(k\) at t = [0-9.]+: k=1 ", out), out
        out = plot("square", run_case(args.exe, "square-patch", 12, w / "s", 3), w / "s.png")
        m = re.search(r"median ([0-9.e+-]+) max ([0-9.e+-]+); closest pair ([0-9.]+)", out)
        assert m and float(m.group(2)) < 1e-6, out  # three steps: the layers stay identical
        assert 0.9 < float(m.group(3)) <= 1.0, out  # the lattice has barely moved
        assert re.search(r"L_z: worst 0\.00[0-9] %", out), out
        p = subprocess.run([sys.executable, PLOTS, "gresho", str(w / "missing.h5"), "-o",
                            str(w / "x.png")], capture_output=True, text=True)
        assert p.returncode == 2 and "no such file" in p.stderr, p.stderr
        assert len(p.stderr.strip().splitlines()) == 1, p.stderr
    print("case_plots: passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
