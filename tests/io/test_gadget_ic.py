#!/usr/bin/python3
"""Issue 62, criterion 2: initial conditions in the GADGET HDF5 layout of other codes.

The files are written here with h5py from the layout's documentation (a /Header group with
NumPart_Total, NumPart_Total_HighWord, MassTable, BoxSize, Time; /PartType0 with Coordinates and
Velocities as N x 3, Masses, InternalEnergy, SmoothingLength (GADGET's h: the kernel's support
radius, 2h in exasph's notation), ParticleIDs), not by exasph.
- Sedov from such a file (the built-in case's particles, moved into [0, 1)) equals, after 5
  steps, on 1 and 2 ranks, with derived fields in double: the same particles in exasph's own
  layout to 1e-12 of each field's scale, and the built-in Sedov to 1e-12 in every field but the
  velocities. Those the move by 0.5 changes at the rounding of the positions (ulp(0.9) = 1.1e-16
  instead of ~1e-18 near 0), which the Press scheme's v = (x_n - x_{n-1}) / dt carries divided
  by dt = 1e-6: measured 5.6e-11 after step 2 (1e-7 of |v|max); bounded here by 8 eps / dt0;
- MassTable instead of Masses gives the same run; a file without SmoothingLength runs;
- a second particle type, and eight malformed files, each end with one line and exit 2.

Usage: test_gadget_ic.py --exe build/exasph --mpirun "mpirun ..." (OMP_NUM_THREADS=1)
"""
import argparse
import os
import pathlib
import shlex
import subprocess
import sys
import tempfile

import h5py
import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "python"))
import exasph  # noqa: E402

SIDE = 10
STEPS = 5
SHIFT = 0.5  # the built-in Sedov's box is [-0.5, 0.5); GADGET's starts at 0


class Runner:
    def __init__(self, exe, mpirun, work):
        self.exe, self.mpirun, self.work = exe, mpirun, work

    def run(self, ranks, *args, expect=0):
        cmd = [self.exe, *map(str, args)]
        if ranks > 1:
            cmd = [*self.mpirun, "-np", str(ranks), *cmd]
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
        if p.returncode != expect:
            raise AssertionError(f"{' '.join(cmd)} exited {p.returncode}, expected {expect}:\n"
                                 f"{p.stdout[-2000:]}\n{p.stderr[-2000:]}")
        return p


def builtin_state(r, case="sedov"):
    """A built-in case's initial particles (its checkpoint of step 0)."""
    out = r.work / f"{case}0"
    r.run(1, "--init", case, "-n", SIDE, "--param", "dt0=1e-6", "-s", 0,
          "--checkpoint-every", 1, "--out", out)
    with h5py.File(out / "checkpoint_000000.h5", "r") as f:
        g = f["state"]
        return {k: g[k][()] for k in ("x", "y", "z", "vx", "vy", "vz", "m", "h", "u", "id")}


def write_gadget(path, s, mass_table=False, smoothing=True, mutate=None, shift=SHIFT):
    """A GADGET-layout file of state s; `mutate(f, header, datasets)` breaks it before writing."""
    n = s["x"].size
    pos = np.stack([s["x"], s["y"], s["z"]], axis=1) + shift
    data = {"Coordinates": pos, "Velocities": np.stack([s["vx"], s["vy"], s["vz"]], axis=1),
            "InternalEnergy": s["u"], "ParticleIDs": s["id"].astype(np.uint64)}
    if not mass_table:
        data["Masses"] = s["m"]
    if smoothing:
        data["SmoothingLength"] = 2 * s["h"]  # GADGET's h: the kernel's support radius
    header = {"NumPart_Total": np.array([n, 0, 0, 0, 0, 0], dtype=np.uint32),
              "NumPart_ThisFile": np.array([n, 0, 0, 0, 0, 0], dtype=np.int32),
              "NumPart_Total_HighWord": np.zeros(6, dtype=np.uint32),
              "MassTable": np.array([s["m"][0] if mass_table else 0.0] + [0.0] * 5),
              "BoxSize": 1.0, "Time": 0.0, "NumFilesPerSnapshot": 1}
    with h5py.File(path, "w") as f:
        if mutate:
            mutate(f, header, data)
        if not header.pop("skip", False):
            h = f.create_group("Header")
            for k, v in header.items():
                h.attrs[k] = v
        g = f.require_group("PartType0")
        for k, v in data.items():
            if k not in g:
                g[k] = v


