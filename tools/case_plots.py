#!/usr/bin/env python3
"""Figures and numbers of the slab and contact validation cases from exasph snapshots, as PNG.

    /usr/bin/python3 tools/case_plots.py gresho SNAP [SNAP ...] -o gresho.png
    /usr/bin/python3 tools/case_plots.py kh SNAP [SNAP ...] -o kh.png [--label A --label B]
    /usr/bin/python3 tools/case_plots.py slice SNAP [SNAP ...] -o slices.png [--field rho]
    /usr/bin/python3 tools/case_plots.py wind SNAP [SNAP ...] -o wind.png [--label A --label B]
    /usr/bin/python3 tools/case_plots.py turb SNAP [SNAP ...] -o turb.png [--label A --label B]
    /usr/bin/python3 tools/case_plots.py square SNAP [SNAP ...] -o square.png

gresho: v_phi against radius (particles, binned mean, analytic profile) of the last snapshot,
and L1(v_phi)/v0 of every snapshot (printed; plotted against time when there are several).
kh: the McNally et al. (2012) mode amplitude of every snapshot against time (one curve per
directory of snapshots, labelled with --label). slice: particles of a thin slice (|z - z_mid|
below one smoothing length) of each snapshot, coloured by a field. wind: the wind-cloud test's
surviving cloud fraction (cloud particles with rho >= 0.64 rho_cloud and u <= 0.9 u_wind,
Agertz et al. 2007, with the run's --param values) against t / tau_KH, one curve per
directory. turb: driven turbulence's rms Mach number against time (from the diagnostics.csv
beside each directory's snapshots: v_rms about the mean velocity over the sound speed of the
mean internal energy) and the velocity power spectrum E(k) of each directory's last snapshot
(volume-weighted cloud-in-cell deposit on a grid of about one cell per particle spacing).
square: the rotating square patch (issue 17): a top view of the layer nearest z = 0 coloured by
pressure for each snapshot, and L_z(t) and E_tot(t) relative to t = 0 from the diagnostics.csv
beside the snapshots; prints, per snapshot, |v_z| / max|v_xy| (median and maximum) and the
closest pair in units of the initial spacing (periodic in z). Exits 2 with one line on a
missing or malformed snapshot.
"""
import argparse
import sys
from pathlib import Path


def fail(msg, code=2):
    print(f"case_plots.py: {msg}", file=sys.stderr)
    sys.exit(code)


try:
    import h5py
    import numpy as np
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "python"))
    import exasph
except ImportError as exc:  # pragma: no cover
    fail(f"needs numpy, h5py and matplotlib ({exc}); on Debian: apt-get install "
         "python3-numpy python3-h5py python3-matplotlib (and run /usr/bin/python3)")


def read_snapshot(path, need):
    try:
        snap = exasph.load_snapshot(path).require(*need)
    except exasph.ExasphFileError as exc:
        fail(str(exc))
    data = {k: snap.id if k == "id" else snap.fields[k] for k in need}
    data["time"] = snap.time
    data["box_lo"] = np.asarray(snap.attrs.get("box_lo", [0, 0, 0]), dtype=float)
    data["box_hi"] = np.asarray(snap.attrs.get("box_hi", [1, 1, 1]), dtype=float)
    return data


def gresho_vphi(r, v0=1.0, r1=0.2):
    s = r / r1
    return v0 * np.where(s < 1, s, np.where(s < 2, 2 - s, 0.0))


def gresho(args):
    rows = []
    for path in args.snapshots:
        d = read_snapshot(path, ["x", "y", "vx", "vy"])
        r = np.hypot(d["x"], d["y"])
        keep = (r < 0.5) & (r > 0)
        vphi = (d["x"] * d["vy"] - d["y"] * d["vx"])[keep] / r[keep]
        l1 = np.mean(np.abs(vphi - gresho_vphi(r[keep])))
        rows.append((d["time"], l1, r[keep], vphi))
        print(f"{path}: t = {d['time']:.4f}, L1(v_phi)/v0 = {l1:.4f}")
    t, l1, r, vphi = rows[-1]
    fig, axes = plt.subplots(1, 2 if len(rows) > 1 else 1, figsize=(11 if len(rows) > 1 else 6, 4))
    ax = axes[0] if len(rows) > 1 else axes
    ax.plot(r, vphi, ",", color="0.6", label="particles")
    edges = np.linspace(0, 0.5, 51)
    idx = np.digitize(r, edges) - 1
    mean = [vphi[idx == b].mean() if np.any(idx == b) else np.nan for b in range(50)]
    ax.plot(0.5 * (edges[1:] + edges[:-1]), mean, "o-", ms=3, label="binned mean")
    rr = np.linspace(0, 0.5, 500)
    ax.plot(rr, gresho_vphi(rr), "k--", label="analytic")
    ax.set(xlabel="r", ylabel="v_phi", title=f"{args.title} t = {t:.2f}, L1 = {l1:.4f}")
    ax.legend()
    if len(rows) > 1:
        axes[1].plot([q[0] for q in rows], [q[1] for q in rows], "o-")
        axes[1].set(xlabel="t", ylabel="L1(v_phi) / v0", title="L1 against time")
    fig.tight_layout()
    fig.savefig(args.output, dpi=110)


