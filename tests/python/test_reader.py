#!/usr/bin/env python3
"""The Python reader (python/exasph, issue 22) against a 3-rank run: snapshots, a checkpoint,
the diagnostics table, the communication matrix (issue 23), radial profiles, the exact solution,
its errors, and a pip install of the folder. Run by CTest as  test_reader.py --exe build/exasph --mpirun "mpirun ..."."""
import argparse
import shlex
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import h5py
import numpy as np

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "python"))
import exasph  # noqa: E402


def expect_error(needle, fn, *args, **kw):
    try:
        fn(*args, **kw)
    except exasph.ExasphFileError as exc:
        assert needle in str(exc) and "\n" not in str(exc), str(exc)
        return
    raise AssertionError(f"{fn.__name__}{args} raised nothing")


def check_snapshot(run):
    """A snapshot (format version 2, the GADGET layout) reads into exasph's field names."""
    path = run / "snapshot_000004.h5"
    s = exasph.load_snapshot(path)
    with h5py.File(path, "r") as f:
        assert f.attrs["format_version"] == 2
        g, header = f["PartType0"], f["Header"]
        assert s.n == 1000 and s.step == 4 and s.time == header.attrs["Time"], (s.n, s.step, s.time)
        assert list(header.attrs["NumPart_Total"]) == [1000, 0, 0, 0, 0, 0]
        for name, dataset, col in (("x", "Coordinates", 0), ("z", "Coordinates", 2),
                                   ("vx", "Velocities", 0), ("ay", "Acceleration", 1)):
            assert np.array_equal(s.fields[name], g[dataset][:, col]), name
        for name, dataset in (("rho", "Density"), ("u", "InternalEnergy"), ("p", "Pressure"),
                              ("m", "Masses"), ("du", "du")):
            assert np.array_equal(s.fields[name], g[dataset][()]), name
        # GADGET's SmoothingLength is the kernel's support radius, 2h.
        assert np.array_equal(s.fields["h"], g["SmoothingLength"][()] / 2)
        assert np.array_equal(s.id, g["ParticleIDs"][()])
    assert sorted(s.id.tolist()) == list(range(1000)), "ids not a permutation"
    assert "id" not in s.fields and "Coordinates" not in s.fields
    assert s.units["rho"] == "mass/length^3" and s.units["vx"] == "length/time", s.units
    assert s.units["h"] == "length", s.units
    assert s.attrs["param:side"] == 10 and s.case == "sedov" and abs(s.gamma - 5 / 3) < 1e-12
    assert len(s.attrs["box_lo"]) == 3
    part = exasph.load_snapshot(path, fields=["rho"])
    assert set(part.fields) == {"x", "y", "z", "rho"}, set(part.fields)
    expect_error("no step 3", exasph.load_snapshot, path, step=3)
    expect_error("no datasets nosuch", exasph.load_snapshot, path, fields=["nosuch"])
    expect_error("lacks the fields alpha", s.require, "rho", "alpha")
    # The checkpoint of the same step holds the same particles (matched by id).
    c = exasph.load_snapshot(run / "checkpoint_000004.h5")
    a, b = np.argsort(s.id), np.argsort(c.id)
    for name in ("x", "vz", "h", "u", "m"):
        assert np.array_equal(s.fields[name][a], c.fields[name][b]), name
    print(f"snapshot: {s.n} particles, {len(s.fields)} fields, t = {s.time:.4g}; checkpoint agrees")
    return s


def check_previous_layout(exe, w):
    """A snapshot of format version 1 (group Step#N, a 1-D dataset per field; tests/data keeps
    216 particles of a -n 30 Sedov snapshot that exasph wrote before version 2) still reads, in
    Python and in `exasph render`."""
    path = ROOT / "tests" / "data" / "snapshot_v1_sedov.h5"
    s = exasph.load_snapshot(path)
    with h5py.File(path, "r") as f:
        assert "format_version" not in f.attrs
        g = f["Step#86"]
        assert s.n == 216 and s.step == 86 and s.time == g.attrs["time"], (s.n, s.step, s.time)
        for k in ("x", "vy", "h", "rho", "u"):
            assert np.array_equal(s.fields[k], g[k][()]), k
        assert np.array_equal(s.id, g["id"][()])
    assert s.units["rho"] == "mass/length^3" and "xyz" not in s.fields
    prefix = w / "v1_rho"
    res = subprocess.run([exe, "render", str(path), "--project", "--resolution", "32", "--out",
                          str(prefix)], capture_output=True, text=True)
    assert res.returncode == 0, res.stderr
    with h5py.File(f"{prefix}.h5", "r") as f:
        image = f["image"][()]
        assert f.attrs["time"] == s.time, f.attrs["time"]
    # The column density integrates to the particles' mass (all well inside the box).
    mass = image.sum() * (1.0 / 32) ** 2
    assert abs(mass / s.fields["m"].sum() - 1) < 0.02, (mass, s.fields["m"].sum())
    print(f"format version 1: {s.n} particles, {len(s.fields)} fields; render {image.shape}")


def check_diagnostics(run, w):
    d = exasph.load_diagnostics(run)
    assert len(d) == 4 and list(d["step"]) == [1, 2, 3, 4], d["step"]
    assert abs(d["etot"][-1] / d["etot"][0] - 1) < 1e-3, d["etot"]
    expect_error("no such file", exasph.load_diagnostics, w / "nowhere")
    (w / "bad.csv").write_text("a,b\n1,2\n")
    expect_error("needs the columns step, time", exasph.load_diagnostics, w / "bad.csv")
    print(f"diagnostics: {len(d)} rows, {len(d.dtype.names)} columns")


