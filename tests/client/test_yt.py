#!/usr/bin/env python3
"""Issue 62: a snapshot opened by yt (Debian's python3-yt, 4.1). Run by CTest (label client) as

    test_yt.py --exe build/exasph --mpirun "mpirun ..." --out DIR

A 2-rank Sedov run (-n 30, to the case's end time 0.09) writes its last snapshot in the GADGET
layout; exasph.yt_load opens it, and
- the particle count, positions, velocities, density, smoothing lengths and internal energy yt
  reads equal h5py's values (matched by ParticleIDs), in the units the run states;
- yt's SPH projection of density along z at 256 x 256 over an off-centre square agrees with
  `exasph render --project` on the same square to <= 2 % (L1 over pixels / mean);
- the shock radius read from a yt slice through the centre (the maximum of the azimuthally
  averaged density, at the time the density was computed) lies within 3 % of the exact Sedov
  solution's.
Exits non-zero on failure.
"""
import argparse
import shlex
import subprocess
import sys
from pathlib import Path

import h5py
import numpy as np

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "python"))
import exasph  # noqa: E402
import yt  # noqa: E402

yt.set_log_level(40)
REGION = (-0.45, 0.25, -0.3, 0.4)  # x and y ranges of the projection: off-centre, square
PIXELS = 256


def run_sedov(a, out):
    cmd = shlex.split(a.mpirun) + ["-np", "2", a.exe, "--init", "sedov", "-n", "30",
                                   "--threads", "1", "-w", "0.09", "--out", str(out)]
    subprocess.run(cmd, check=True, capture_output=True, text=True)
    snaps = sorted(out.glob("snapshot_*.h5"))
    assert snaps, f"{out}: no snapshot"
    return snaps[-1]


def by_id(ids, values):
    return values[np.argsort(ids, kind="stable")]


def check_fields(ds, path):
    """What yt reads is what h5py reads, in the run's units (code units: cm, g, s)."""
    ad = ds.all_data()
    with h5py.File(path, "r") as f:
        g = f["PartType0"]
        ids = g["ParticleIDs"][()]
        n = len(ids)
        assert f.attrs["units"] == "code units", f.attrs["units"]
        expect = {
            ("PartType0", "Coordinates"): (g["Coordinates"][()], "cm"),
            ("PartType0", "Velocities"): (g["Velocities"][()], "cm/s"),
            ("PartType0", "density"): (g["Density"][()], "g/cm**3"),
            ("PartType0", "smoothing_length"): (g["SmoothingLength"][()], "cm"),
            ("PartType0", "specific_thermal_energy"): (g["InternalEnergy"][()], "cm**2/s**2"),
            ("PartType0", "Masses"): (g["Masses"][()], "g"),
        }
        t_file = f["Header"].attrs["Time"]
    yt_ids = ad["PartType0", "ParticleIDs"].d.astype(np.uint64)
    assert len(yt_ids) == n and ds.particle_type_counts["PartType0"] == n, (len(yt_ids), n)
    assert np.array_equal(np.sort(yt_ids), np.sort(ids))
    for field, (values, unit) in expect.items():
        got = by_id(yt_ids, ad[field].to(unit).d)
        want = by_id(ids, values)
        assert got.shape == want.shape, (field, got.shape, want.shape)
        worst = np.max(np.abs(got - want)) / np.max(np.abs(want))
        assert worst <= 1e-14, f"{field}: yt differs from h5py by {worst:.3e} (relative)"
    assert abs(ds.current_time.to("s").d - t_file) <= 1e-15 * t_file, (ds.current_time, t_file)
    print(f"yt reads {n} particles; positions, velocities, density, smoothing length, internal "
          f"energy and mass equal h5py's; t = {t_file}")


def check_projection(ds, path, a, out):
    x0, x1, y0, y1 = REGION
    prefix = out / "render_projection"
    subprocess.run([a.exe, "render", str(path), "--project", "--field", "rho", "--resolution",
                    str(PIXELS), "--region", *map(str, REGION), "--out", str(prefix)],
                   check=True, capture_output=True, text=True)
    with h5py.File(f"{prefix}.h5", "r") as f:
        mine = f["image"][()]
    centre = [(x0 + x1) / 2, (y0 + y1) / 2, 0.0]
    prj = yt.ProjectionPlot(ds, "z", ("gas", "density"), center=centre, width=x1 - x0,
                            buff_size=(PIXELS, PIXELS))
    theirs = np.array(prj.frb["gas", "density"].to("g/cm**2").d)
    assert theirs.shape == mine.shape, (theirs.shape, mine.shape)
    l1 = np.abs(theirs - mine).mean() / np.abs(mine).mean()
    # The same picture mirrored would be far off: the region is off-centre.
    mirrored = np.abs(theirs.T - mine).mean() / np.abs(mine).mean()
    print(f"projection of density along z, {PIXELS}^2 over x {x0}..{x1}, y {y0}..{y1}: "
          f"L1(yt - exasph render) / mean = {l1:.4f} (transposed: {mirrored:.4f})")
    assert l1 <= 0.02, l1
    prj.save(str(out / "yt_projection.png"))


def check_shock(ds, path, exe, out):
    sl = yt.SlicePlot(ds, "z", ("gas", "density"), center=[0.0, 0.0, 0.0],
                      buff_size=(512, 512))
    image = np.array(sl.frb["gas", "density"].to("g/cm**3").d)
    width = float(ds.domain_width[0].to("cm").d)
    side = image.shape[0]
    centres = ((np.arange(side) + 0.5) / side - 0.5) * width
    r = np.hypot(*np.meshgrid(centres, centres))
    edges = np.linspace(0.0, 0.5 * width, 101)
    bin_of = np.digitize(r.ravel(), edges) - 1
    profile = np.array([image.ravel()[bin_of == k].mean() for k in range(100)])
    mid = 0.5 * (edges[1:] + edges[:-1])
    k = int(np.argmax(profile))
    # The peak between bins: the vertex of the parabola through the three bins around it.
    p0, p1, p2 = profile[k - 1:k + 2]
    r_peak = mid[k] + 0.5 * (mid[1] - mid[0]) * (p0 - p2) / (p0 - 2 * p1 + p2)
    s = exasph.load_snapshot(path, fields=[])
    t_rho = s.time - s.dt  # the density was computed from the positions before the last update
    ex = exasph.exact_solution("sedov", t_rho, gamma=s.gamma, exasph=exe)
    r_shock = ex["r"][int(np.argmax(ex["rho"]))]
    error = r_peak / r_shock - 1
    print(f"yt slice through the centre: density peak at r = {r_peak:.4f}, exact shock at "
          f"{r_shock:.4f} (t = {t_rho:.5f}): {100 * error:+.2f} %")
    assert abs(error) <= 0.03, error
    sl.save(str(out / "yt_slice.png"))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--exe", required=True)
    ap.add_argument("--mpirun", required=True)
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    path = run_sedov(a, out / "run")
    ds = exasph.yt_load(path)
    assert ds.periodicity == (True, True, True), ds.periodicity
    check_fields(ds, path)
    check_projection(ds, path, a, out)
    check_shock(ds, path, a.exe, out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