def mode_amplitude(d):
    x, y, vy = d["x"], d["y"], d["vy"]
    w = np.exp(-4 * np.pi * np.abs(np.where(y < 0.5, y, 1 - y) - 0.25))
    vol = d["m"] / d["rho"]
    s = np.sum(vol * vy * np.sin(4 * np.pi * x) * w)
    c = np.sum(vol * vy * np.cos(4 * np.pi * x) * w)
    n = np.sum(vol * w)
    return 2 * np.hypot(s / n, c / n)


def kh(args):
    fig, ax = plt.subplots(figsize=(6, 4))
    for label, paths in group_by_directory(args.snapshots, args.label):
        pts = sorted((d["time"], mode_amplitude(d)) for d in
                     (read_snapshot(p, ["x", "y", "vy", "m", "rho"]) for p in paths))
        for t, a in pts:
            print(f"{label}: t = {t:.3f}, mode amplitude {a:.4f}")
        ax.semilogy([p[0] for p in pts], [p[1] for p in pts], "o-", ms=3, label=label)
    ax.set(xlabel="t", ylabel="mode amplitude (McNally et al. 2012)", title=args.title)
    ax.legend()
    fig.tight_layout()
    fig.savefig(args.output, dpi=110)


def group_by_directory(paths, labels):
    groups = {}
    for path in paths:
        groups.setdefault(str(Path(path).parent), []).append(path)
    labels = labels or list(groups)
    if len(labels) != len(groups):
        fail(f"{len(groups)} directories of snapshots but {len(labels)} --label")
    return zip(labels, groups.values())


def case_parameters(path, defaults):
    """The case parameters a snapshot's run used: defaults overridden by its --param values."""
    text = h5py.File(path, "r").attrs.get("case_params", "")
    values = dict(defaults)
    for kv in (text.decode() if isinstance(text, bytes) else str(text)).split():
        key, _, value = kv.partition("=")
        if key in values:
            values[key] = float(value)
    return values


WIND_CLOUD_DEFAULTS = {"contrast": 10.0, "u_wind": 1.5, "radius": 0.025, "v_wind": 2.7}


def wind(args):
    fig, ax = plt.subplots(figsize=(6, 4))
    for label, paths in group_by_directory(args.snapshots, args.label):
        pts = []
        for p in paths:
            w = case_parameters(p, WIND_CLOUD_DEFAULTS)
            contrast, u_wind = w["contrast"], w["u_wind"]
            tau_kh = 1.6 * 2 * w["radius"] * np.sqrt(contrast) / w["v_wind"]
            d = read_snapshot(p, ["id", "rho", "u"])
            side = int(h5py.File(p, "r").attrs.get("param:side", 0))
            cloud = d["id"] >= 4 * side ** 3
            alive = cloud & (d["rho"] >= 0.64 * contrast) & (d["u"] <= 0.9 * u_wind)
            pts.append((d["time"] / tau_kh, alive.sum() / max(cloud.sum(), 1)))
        pts.sort()
        for t, f in pts:
            print(f"{label}: t = {t:.2f} tau_KH, surviving fraction {f:.3f}")
        ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-", ms=3, label=label)
    ax.set(xlabel="t / tau_KH", ylabel="surviving cloud fraction", title=args.title, ylim=(0, 1.1))
    ax.legend()
    fig.tight_layout()
    fig.savefig(args.output, dpi=110)


