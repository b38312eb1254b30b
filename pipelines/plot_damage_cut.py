#!/usr/bin/env python3
"""Damage picture of a uhpc-macro run (like the paper's Fig. 20): a thin slab through the axis
(a particle is in it when |y| < 0.55 volume^(1/3), i.e. its cell reaches y = 0, or |y| < S/2 with
--slab-mm S), plotted in the x-z plane, coloured by tensile damage and compressive damage side by
side, the sphere drawn as a circle.

usage: plot_damage_cut.py RUN_DIR [--out PNG] [--step N | --time-us T] [--slab-mm S] [--window-mm W]
                          [--radius-mm R] [--fields F1 F2]

RUN_DIR holds uhpc-macro's fields.h5 (groups step_NNNNNN with position, damage_tension,
damage_compression, volume; attribute time_s) and history.csv (sphere_x_m, sphere_y_m, sphere_z_m
per step). Without --step/--time-us the output step closest to the moment the sphere leaves the back
face (its rear surface past the exit face z = T, T from the particles of the first output step) is
drawn; when the sphere never leaves, the last output step. Writes RUN_DIR/damage_cut.png by default.
The sphere radius defaults to data/projectile.json's diameter / 2.
"""
import argparse
import csv
import json
import sys
from pathlib import Path

import h5py
import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Circle  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent


def fail(message: str) -> None:
    print(f"error: {message}", file=sys.stderr)
    sys.exit(2)


def read_history(path: Path):
    if not path.exists():
        fail(f"{path}: cannot open file (No such file or directory)")
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        fail(f"{path}: no rows")
    try:
        t = np.array([float(r["time_s"]) for r in rows])
        x = np.array([[float(r["sphere_x_m"]), float(r["sphere_y_m"]), float(r["sphere_z_m"])] for r in rows])
    except KeyError as e:
        fail(f"{path}: column {e} is missing")
    return t, x


