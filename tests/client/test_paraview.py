#!/usr/bin/env python3
"""Issue 22: the output opened by a real visualisation client. Run by CTest (label client) as

    test_paraview.py --exe build/exasph --mpirun "mpirun ..." --out DIR

which runs exasph, then itself in `pvpython` with --check on an Xvfb display of its own
(pvpython starts MPI itself, so exasph's mpirun cannot run inside it).
A 2-rank Sedov run writes three snapshots; ParaView (Debian's python3-paraview) opens one
snapshot with each of its XDMF readers and the run's time series (snapshots.xdmf), and every
point count, field name, field range and time value is checked against h5py; a PNG of the
points coloured by Density is rendered off-screen and must show more than the background; the
grid that `exasph render` writes opens as an image holding the HDF5 grid's values.
Exits non-zero on failure.
"""
import argparse
import os
import shlex
import select
import subprocess
import sys
from pathlib import Path

import h5py
import numpy as np

if "--check" in sys.argv:  # the half that runs in pvpython
    from paraview import servermanager
    from paraview.simple import (ColorBy, CreateView, Show, ResetCamera, SaveScreenshot,
                                 XDMFReader, Xdmf3ReaderS, Xdmf3ReaderT)
    from vtkmodules.vtkIOImage import vtkPNGReader
    from vtkmodules.util.numpy_support import vtk_to_numpy

    READERS = {
        "XDMF Reader": lambda f: XDMFReader(FileNames=[f]),
        "Xdmf3 Reader S": lambda f: Xdmf3ReaderS(FileName=[f]),
        "Xdmf3 Reader T": lambda f: Xdmf3ReaderT(FileName=[f]),
    }
SKIP = {"Coordinates", "ParticleIDs"}  # positions are the points; ids are not a field


def points(reader, time=None):
    """The reader's output at `time` as (point count, {name: numpy array})."""
    reader.UpdatePipeline(time) if time is not None else reader.UpdatePipeline()
    data = servermanager.Fetch(reader)
    while data.IsA("vtkMultiBlockDataSet"):
        data = data.GetBlock(0)
    pd = data.GetPointData()
    arrays = {pd.GetArrayName(i): vtk_to_numpy(pd.GetArray(i)) for i in range(pd.GetNumberOfArrays())}
    return data.GetNumberOfPoints(), arrays, vtk_to_numpy(data.GetPoints().GetData())


def expected(h5_path, step):
    with h5py.File(h5_path, "r") as f:
        g = f["PartType0"]
        assert f["Header"].attrs["step"] == step
        fields = {k: g[k][()] for k in g.keys() if k not in SKIP}
        return float(f["Header"].attrs["Time"]), fields, g["Coordinates"][()]


def check_same(what, n, arrays, pts, fields, xyz):
    assert n == len(xyz), f"{what}: {n} points, h5py reads {len(xyz)}"
    assert set(arrays) == set(fields), f"{what}: fields {sorted(arrays)} vs {sorted(fields)}"
    for name, v in fields.items():
        lo, hi = float(arrays[name].min()), float(arrays[name].max())
        scale = max(abs(v.min()), abs(v.max()), 1e-300)
        assert abs(lo - v.min()) <= 1e-12 * scale and abs(hi - v.max()) <= 1e-12 * scale, \
            f"{what}: {name} range [{lo}, {hi}] vs h5py [{v.min()}, {v.max()}]"
    # The same points in the same order as the datasets.
    assert np.array_equal(np.asarray(pts, dtype=float), xyz), f"{what}: points differ"


def render(reader, png):
    view = CreateView("RenderView")
    view.ViewSize = [480, 360]
    shown = Show(reader, view)
    ColorBy(shown, ("POINTS", "Density"))
    shown.SetScalarBarVisibility(view, True)
    ResetCamera(view)
    SaveScreenshot(str(png), view, ImageResolution=[480, 360])
    image = vtkPNGReader()
    image.SetFileName(str(png))
    image.Update()
    pixels = vtk_to_numpy(image.GetOutput().GetPointData().GetScalars())
    colours = {tuple(p[:3]) for p in pixels}
    # Background, points in a colour map, a colour bar and its labels: many colours.
    assert len(colours) > 50, f"{png}: only {len(colours)} colours, nothing rendered?"
    return len(colours)


