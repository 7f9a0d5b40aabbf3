"""The communication record of a run (DIR/comm_matrix.csv, written with --comm-report): one
row per rank, peer and kind of traffic (halo, migration, gravity)."""
from pathlib import Path

import numpy as np

from .errors import ExasphFileError

TRAFFIC = ("halo", "migration", "gravity")
COLUMNS = ("rank", "peer", "traffic", "sent_messages", "sent_bytes", "received_messages",
           "received_bytes", "sent_bytes_per_step")


def load_comm_matrix(path, traffic="halo", value="sent_bytes_per_step"):
    """The ranks x ranks matrix of one kind of traffic from a run's folder or its
    comm_matrix.csv: entry [i, j] is `value` (a column name) of rank i towards peer j."""
    path = Path(path)
    if path.is_dir():
        path = path / "comm_matrix.csv"
    if not path.exists():
        raise ExasphFileError(f"{path}: no such file (run exasph with --comm-report)")
    if traffic not in TRAFFIC:
        raise ExasphFileError(f"traffic must be one of {', '.join(TRAFFIC)}, got {traffic!r}")
    lines = path.read_text().splitlines()
    if not lines or tuple(lines[0].split(",")) != COLUMNS:
        raise ExasphFileError(f"{path}: not an exasph comm_matrix.csv (header {COLUMNS})")
    if value not in COLUMNS[3:]:
        raise ExasphFileError(f"value must be one of {', '.join(COLUMNS[3:])}, got {value!r}")
    rows = [ln.split(",") for ln in lines[1:] if ln]
    if any(len(r) != len(COLUMNS) for r in rows):
        raise ExasphFileError(f"{path}: a row without {len(COLUMNS)} fields")
    try:
        nranks = 1 + max([int(r[0]) for r in rows] + [int(r[1]) for r in rows], default=0)
        m = np.zeros((nranks, nranks))
        col = COLUMNS.index(value)
        for r in rows:
            if r[2] == traffic:
                m[int(r[0]), int(r[1])] = float(r[col])
    except ValueError as exc:
        raise ExasphFileError(f"{path}: malformed number ({exc})") from None
    return m