def particles(snapshot, step, shift=0.0, wrap=True):
    """Fields of a snapshot by particle id, positions moved back by `shift` (and, with `wrap`,
    into the periodic image in [-0.5, 0.5])."""
    snap = exasph.load_snapshot(snapshot, step=step)
    order = np.argsort(snap.id)
    out = {k: snap.fields[k][order] for k in ("x", "y", "z", "vx", "vy", "vz", "u", "h", "rho")}
    for k in "xyz":
        out[k] = out[k] - shift
        if wrap:
            out[k] -= np.round(out[k])
    return out


def expect_same(a, b, rtol, what, velocity_tol=None):
    """Every field within rtol of its scale; velocities within velocity_tol if given."""
    for k in a:
        scale = max(np.abs(a[k]).max(), np.abs(b[k]).max(), 1e-300)
        diff = np.abs(a[k] - b[k]).max()
        if velocity_tol is not None and k in ("vx", "vy", "vz"):
            assert diff <= velocity_tol, f"{what}: {k} differs by {diff:.3g} > {velocity_tol:.3g}"
        else:
            assert diff <= rtol * scale, f"{what}: {k} differs by {diff / scale:.3g} of its scale"
    print(f"{what}: every field within {rtol} of its scale" +
          (f", velocities within {velocity_tol:.2g}" if velocity_tol else ""))


def write_own_layout(path, s):
    """The same particles in exasph's own layout (docs/file-format.md), box [0, 1)."""
    with h5py.File(path, "w") as f:
        f.attrs["box_lo"], f.attrs["box_hi"], f.attrs["periodic"] = [0.0] * 3, [1.0] * 3, [1] * 3
        f.attrs["gamma"], f.attrs["dt0"] = 5 / 3, 1e-6
        for k in ("x", "y", "z"):
            f[k] = s[k] + SHIFT
        for k in ("vx", "vy", "vz", "m", "h", "u", "id"):
            f[k] = s[k]


def test_runs(r, state):
    def run(name, ranks, *init):
        out = r.work / name
        r.run(ranks, "--init", *init, "-s", STEPS, "-w", STEPS, "--double-precision", "--out", out)
        return out / f"snapshot_{STEPS:06d}.h5"

    builtin = particles(run("builtin", 1, "sedov", "-n", SIDE, "--param", "dt0=1e-6"), STEPS)
    own = r.work / "own_layout.h5"
    write_own_layout(own, state)
    own_run = particles(run("own", 1, own), STEPS, SHIFT)
    masses = r.work / "masses.hdf5"
    write_gadget(masses, state)
    table = r.work / "mass_table.hdf5"
    write_gadget(table, state, mass_table=True)
    v_tol = 8 * np.finfo(float).eps / 1e-6
    for name, path, ranks in (("Masses", masses, 1), ("Masses, 2 ranks", masses, 2),
                              ("MassTable", table, 1)):
        got = particles(run(f"gadget_{ranks}_{path.stem}", ranks, path), STEPS, SHIFT)
        expect_same(own_run, got, 1e-12, f"GADGET file ({name}) vs own layout, {STEPS} steps")
        expect_same(builtin, got, 1e-12, f"GADGET file ({name}) vs built-in Sedov", v_tol)
    no_h = r.work / "no_smoothing_length.hdf5"
    write_gadget(no_h, state, smoothing=False)
    out = r.work / "run_no_h"
    r.run(1, "--init", no_h, "-s", STEPS, "-w", STEPS, "--out", out)
    got = particles(out / f"snapshot_{STEPS:06d}.h5", STEPS, SHIFT)
    assert np.all(np.isfinite(got["rho"])) and abs(np.median(got["rho"]) - 1.0) < 0.05, \
        np.median(got["rho"])
    print(f"no SmoothingLength: ran, median density {np.median(got['rho']):.4f} (1 expected)")


