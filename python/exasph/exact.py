"""The exact solutions (Sedov-Taylor, Noh) computed by `exasph exact`."""
import shutil
import subprocess
from pathlib import Path

import numpy as np

from .errors import ExasphFileError

COLUMNS = ("r", "rho", "v", "p", "u")


def find_exasph(given=None):
    """The exasph binary: `given`, the repository's build/exasph, or exasph on PATH."""
    if given:
        return str(given)
    here = Path(__file__).resolve().parent.parent.parent / "build" / "exasph"
    if here.exists():
        return str(here)
    found = shutil.which("exasph")
    if found:
        return found
    raise ExasphFileError("cannot find the exasph binary (build it, or pass its path)")


def exact_solution(problem, t, gamma=5.0 / 3.0, rmax=0.5, points=2000, exasph=None):
    """The exact profiles of `problem` (sedov or noh) at time t: a dict of arrays r, rho, v
    (radial velocity), p, u."""
    cmd = [find_exasph(exasph), "exact", problem, "--t", repr(float(t)), "--gamma",
           repr(float(gamma)), "--rmax", repr(float(rmax)), "--points", str(int(points))]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        raise ExasphFileError(f"'{' '.join(cmd)}' failed: {p.stderr.strip()}")
    rows = np.array([list(map(float, ln.split())) for ln in p.stdout.splitlines()
                     if ln.strip() and not ln.startswith("#")])
    return {name: rows[:, k] for k, name in enumerate(COLUMNS)}
