"""Snapshots and checkpoints (/state). Snapshots of format version 2 (root attribute
format_version) are in the GADGET layout: /Header and the gas in /PartType0, vectors as N x 3
(Coordinates, Velocities, Acceleration), scalars under GADGET names (Masses, InternalEnergy,
SmoothingLength = 2h, Density, Pressure, Potential) or exasph's (du, nc, ...), ids in ParticleIDs.
Version 1 (no format_version) had group Step#N with one 1-D dataset per field. Both read into the
same Snapshot, keyed by exasph's field names; GADGET-layout files of other codes read too."""
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .errors import ExasphFileError


def _open(path):
    import h5py

    if not Path(path).exists():
        raise ExasphFileError(f"{path}: no such file")
    try:
        return h5py.File(path, "r")
    except OSError as exc:
        raise ExasphFileError(f"{path}: not a readable HDF5 file ({exc})") from None


# GADGET-layout datasets that hold exasph fields: name -> (the fields, in columns; stored scale).
# SmoothingLength is GADGET's kernel support radius, 2h (include/exasph/io/gadget_layout.hpp).
GADGET_DATASETS = {
    "Coordinates": (("x", "y", "z"), 1.0),
    "Velocities": (("vx", "vy", "vz"), 1.0),
    "Acceleration": (("ax", "ay", "az"), 1.0),
    "Masses": (("m",), 1.0),
    "InternalEnergy": (("u",), 1.0),
    "SmoothingLength": (("h",), 2.0),
    "Density": (("rho",), 1.0),
    "Pressure": (("p",), 1.0),
    "Potential": (("phi",), 1.0),
}


def is_gadget_layout(f):
    """A file in the GADGET layout (format version 2 snapshots, other codes' files)."""
    return "Header" in f and "PartType0" in f


def particle_group(f, step=None):
    """The /state group of a checkpoint, /PartType0 of a GADGET-layout file, else the group
    Step#`step` of a version-1 snapshot (the last one when step is None), else the root of an
    initial-conditions file."""
    if "state" in f:
        return f["state"]
    if is_gadget_layout(f):
        return f["PartType0"]
    steps = sorted((int(k[5:]) for k in f.keys() if k.startswith("Step#")))
    if not steps and "x" in f:
        return f["/"]
    if not steps:
        raise ExasphFileError(f"{f.filename}: no Step#N group (not an exasph snapshot)")
    if step is None:
        step = steps[-1]
    if step not in steps:
        raise ExasphFileError(f"{f.filename}: no step {step} (steps: {steps})")
    return f[f"Step#{step}"]


def _attribute(v):
    if isinstance(v, bytes):
        return v.decode()
    if isinstance(v, np.ndarray) and v.size == 1 and v.dtype.kind in "iuf":
        return v.reshape(()).item()
    return v.item() if isinstance(v, np.generic) else v


@dataclass
class Snapshot:
    """One snapshot's particles: `fields` maps each 1-D dataset's name to a float64 array (ids
    as uint64 in `id`), in the file's order; `units` the symbolic unit of each field; `attrs`
    the run's attributes (parameters as `param:KEY`, `units`, `box_lo`, `box_hi`, `periodic`,
    `gamma`, `code_version`)."""

    path: str
    step: int
    time: float
    dt: float
    fields: dict
    units: dict
    attrs: dict = field(default_factory=dict)
    id: np.ndarray = None

    @property
    def n(self):
        return len(next(iter(self.fields.values())))

    @property
    def gamma(self):
        return float(self.attrs.get("gamma", 5.0 / 3.0))

    @property
    def case(self):
        return str(self.attrs.get("param:init", ""))

    def positions(self):
        return np.stack([self.fields["x"], self.fields["y"], self.fields["z"]], axis=1)

    def radius(self, centre=(0.0, 0.0, 0.0)):
        d = self.positions() - np.asarray(centre, dtype=float)
        return np.sqrt(np.sum(d * d, axis=1))

    def radial_velocity(self, centre=(0.0, 0.0, 0.0)):
        d = self.positions() - np.asarray(centre, dtype=float)
        r = np.sqrt(np.sum(d * d, axis=1))
        v = np.stack([self.fields["vx"], self.fields["vy"], self.fields["vz"]], axis=1)
        return np.where(r > 0, np.sum(d * v, axis=1) / np.maximum(r, 1e-300), 0.0)

    def require(self, *names):
        missing = [k for k in names if k not in self.fields and not (k == "id" and
                                                                      self.id is not None)]
        if missing:
            raise ExasphFileError(f"{self.path}: snapshot lacks the fields {', '.join(missing)} "
                                  "(write them with -f)")
        return self


