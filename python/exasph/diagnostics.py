"""The diagnostics table (DIR/diagnostics.csv: one row per step, one column per quantity)."""
from pathlib import Path

import numpy as np

from .errors import ExasphFileError


def load_diagnostics(path, need=("step", "time")):
    """The table of a run (its folder or the CSV file) as a numpy structured array: columns by
    name (d["time"], d["etot"], ...), one row per step. `need` names columns that must exist."""
    path = Path(path)
    if path.is_dir():
        path = path / "diagnostics.csv"
    if not path.exists():
        raise ExasphFileError(f"{path}: no such file")
    lines = [ln for ln in path.read_text().splitlines() if ln and not ln.startswith("#")]
    if not lines:
        raise ExasphFileError(f"{path}: empty")
    try:
        data = np.genfromtxt(lines, delimiter=",", names=True, dtype=float)
    except ValueError as exc:
        raise ExasphFileError(f"{path}: malformed CSV ({str(exc).splitlines()[0]})") from None
    if data.dtype.names is None:
        raise ExasphFileError(f"{path}: no header line (not an exasph diagnostics.csv)")
    missing = [c for c in need if c not in data.dtype.names]
    if missing:
        raise ExasphFileError(f"{path}: needs the columns {', '.join(missing)} "
                              "(an exasph diagnostics.csv)")
    return np.atleast_1d(data)
