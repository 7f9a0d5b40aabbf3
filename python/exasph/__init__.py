"""Reading exasph output in Python: snapshots and checkpoints (any rank count's file), the
diagnostics table, radial profiles, and the exact solutions that `exasph exact` computes.

    import exasph
    s = exasph.load_snapshot("run/snapshot_000100.h5")      # s.fields["rho"], s.time, s.units
    d = exasph.load_diagnostics("run")                        # d["time"], d["etot"], ...
    r, rho, n = exasph.radial_profile(s.radius(), s.fields["rho"], bins=100, rmax=0.5)
    ex = exasph.exact_solution("sedov", s.time, gamma=s.gamma)  # ex["r"], ex["rho"], ...
    m = exasph.load_comm_matrix("run", "halo")                # ranks x ranks, bytes per step
    ds = exasph.yt_load("run/snapshot_000100.h5")             # yt dataset (needs yt 4.x)

Errors in the files raise ExasphFileError with one line naming the file and the problem.
"""
from .comm_matrix import load_comm_matrix
from .diagnostics import load_diagnostics
from .errors import ExasphFileError
from .exact import exact_solution, find_exasph
from .profiles import binned_mean, radial_profile
from .snapshot import Snapshot, load_snapshot, particle_group
from .yt_support import yt_load

__all__ = ["ExasphFileError", "Snapshot", "binned_mean", "exact_solution", "find_exasph",
           "load_comm_matrix", "load_diagnostics", "load_snapshot", "particle_group",
           "radial_profile", "yt_load"]