def _gadget_columns(g):
    """{exasph field: (dataset, column, scale)} of a /PartType0 group."""
    out = {}
    for name in g.keys():
        if name == "ParticleIDs":
            continue
        names, scale = GADGET_DATASETS.get(name, ((name,), 1.0))
        for col, field_name in enumerate(names):
            out[field_name] = (name, col, scale)
    return out


def _selected(names, fields, path, g):
    """The field names to read: `fields` and x, y, z (all when fields is None)."""
    if fields is None:
        return names
    wanted = set(fields) | {"x", "y", "z"}
    missing = sorted(wanted - set(names))
    if missing:
        raise ExasphFileError(f"{path}: no datasets {', '.join(missing)} in {g.name}")
    return [k for k in names if k in wanted]


def _load_gadget(f, path, step, fields):
    g, header = f["PartType0"], f["Header"]
    columns = _gadget_columns(g)
    if step is not None and int(header.attrs.get("step", -1)) != step:
        raise ExasphFileError(f"{path}: no step {step} (step: {int(header.attrs.get('step', -1))})")
    names = list(columns)
    names = _selected(names, fields, path, g)
    data, units, read = {}, {}, {}
    for k in names:
        dataset, col, scale = columns[k]
        if dataset not in read:
            read[dataset] = np.asarray(g[dataset][()], dtype=float)
        v = read[dataset]
        data[k] = (v[:, col] if v.ndim == 2 else v) / scale
        if f"unit:{dataset}" in g.attrs:
            units[k] = _attribute(g.attrs[f"unit:{dataset}"])
    attrs = {k: _attribute(v) for k, v in f.attrs.items()}
    ids = np.asarray(g["ParticleIDs"][()], dtype=np.uint64) if "ParticleIDs" in g else None
    return Snapshot(str(path), int(header.attrs.get("step", -1)),
                    float(header.attrs.get("Time", 0.0)), float(header.attrs.get("dt", 0.0)),
                    data, units, attrs, ids)


def load_snapshot(path, step=None, fields=None):
    """The particles of a snapshot (its last step, or `step`), of a checkpoint or of an
    initial-conditions file, in either snapshot format version; `fields` limits the fields read
    (x, y, z are always read)."""
    with _open(path) as f:
        if is_gadget_layout(f):
            return _load_gadget(f, path, step, fields)
        g = particle_group(f, step)
        names = [k for k in g.keys() if getattr(g[k], "ndim", 0) == 1 and k != "id"]
        names = _selected(names, fields, path, g)
        data = {k: np.asarray(g[k][()], dtype=float) for k in names}
        for k in ("x", "y", "z"):
            if k not in data:
                raise ExasphFileError(f"{path}: no dataset {k} in {g.name}")
        units = {k: _attribute(g.attrs[f"unit:{k}"]) for k in names if f"unit:{k}" in g.attrs}
        attrs = {k: _attribute(v) for k, v in f.attrs.items()}
        ids = np.asarray(g["id"][()], dtype=np.uint64) if "id" in g else None
        step_no = int(g.attrs.get("step", -1)) if "step" in g.attrs else -1
        return Snapshot(str(path), step_no, float(g.attrs.get("time", f.attrs.get("time", 0.0))),
                        float(g.attrs.get("dt", 0.0)), data, units, attrs, ids)