def test_open_box(r):
    """--open-box: Noh (an open case) from a GADGET file without BoxSize, in open boundaries
    around its particles, equals the built-in Noh after 5 steps (the box only orders the
    particles along the curve: round-off); without --open-box the file is refused (no BoxSize),
    and --open-box on a test case or an exasph-layout file is refused."""
    noh = builtin_state(r, "noh")

    def no_box(f, h, d):
        del h["BoxSize"]

    path = r.work / "noh_open.hdf5"
    write_gadget(path, noh, mutate=no_box, shift=0.0)
    out = r.work / "noh_gadget_open"
    r.run(2, "--init", path, "--open-box", "-s", STEPS, "-w", STEPS, "--double-precision",
          "--out", out)
    got = exasph.load_snapshot(out / f"snapshot_{STEPS:06d}.h5")
    assert not any(got.attrs["periodic"]), got.attrs["periodic"]
    ref_out = r.work / "noh_builtin"
    r.run(1, "--init", "noh", "-n", SIDE, "--param", "dt0=1e-6", "-s", STEPS, "-w", STEPS,
          "--double-precision", "--out", ref_out)
    builtin = particles(ref_out / f"snapshot_{STEPS:06d}.h5", STEPS, wrap=False)
    mine = particles(out / f"snapshot_{STEPS:06d}.h5", STEPS, wrap=False)
    expect_same(builtin, mine, 1e-10, f"Noh from a GADGET file, --open-box, 2 ranks, {STEPS} steps")
    expect_one_line(r, path, "BoxSize", "no BoxSize, no --open-box")
    p = r.run(1, "--init", "sedov", "--open-box", "-s", 1, "--out", r.work / "refused", expect=2)
    assert "--open-box: only for initial conditions from a GADGET-layout file" in p.stderr
    own = r.work / "own_for_open.h5"
    write_own_layout(own, noh)
    p = r.run(1, "--init", own, "--open-box", "-s", 1, "--out", r.work / "refused", expect=2)
    assert "states its box" in p.stderr and p.stderr.strip().count("\n") == 0, p.stderr
    print("--open-box: Noh equals the built-in one; refused without it, on a case, on own layout")


def test_units(r, state):
    """Unit scales stated by the file (GADGET-4's /Parameters, SWIFT's /Units) become the run's
    units: the root attribute `units` and /Header's Unit*_in_* of its snapshots."""
    kpc, msun10, kms = 3.0856775814913673e21, 1.98841e43, 1e5

    def gadget4(f, h, d):
        p = f.create_group("Parameters")
        p.attrs["UnitLength_in_cm"], p.attrs["UnitMass_in_g"] = kpc, msun10
        p.attrs["UnitVelocity_in_cm_per_s"] = kms

    def swift(f, h, d):
        u = f.create_group("Units")
        u.attrs["Unit length in cgs (U_L)"] = np.array([kpc])
        u.attrs["Unit mass in cgs (U_M)"] = np.array([msun10])
        u.attrs["Unit time in cgs (U_t)"] = np.array([kpc / kms])
        u.attrs["Unit current in cgs (U_I)"] = np.array([1.0])

    for name, mutate in (("GADGET-4 /Parameters", gadget4), ("SWIFT /Units", swift)):
        path = r.work / f"units_{mutate.__name__}.hdf5"
        write_gadget(path, state, mutate=mutate)
        out = r.work / f"units_{mutate.__name__}"
        r.run(1, "--init", path, "-s", 1, "-w", 1, "--out", out)
        with h5py.File(out / "snapshot_000001.h5", "r") as f:
            h = f["Header"].attrs
            assert f.attrs["units"].startswith("GADGET units: UnitLength_in_cm="), f.attrs["units"]
            got = (h["UnitLength_in_cm"], h["UnitMass_in_g"], h["UnitVelocity_in_cm_per_s"])
            assert np.allclose(got, (kpc, msun10, kms), rtol=1e-15, atol=0), got
            assert abs(h["UnitTime_in_s"] / (kpc / kms) - 1) < 1e-15, h["UnitTime_in_s"]
        print(f"units from {name}: {got}, stated in the snapshot's /Header")