def check(run, out):
    steps = [2, 4, 6]
    for name, make in READERS.items():
        t, fields, xyz = expected(run / "snapshot_000004.h5", 4)
        n, arrays, pts = points(make(str(run / "snapshot_000004.xdmf")))
        check_same(f"{name}, snapshot 4", n, arrays, pts, fields, xyz)
        series = make(str(run / "snapshots.xdmf"))
        times = [expected(run / f"snapshot_{s:06d}.h5", s)[0] for s in steps]
        assert list(series.TimestepValues) == times, (name, list(series.TimestepValues), times)
        for s, t in zip(steps, times):
            n, arrays, pts = points(series, t)
            _, fields, xyz = expected(run / f"snapshot_{s:06d}.h5", s)
            check_same(f"{name}, series at t = {t}", n, arrays, pts, fields, xyz)
        print(f"{name}: {n} points, {len(arrays)} fields, times {times}: as h5py reads them")
    colours = render(XDMFReader(FileNames=[str(run / "snapshots.xdmf")]), out / "rho.png")
    print(f"rendered {out / 'rho.png'}: {colours} colours")
    check_render_grid(out / "slice")


def check_render_grid(prefix):
    """`exasph render`'s XDMF opens as an image of the HDF5 grid's size and values, in order."""
    with h5py.File(f"{prefix}.h5", "r") as f:
        image = f["image"][()]
    for name, make in READERS.items():
        reader = make(f"{prefix}.xdmf")
        reader.UpdatePipeline()
        data = servermanager.Fetch(reader)
        while data.IsA("vtkMultiBlockDataSet"):
            data = data.GetBlock(0)
        values = vtk_to_numpy(data.GetPointData().GetArray("rho"))
        assert data.GetNumberOfPoints() == image.size, (name, data.GetNumberOfPoints())
        assert np.array_equal(values, image.ravel()), f"{name}: values or their order differ"
        print(f"{name}: render grid {image.shape[1]} x {image.shape[0]} as h5py reads it")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--exe")
    ap.add_argument("--mpirun")
    ap.add_argument("--out", required=True)
    ap.add_argument("--check", action="store_true", help="(in pvpython) check DIR/run")
    a = ap.parse_args()
    out = Path(a.out)
    run = out / "run"
    if a.check:
        check(run, out)
        # Leave without VTK's teardown: closing the render window under Xvfb raises an X error
        # (GLXBadContext) after everything has passed.
        sys.stdout.flush()
        os._exit(0)
    subprocess.run(shlex.split(a.mpirun) + ["-np", "2", a.exe, "--init", "sedov", "-n", "12",
                                            "-s", "6", "-w", "2", "--threads", "1", "--out",
                                            str(run)], check=True, capture_output=True)
    subprocess.run([a.exe, "render", str(run / "snapshot_000006.h5"), "--resolution", "64",
                    "--out", str(out / "slice")], check=True, capture_output=True)
    return under_fresh_xvfb(["pvpython", __file__, "--check", "--out", str(out)])


def under_xvfb(cmd):
    """cmd with DISPLAY on an Xvfb of its own, access control off, stopped at the end. Xvfb picks
    a free display number and writes it to a pipe (-displayfd) once it accepts connections: no
    race with other X servers starting beside it (xvfb-run -a once found no server under ctest
    -j2), and no guess of when the server is ready (a display number from the process id, with a
    wait for its socket, still met "bad X server connection" once under load)."""
    read_end, write_end = os.pipe()
    xvfb = subprocess.Popen(["Xvfb", "-displayfd", str(write_end), "-screen", "0",
                             "1280x1024x24", "-nolisten", "tcp", "-ac"], pass_fds=(write_end,),
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    os.close(write_end)
    try:
        ready, _, _ = select.select([read_end], [], [], 60)
        number = os.read(read_end, 32).decode().strip() if ready else ""
        assert number.isdigit() and xvfb.poll() is None, \
            f"Xvfb gave no display within 60 s (exit status {xvfb.poll()})"
        # llvmpipe on one thread: the render beside another test once crashed in its threads
        env = {**os.environ, "DISPLAY": f":{number}", "LP_NUM_THREADS": "1"}
        p = subprocess.run(cmd, env=env, capture_output=True, text=True)
        print(p.stdout, end="")
        print(p.stderr, end="", file=sys.stderr)
        x_failed = "bad X server connection" in p.stderr or "Loguru caught a signal" in p.stderr
        return p.returncode, x_failed
    finally:
        os.close(read_end)
        xvfb.terminate()
        xvfb.wait()


def under_fresh_xvfb(cmd, tries=3):
    """under_xvfb, again on a new server when the render could not connect to the one it had
    or crashed in the GL stack (seen under ctest -j2 and beside a busy job: "bad X server
    connection" right after the server reported itself ready, once a SIGSEGV inside
    StillRender); a failed check (an assertion, exit status 1 without a signal) counts at once."""
    for attempt in range(tries):
        status, no_connection = under_xvfb(cmd)
        if status == 0 or not no_connection:
            return status
        print(f"the render lost its X server or crashed (attempt {attempt + 1} of {tries})",
              file=sys.stderr)
    return status


if __name__ == "__main__":
    sys.exit(main())
