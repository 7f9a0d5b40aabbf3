"""exasph snapshots in yt (4.x): one call with the run's domain, periodicity and units."""
from pathlib import Path

import numpy as np

from .errors import ExasphFileError

# yt's GADGET frontend takes the unit scales as unit_base; a run in exasph's dimensionless code
# units maps them to 1 cm, 1 g, 1 cm/s, so that yt's values equal the file's.
_UNIT_SCALES = ("UnitLength_in_cm", "UnitMass_in_g", "UnitVelocity_in_cm_per_s")


def yt_arguments(path):
    """The keyword arguments of yt.load for an exasph snapshot (format version 2): unit_base,
    bounding_box (the run's box, which need not start at 0 as GADGET's does), and whether the
    run's box is periodic on every axis."""
    import h5py

    if not Path(path).exists():
        raise ExasphFileError(f"{path}: no such file")
    with h5py.File(path, "r") as f:
        if "Header" not in f or "PartType0" not in f:
            raise ExasphFileError(f"{path}: not a GADGET-layout snapshot (format version 2); "
                                  "version 1 snapshots open in ParaView and exasph.load_snapshot")
        header = f["Header"].attrs
        unit_base = {k: float(header.get(k, 1.0)) for k in _UNIT_SCALES}
        # Specific energy in (length / time)^2 (yt's default would be (km/s)^2).
        unit_base["UnitEnergy_in_cgs"] = (unit_base["UnitMass_in_g"] *
                                          unit_base["UnitVelocity_in_cm_per_s"] ** 2)
        if "box_lo" in f.attrs:
            lo, hi = np.asarray(f.attrs["box_lo"], float), np.asarray(f.attrs["box_hi"], float)
            periodic = bool(np.all(np.asarray(f.attrs.get("periodic", [0, 0, 0])) != 0))
        else:  # another code's file: GADGET's box [0, BoxSize)
            hi = np.ones(3) * np.asarray(header["BoxSize"], float)
            lo, periodic = np.zeros(3), True
    return {"unit_base": unit_base, "bounding_box": np.stack([lo, hi], axis=1)}, periodic


def yt_load(path, **kwargs):
    """The snapshot at `path` as a yt dataset, e.g.

        ds = exasph.yt_load("run/snapshot_000100.h5")
        yt.SlicePlot(ds, "z", ("gas", "density")).save()

    Gas is particle type PartType0 (alias "gas"); yt's smoothing_length is GADGET's kernel
    support radius, 2h. `kwargs` go to yt.load (e.g. kernel_name)."""
    import yt

    from yt.utilities.logger import ytLogger

    arguments, periodic = yt_arguments(path)
    arguments.update(kwargs)
    level = ytLogger.level
    if periodic:  # yt warns that a bounding box turns periodicity off; it is turned back on
        ytLogger.setLevel(max(level, 40))
    try:
        ds = yt.load(str(path), **arguments)
    finally:
        ytLogger.setLevel(level)
    if periodic:
        ds.force_periodicity()
    return ds