def default_radius_m() -> float:
    p = ROOT / "data" / "projectile.json"
    try:
        return 0.5 * json.loads(p.read_text())["diameter_m"]
    except (OSError, KeyError, ValueError):
        return 0.00635


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run_dir", type=Path)
    ap.add_argument("--out", type=Path, help="PNG to write (default RUN_DIR/damage_cut.png)")
    g = ap.add_mutually_exclusive_group()
    g.add_argument("--step", type=int, help="output step index (0 = first group in fields.h5; -1 = last)")
    g.add_argument("--time-us", type=float, help="the output step closest to this time [us]")
    ap.add_argument("--slab-mm", type=float, help="fixed slab thickness in y [mm] (default: each particle's cell)")
    ap.add_argument("--window-mm", type=float, default=60.0, help="half width of the picture in x [mm] (default 60)")
    ap.add_argument("--radius-mm", type=float, help="sphere radius [mm] (default data/projectile.json)")
    ap.add_argument("--fields", nargs=2, default=["damage_tension", "damage_compression"],
                    help="the two fields side by side (default damage_tension damage_compression)")
    a = ap.parse_args()

    fields_path = a.run_dir / "fields.h5"
    if not fields_path.exists():
        fail(f"{fields_path}: cannot open file (No such file or directory)")
    t_hist, x_hist = read_history(a.run_dir / "history.csv")
    radius = a.radius_mm * 1e-3 if a.radius_mm else default_radius_m()

    with h5py.File(fields_path, "r") as f:
        steps = sorted(k for k in f if k.startswith("step_"))
        if not steps:
            fail(f"{fields_path}: no step_NNNNNN groups")
        times = np.array([float(f[k].attrs["time_s"]) for k in steps])
        first = f[steps[0]]
        for name in a.fields + ["position", "volume"]:
            if name not in first:
                fail(f"{fields_path}: no dataset '{name}' (has: {', '.join(sorted(first.keys()))})")
        x0 = first["position"][:]
        # the target spans z in [0, T] (entry face at z = 0): T = the outermost particle's cell face
        thickness = float((x0[:, 2] + 0.5 * np.cbrt(first["volume"][:])).max())

        if a.step is not None:
            if not -len(steps) <= a.step < len(steps):
                fail(f"--step {a.step}: fields.h5 has {len(steps)} output steps")
            index = a.step % len(steps)
            why = f"--step {a.step}"
        elif a.time_us is not None:
            index = int(np.argmin(np.abs(times - a.time_us * 1e-6)))
            why = f"closest to {a.time_us:g} us"
        else:
            out_of_back = np.nonzero(x_hist[:, 2] - radius > thickness)[0]
            if out_of_back.size:
                t_exit = t_hist[out_of_back[0]]
                index = int(np.argmin(np.abs(times - t_exit)))
                why = f"sphere leaves the back face at {t_exit * 1e6:.1f} us"
            else:
                index = len(steps) - 1
                why = "last output: the sphere's rear is not yet past the back face when the run ends"
        group = f[steps[index]]
        time = times[index]
        x = group["position"][:]
        size = np.cbrt(group["volume"][:])  # each particle's own spacing
        values = [group[name][:] for name in a.fields]

    sphere = np.array([np.interp(time, t_hist, x_hist[:, k]) for k in range(3)])
    # The slab: a particle is in the cut when its own cell (side volume^(1/3), 10 % slack for the rings
    # whose nearest particles sit at y = +-h/2) reaches the plane y = 0, so
    # a graded (ring) lattice keeps one particle per ring however coarse; or a fixed --slab-mm.
    half = np.full(len(x), 0.5 * a.slab_mm * 1e-3) if a.slab_mm else 0.55 * size
    window = a.window_mm * 1e-3
    cut = (np.abs(x[:, 1]) < half) & (np.abs(x[:, 0]) < window)
    slab_text = f"|y| < {a.slab_mm / 2:.2f} mm" if a.slab_mm else "|y| < 0.55 volume^(1/3)"
    if not cut.any():
        fail(f"no particle with {slab_text} within |x| < {a.window_mm:g} mm at {steps[index]}")

    z_lo = min(x[cut, 2].min(), sphere[2] - radius) - 2e-3
    z_hi = max(x[cut, 2].max(), sphere[2] + radius) + 2e-3
    fig, axes = plt.subplots(1, 2, figsize=(11, 11 * window / (z_hi - z_lo) * 0.5 + 1.2), sharey=True)
    for ax, name, v in zip(axes, a.fields, values):
        ax.set_xlim(z_lo * 1e3, z_hi * 1e3)
        ax.set_ylim(-window * 1e3, window * 1e3)
        ax.set_aspect("equal")
    fig.tight_layout()
    fig.canvas.draw()
    # marker side = each particle's spacing (volume^(1/3)) in points
    bbox = axes[0].get_window_extent()
    points_per_mm = bbox.width * 72.0 / fig.dpi / ((z_hi - z_lo) * 1e3)
    side = np.maximum(size[cut] * 1e3 * points_per_mm, 1.0)
    for ax, name, v in zip(axes, a.fields, values):
        order = np.argsort(v[cut])  # damaged particles on top
        sc = ax.scatter(x[cut, 2][order] * 1e3, x[cut, 0][order] * 1e3, c=v[cut][order], s=side[order] ** 2, marker="s",
                        cmap="jet", vmin=0.0, vmax=1.0, linewidths=0)
        ax.add_patch(Circle((sphere[2] * 1e3, sphere[0] * 1e3), radius * 1e3, fill=False, color="k", lw=1.5))
        ax.axvline(0.0, color="0.5", lw=0.5, ls=":")
        ax.axvline(thickness * 1e3, color="0.5", lw=0.5, ls=":")
        ax.set(xlabel="z (mm), flight direction", title=name.replace("_", " "))
        fig.colorbar(sc, ax=ax, shrink=0.8)
    axes[0].set_ylabel("x (mm)")
    fig.suptitle(f"{a.run_dir.name}: {steps[index]}, t = {time * 1e6:.1f} us ({why}); "
                 f"slab {slab_text}, sphere at z = {sphere[2] * 1e3:.1f} mm", fontsize=9)
    fig.tight_layout()
    out = a.out or a.run_dir / "damage_cut.png"
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=120)
    print(f"wrote {out} ({steps[index]}, t = {time * 1e6:.2f} us, {why}; {int(cut.sum())} particles in the cut)")


if __name__ == "__main__":
    main()