def check_profiles(s, exe):
    r = np.random.default_rng(1).uniform(0, 1, 100000)
    centres, mean, count = exasph.radial_profile(r, 2 * r, bins=10, rmax=1.0)
    assert count.sum() == r.size and np.all(np.abs(mean - 2 * centres) < 0.01), mean
    ex = exasph.exact_solution("sedov", 0.05, gamma=5 / 3, rmax=0.5, points=2000, exasph=exe)
    k = int(np.argmax(ex["rho"]))
    # The strong shock's compression (gamma + 1) / (gamma - 1) = 4 at the shock radius 0.3475.
    assert 3.9 < ex["rho"][k] <= 4 + 1e-9 and abs(ex["r"][k] - 0.3475) < 0.002, (ex["rho"][k],
                                                                                ex["r"][k])
    expect_error("failed", exasph.exact_solution, "nosuch", 0.05, exasph=exe)
    rp, rho, _ = exasph.radial_profile(s.radius(), s.fields["rho"], bins=20, rmax=0.5)
    assert np.nanmax(rho) > 1.0, rho
    print(f"profiles: exact Sedov peak {ex['rho'][k]:.4f} at r = {ex['r'][k]:.4f}")


def check_comm_matrix(run, w, out):
    """--comm-report (issue 23): what each rank sent is what its peers received; the tool draws
    it; the summary names the peers."""
    assert "communication: halo peers per rank mean 2.0 max 2;" in out, out[-600:]
    for kind in ("halo", "migration"):
        sent = exasph.load_comm_matrix(run, kind, "sent_bytes")
        received = exasph.load_comm_matrix(run, kind, "received_bytes")
        assert sent.shape == (3, 3), sent.shape
        assert np.array_equal(sent, received.T), (kind, sent, received)
        assert np.all(np.diag(sent) == 0), sent
    assert exasph.load_comm_matrix(run, "halo").min() >= 0
    assert np.count_nonzero(exasph.load_comm_matrix(run, "halo")) == 6
    png = w / "matrix.png"
    res = subprocess.run([sys.executable, str(ROOT / "tools" / "comm_matrix.py"), str(run), "-o",
                          str(png)], capture_output=True, text=True)
    assert res.returncode == 0 and png.stat().st_size > 1000, res.stderr
    assert res.stdout.startswith("3 ranks, halo peers per rank mean 2.00 max 2"), res.stdout
    expect_error("no such file", exasph.load_comm_matrix, w / "nothing")
    expect_error("traffic must be one of", exasph.load_comm_matrix, run, "email")
    bad = w / "bad.csv"
    bad.write_text("step,time\n1,2\n")
    expect_error("not an exasph comm_matrix.csv", exasph.load_comm_matrix, bad)
    res = subprocess.run([sys.executable, str(ROOT / "tools" / "comm_matrix.py"), str(bad)],
                         capture_output=True, text=True)
    assert res.returncode == 2 and res.stderr.count("\n") == 1, res.stderr


def check_import_from_repo():
    """`python3 -c "import exasph"` in the repository's root (exasph -> python/exasph)."""
    p = subprocess.run([sys.executable, "-c", "import exasph; print(exasph.load_snapshot)"],
                       cwd=ROOT, env={}, capture_output=True, text=True)
    assert p.returncode == 0 and "function load_snapshot" in p.stdout, (p.stdout, p.stderr)


def check_pip_install(w):
    """pip installs the folder (from a copy: a build leaves build/ and egg-info behind)."""
    target, source = w / "site", w / "python"
    shutil.copytree(ROOT / "python", source, ignore=shutil.ignore_patterns("__pycache__"))
    subprocess.run([sys.executable, "-m", "pip", "install", "--quiet", "--no-index",
                    "--no-deps", "--no-build-isolation", "--target", str(target), str(source)],
                   check=True, capture_output=True)
    p = subprocess.run([sys.executable, "-c", "import exasph; print(exasph.__file__)"],
                       env={"PYTHONPATH": str(target)}, capture_output=True, text=True, cwd=w)
    assert p.returncode == 0 and str(target) in p.stdout, (p.stdout, p.stderr)
    print(f"pip install python/: imported from {p.stdout.strip()}")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--exe", required=True)
    ap.add_argument("--mpirun", required=True)
    a = ap.parse_args()
    with tempfile.TemporaryDirectory() as w:
        w = Path(w)
        run = w / "run"
        out = subprocess.run(shlex.split(a.mpirun) + ["-np", "3", a.exe, "--init", "sedov", "-n",
                             "10", "--lattice", "-s", "4", "-w", "2", "--checkpoint-every", "4",
                             "--threads", "1", "--comm-report", "--out", str(run)],
                             check=True, capture_output=True, text=True).stdout
        check_comm_matrix(run, w, out)
        s = check_snapshot(run)
        check_previous_layout(a.exe, w)
        check_diagnostics(run, w)
        check_profiles(s, a.exe)
        check_import_from_repo()
        check_pip_install(w)
    return 0


if __name__ == "__main__":
    sys.exit(main())
