"""Radial profiles: particle quantities averaged in radial bins."""
import numpy as np


def binned_mean(r, q, edges):
    """The mean of q over the particles with edges[k] <= r < edges[k+1], and their counts
    (NaN where a bin is empty)."""
    r, q = np.asarray(r, dtype=float), np.asarray(q, dtype=float)
    nb = len(edges) - 1
    idx = np.digitize(r, edges) - 1
    ok = (idx >= 0) & (idx < nb)
    count = np.bincount(idx[ok], minlength=nb)
    total = np.bincount(idx[ok], weights=q[ok], minlength=nb)
    return np.where(count > 0, total / np.maximum(count, 1), np.nan), count


def radial_profile(r, q, bins=100, rmax=None):
    """(bin centres, mean of q per bin, particles per bin) for `bins` equal bins in [0, rmax]
    (rmax: the largest r by default)."""
    r = np.asarray(r, dtype=float)
    rmax = float(r.max()) if rmax is None else float(rmax)
    edges = np.linspace(0.0, rmax, bins + 1)
    mean, count = binned_mean(r, q, edges)
    return 0.5 * (edges[1:] + edges[:-1]), mean, count