def mach_history(csv, gamma, mass):
    if not Path(csv).exists():
        fail(f"{csv}: no such file (turb reads the diagnostics.csv beside the snapshots)")
    d = np.genfromtxt(csv, delimiter=",", names=True)
    # v_rms^2 = 2 E_kin / M - |P / M|^2; c_s^2 = gamma (gamma - 1) E_int / M
    v2 = 2 * d["ekin"] / mass - (d["px"] ** 2 + d["py"] ** 2 + d["pz"] ** 2) / mass ** 2
    return d["time"], np.sqrt(np.maximum(v2, 0) / (gamma * (gamma - 1) * d["eint"] / mass))


def velocity_spectrum(d):
    n = max(8, int(round(len(d["m"]) ** (1 / 3))))
    lo, length = d["box_lo"], d["box_hi"] - d["box_lo"]
    vol = d["m"] / d["rho"]
    weight = np.zeros((n, n, n))
    mom = np.zeros((3, n, n, n))
    s = np.stack([(d[a] - lo[k]) / length[k] * n - 0.5 for k, a in enumerate("xyz")])
    i0 = np.floor(s).astype(int)
    f = s - i0
    for corner in range(8):
        o = [(corner >> k) & 1 for k in range(3)]
        w = vol * np.prod([f[k] if o[k] else 1 - f[k] for k in range(3)], axis=0)
        idx = tuple((i0[k] + o[k]) % n for k in range(3))
        np.add.at(weight, idx, w)
        for k, a in enumerate(("vx", "vy", "vz")):
            np.add.at(mom[k], idx, w * d[a])
    v = mom / np.maximum(weight, 1e-300)
    v -= v.mean(axis=(1, 2, 3), keepdims=True)
    power = sum(np.abs(np.fft.fftn(c) / n ** 3) ** 2 for c in v)
    kk = np.fft.fftfreq(n, 1.0 / n)
    kmag = np.sqrt(sum(q ** 2 for q in np.meshgrid(kk, kk, kk, indexing="ij")))
    shells = np.rint(kmag).astype(int)
    spec = np.bincount(shells.ravel(), weights=power.ravel())
    k = np.arange(len(spec))
    keep = (k >= 1) & (k <= n // 2)
    return k[keep], 0.5 * spec[keep]


def turb(args):
    fig, (ax_m, ax_e) = plt.subplots(1, 2, figsize=(11, 4))
    for label, paths in group_by_directory(args.snapshots, args.label):
        last = max(paths, key=lambda p: read_snapshot(p, [])["time"])
        gamma = float(h5py.File(last, "r").attrs.get("gamma", 1.001))
        d = read_snapshot(last, ["x", "y", "z", "vx", "vy", "vz", "m", "rho"])
        t, mach = mach_history(Path(last).parent / "diagnostics.csv", gamma, d["m"].sum())
        late = t >= 0.5 * t[-1]
        print(f"{label}: Mach_rms {mach[-1]:.3f} at t = {t[-1]:.2f}; mean over "
              f"t >= {0.5 * t[-1]:.2f}: {mach[late].mean():.3f} (min {mach[late].min():.3f}, "
              f"max {mach[late].max():.3f})")
        ax_m.plot(t, mach, label=label)
        k, e = velocity_spectrum(d)
        print(f"{label}: E(k) at t = {d['time']:.2f}: " +
              ", ".join(f"k={a} {b:.2e}" for a, b in zip(k, e)))
        ax_e.loglog(k, e, "o-", ms=3, label=f"{label}, t = {d['time']:.1f}")
    ax_m.set(xlabel="t", ylabel="rms Mach number", title=args.title)
    ax_e.set(xlabel="k L / 2 pi", ylabel="E(k)", title="velocity power spectrum")
    kref = np.array([2.0, 8.0])
    ax_e.loglog(kref, 0.5 * e[1] * (kref / 2) ** (-5 / 3), "k--", lw=0.8, label="k^-5/3")
    for ax in (ax_m, ax_e):
        ax.legend()
    fig.tight_layout()
    fig.savefig(args.output, dpi=110)


def closest_pair(x, y, z, period, block=512):
    best = np.inf
    for i in range(0, len(x), block):
        dx = x[i:i + block, None] - x[None, :]
        dy = y[i:i + block, None] - y[None, :]
        dz = np.abs(z[i:i + block, None] - z[None, :])
        dz = np.minimum(dz, period - dz)
        d2 = dx * dx + dy * dy + dz * dz
        d2[np.arange(d2.shape[0]), np.arange(i, i + d2.shape[0])] = np.inf
        best = min(best, d2.min())
    return np.sqrt(best)


def square(args):
    n = len(args.snapshots)
    fig, axes = plt.subplots(1, n + 1, figsize=(4.2 * n + 5, 4), squeeze=False)
    for ax, path in zip(axes[0], args.snapshots):
        d = read_snapshot(path, ["x", "y", "z", "vx", "vy", "vz", "p"])
        side = int(h5py.File(path, "r").attrs.get("param:side", 0))
        if side < 2:
            fail(f"{path}: no param:side attribute (not a square-patch snapshot)")
        period = d["box_hi"][2] - d["box_lo"][2]
        vxy = np.hypot(d["vx"], d["vy"]).max()
        ratio = np.abs(d["vz"]) / vxy
        closest = closest_pair(d["x"], d["y"], d["z"], period) / (period / side)
        print(f"t = {d['time']:.4f}: |v_z|/max|v_xy| median {np.median(ratio):.3e} max "
              f"{ratio.max():.3e}; closest pair {closest:.3f} of the spacing")
        layer = d["z"][np.argmin(np.abs(d["z"]))]
        keep = np.abs(d["z"] - layer) < 0.25 * period / side
        sc = ax.scatter(d["x"][keep], d["y"][keep], c=d["p"][keep], s=args.size, cmap="viridis",
                        linewidths=0)
        ax.set_aspect("equal")
        ax.set(xlabel="x [cm]", ylabel="y [cm]", title=f"t = {d['time']:.2f} s, z = {layer:.1f}")
        fig.colorbar(sc, ax=ax, label="P [Ba]", shrink=0.8)
    csv = Path(args.snapshots[0]).parent / "diagnostics.csv"
    if not csv.exists():
        fail(f"{csv}: no such file (square reads the diagnostics.csv beside the snapshots)")
    h = np.genfromtxt(csv, delimiter=",", names=True)
    lz = 100 * (h["lz"] / h["lz"][0] - 1)
    et = 100 * (h["etot"] / h["etot"][0] - 1)
    print(f"L_z: worst {np.abs(lz).max():.3f} % of L_z(0) = {h['lz'][0]:.4e}, at the end "
          f"{lz[-1]:+.3f} %; E_tot at the end {et[-1]:+.3f} % (t = {h['time'][-1]:.4f})")
    ax = axes[0][n]
    ax.plot(h["time"], lz, label="L_z")
    ax.plot(h["time"], et, label="E_tot = E_kin + sum m u")
    ax.axhspan(-0.2, 0.2, color="0.9", label="0.2 %")
    ax.set(xlabel="t [s]", ylabel="change since t = 0 [%]")
    ax.legend()
    fig.suptitle(args.title)
    fig.tight_layout()
    fig.savefig(args.output, dpi=110)


def slice_plot(args):
    n = len(args.snapshots)
    fig, axes = plt.subplots(1, n, figsize=(4.2 * n + 0.8, 4), squeeze=False)
    for ax, path in zip(axes[0], args.snapshots):
        d = read_snapshot(path, ["x", "y", "z", "h", args.field])
        zmid = 0.5 * (d["box_lo"][2] + d["box_hi"][2])
        keep = np.abs(d["z"] - zmid) < np.median(d["h"])
        sc = ax.scatter(d["x"][keep], d["y"][keep], c=d[args.field][keep], s=args.size,
                        cmap="viridis", linewidths=0)
        ax.set_aspect("equal")
        ax.set(xlabel="x", ylabel="y", title=f"t = {d['time']:.2f}")
        fig.colorbar(sc, ax=ax, label=args.field, shrink=0.8)
    fig.suptitle(args.title)
    fig.tight_layout()
    fig.savefig(args.output, dpi=110)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = ap.add_subparsers(dest="command", required=True)
    for name, fn in (("gresho", gresho), ("kh", kh), ("slice", slice_plot), ("wind", wind),
                     ("turb", turb), ("square", square)):
        p = sub.add_parser(name)
        p.add_argument("snapshots", nargs="+")
        p.add_argument("-o", "--output", required=True, help="PNG file")
        p.add_argument("--title", default="")
        p.set_defaults(run=fn)
        if name in ("kh", "wind", "turb"):
            p.add_argument("--label", action="append", help="one per directory of snapshots")
        if name == "slice":
            p.add_argument("--field", default="rho")
        if name in ("slice", "square"):
            p.add_argument("--size", type=float, default=2.0, help="marker size")
    args = ap.parse_args()
    args.run(args)


if __name__ == "__main__":
    main()