def malformed():
    """Each case: (name, mutate, words the one line must contain)."""
    def no_header(f, h, d):
        h["skip"] = True

    def count(f, h, d):
        h["NumPart_Total"] = h["NumPart_Total"] + np.array([1, 0, 0, 0, 0, 0], dtype=np.uint32)

    def nan(f, h, d):
        d["Coordinates"] = d["Coordinates"].copy()
        d["Coordinates"][17, 1] = np.nan

    def shape(f, h, d):
        d["Coordinates"] = d["Coordinates"][:, :2].copy()

    def zero_mass(f, h, d):
        d["Masses"] = d["Masses"].copy()
        d["Masses"][3] = 0.0

    def negative_u(f, h, d):
        d["InternalEnergy"] = d["InternalEnergy"].copy()
        d["InternalEnergy"][8] = -1.0

    def small_box(f, h, d):
        h["BoxSize"] = 0.5

    def second_type(f, h, d):
        h["NumPart_Total"] = np.array([h["NumPart_Total"][0], 64, 0, 0, 0, 0], dtype=np.uint32)
        f.create_group("PartType1")["Coordinates"] = np.zeros((64, 3))

    return [("missing Header", no_header, "/Header"),
            ("N mismatch", count, "NumPart_Total"),
            ("NaN in Coordinates", nan, "not finite"),
            ("wrong shape", shape, "N x 3"),
            ("zero mass", zero_mass, "must be positive"),
            ("negative u", negative_u, "must not be negative"),
            ("BoxSize below the extent", small_box, "outside the periodic box"),
            ("second particle type", second_type, "PartType1 (64)")]


def test_refused(r, state):
    for name, mutate, words in malformed():
        path = r.work / f"bad_{name.replace(' ', '_')}.hdf5"
        write_gadget(path, state, mutate=mutate)
        expect_one_line(r, path, words, name)
    text = r.work / "not_hdf5.hdf5"
    text.write_text("PartType0 Coordinates\n" * 20)
    expect_one_line(r, text, "not an HDF5 file", "not HDF5")


def expect_one_line(r, path, words, name):
    p = r.run(1, "--init", path, "-s", 1, "--out", r.work / "refused", expect=2)
    lines = [s for s in p.stderr.splitlines() if s.strip()]
    assert len(lines) == 1 and words in lines[0], f"{name}: stderr {p.stderr!r}"
    assert not (r.work / "refused" / "snapshot_000000.h5").exists()
    print(f"{name}: exit 2, '{lines[0]}'")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--exe", required=True)
    ap.add_argument("--mpirun", required=True)
    a = ap.parse_args()
    os.environ.setdefault("OMP_NUM_THREADS", "1")
    with tempfile.TemporaryDirectory() as tmp:
        r = Runner(a.exe, shlex.split(a.mpirun), pathlib.Path(tmp))
        state = builtin_state(r)
        test_runs(r, state)
        test_refused(r, state)
        test_open_box(r)
        test_units(r, state)
    print("GADGET-layout initial conditions: all checks passed")


if __name__ == "__main__":
    sys.exit(main())
