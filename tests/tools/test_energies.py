#!/usr/bin/env python3
"""tools/energies.py writes a non-trivial PNG from the diagnostics of an Evrard run (the
potential energy column is filled, the snapshot carries phi) and exits 2 with a clear message on
a missing or malformed file. tools/evrard.py puts the run beside the reference data
(tests/data/evrard) and prints the 1D computation's numbers."""
import argparse
import subprocess
import sys
import tempfile
from pathlib import Path

ENERGIES = Path(__file__).resolve().parents[2] / "tools" / "energies.py"
EVRARD = ENERGIES.parent / "evrard.py"


def check_evrard(run, w):
    p = subprocess.run([sys.executable, EVRARD, run, "-o", w / "ev"], capture_output=True,
                       text=True)
    assert p.returncode == 0, p.stderr
    one_d = "1D: E_kin peak 0.450, E_pot min -2.542, E_int peak 1.759, shock at t = 0.77: 0.126"
    assert one_d in p.stdout, p.stdout
    assert "run: E_kin peak" in p.stdout, p.stdout
    for suffix in ("energies", "profiles"):
        png = w / f"ev_{suffix}.png"
        assert png.exists() and png.stat().st_size > 20000, (png, png.stat().st_size)
    p = subprocess.run([sys.executable, EVRARD, run, "--reference", w / "nowhere"],
                       capture_output=True, text=True)
    assert p.returncode == 2 and "no such file" in p.stderr, p.stderr
    assert len(p.stderr.strip().splitlines()) == 1, p.stderr
    print(f"evrard.py: {one_d}; exit 2 without the reference data")


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
            g = f["PartType0"]
            assert "Potential" in g and float(g["Potential"][:].max()) < 0, \
                "no potential in the snapshot"
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
        check_evrard(w / "run", w)
        bad = w / "bad.csv"
        bad.write_text("a,b\n1,2\n3,4\n")
        for path, needle in ((w / "missing.csv", "no such file"), (bad, "needs the columns")):
            p = subprocess.run([sys.executable, ENERGIES, path, "-o", w / "x.png"],
                               capture_output=True, text=True)
            assert p.returncode == 2, (path, p.returncode, p.stderr)
            assert needle in p.stderr and len(p.stderr.strip().splitlines()) == 1, p.stderr
            print(f"{path.name}: exit 2: {p.stderr.strip()}")
    print("energies, evrard: passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
