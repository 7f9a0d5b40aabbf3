#!/usr/bin/env python3
"""tools/energies.py writes a non-trivial PNG from the diagnostics of an Evrard run (the
potential energy column is filled, the snapshot carries phi) and exits 2 with a clear message on
a missing or malformed file."""
import argparse
import subprocess
import sys
import tempfile
from pathlib import Path

ENERGIES = Path(__file__).resolve().parents[2] / "tools" / "energies.py"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--exe", required=True)
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as w:
        w = Path(w)
        subprocess.run([args.exe, "--init", "evrard", "-n", "14", "--lattice", "-s", "20",
                        "-w", "20", "--out", w / "run"], check=True, capture_output=True)
        import h5py
        with h5py.File(w / "run" / "snapshot_000020.h5", "r") as f:
            g = f["Step#20"]
            assert "phi" in g and float(g["phi"][:].max()) < 0, "no potential in the snapshot"
            assert float(f.attrs["param:G"]) == 1.0
        png = w / "energies.png"
        ref = w / "ref.csv"
        ref.write_text("time,ekin,epot\n0.0,0.0,-0.6667\n0.5,0.1,-0.8\n")
        p = subprocess.run([sys.executable, ENERGIES, w / "run" / "diagnostics.csv", "-o", png,
                            "--reference", ref], capture_output=True, text=True)
        assert p.returncode == 0, p.stderr
        assert "% of |E_pot(0)|" in p.stdout, p.stdout
        assert png.exists() and png.stat().st_size > 20000, png.stat().st_size
        print(p.stdout.strip())
        bad = w / "bad.csv"
        bad.write_text("a,b\n1,2\n3,4\n")
        for path, needle in ((w / "missing.csv", "no such file"), (bad, "needs the columns")):
            p = subprocess.run([sys.executable, ENERGIES, path, "-o", w / "x.png"],
                               capture_output=True, text=True)
            assert p.returncode == 2, (path, p.returncode, p.stderr)
            assert needle in p.stderr and len(p.stderr.strip().splitlines()) == 1, p.stderr
            print(f"{path.name}: exit 2: {p.stderr.strip()}")
    print("energies: passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
