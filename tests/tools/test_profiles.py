#!/usr/bin/env python3
"""tools/profiles.py writes a non-trivial PNG from a Sedov snapshot and exits 2 with a clear
message on a missing or malformed file."""
import argparse
import subprocess
import sys
import tempfile
from pathlib import Path

PROFILES = Path(__file__).resolve().parents[2] / "tools" / "profiles.py"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--exe", required=True)
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as w:
        w = Path(w)
        subprocess.run([args.exe, "--init", "sedov", "-n", "16", "--lattice", "-s", "10",
                        "-w", "10", "--out", w / "run"], check=True, capture_output=True)
        snap = w / "run" / "snapshot_000010.h5"
        png = w / "profile.png"
        p = subprocess.run([sys.executable, PROFILES, snap, "-o", png, "--exasph", args.exe],
                           capture_output=True, text=True)
        assert p.returncode == 0, p.stderr
        assert png.exists() and png.stat().st_size > 20000, png.stat().st_size
        print(f"profile PNG {png.stat().st_size} bytes")
        bad = w / "bad.h5"
        bad.write_bytes(b"not hdf5" * 100)
        subprocess.run([args.exe, "--init", "sedov", "-n", "16", "--lattice", "-s", "1", "-w", "1",
                        "-f", "rho", "--out", w / "few"], check=True, capture_output=True)
        for path, needle in ((w / "missing.h5", "no such file"), (bad, "not a readable HDF5"),
                             (w / "few" / "snapshot_000001.h5", "lacks the fields")):
            p = subprocess.run([sys.executable, PROFILES, path, "-o", w / "x.png", "--exasph",
                                args.exe], capture_output=True, text=True)
            assert p.returncode == 2, (path, p.returncode, p.stderr)
            assert needle in p.stderr and len(p.stderr.strip().splitlines()) == 1, p.stderr
            print(f"{path.name}: exit 2: {p.stderr.strip()}")
    print("profiles: passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
