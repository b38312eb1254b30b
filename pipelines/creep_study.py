#!/usr/bin/env python3
"""What resists a slow sphere: the force on it over time and the state of the material in front of it.

usage: creep_study.py RUN_DIR [RUN_DIR ...] --out DIR [--ahead-mm 15]

For each uhpc-macro run (result.json, history.csv, fields.h5 of an AFC target) and each field output:
the sphere's depth (centre below the entry face z = 0), axial velocity, the axial contact force on it
(the only force on the rigid sphere: its sum over the particles in contact) and how many particles
touch it, averaged over the history rows since the last output; and two groups of particles:
  ahead: lateral distance from the sphere's flight line < 2 R, axial distance from its centre in
         [0, R + ahead-mm]: the material the sphere must push;
  ring:  lateral distance in [R, 3 R] and behind the sphere's front (axial distance < R): the wall of
         the hole beside it.
Per group: the count, the share with d+ >= 0.999, the median density ratio rho/rho0 (V0/V, V0 from the
first output), the median pressure and d-, the share that carries no stress (|P| and q below 1 kPa)
and the median axial velocity. Writes DIR/creep.md, DIR/creep.json and DIR/creep.png.
"""
import argparse
import csv
import json
import pathlib

import h5py
import numpy as np

NO_STRESS_PA = 1e3


def history(run):
    with open(run / "history.csv") as f:
        rows = list(csv.DictReader(f))
    cols = ("time_s", "sphere_z_m", "sphere_vz_m_s", "contact_force_z_N", "contact_particles")
    return {c: np.array([float(r[c]) for r in rows]) for c in cols}


def group_stats(mask, d_plus, d_minus, rho, p, q, vz):
    n = int(mask.sum())
    if n == 0:
        return {"count": 0}
    med = lambda a: float(np.median(a[mask]))  # noqa: E731
    return {"count": n, "share_d_plus_1": float((d_plus[mask] >= 0.999).mean()),
            "density_ratio_median": med(rho), "density_ratio_min": float(rho[mask].min()),
            "pressure_median_MPa": med(p) / 1e6, "d_minus_median": med(d_minus),
            "share_no_stress": float(((np.abs(p[mask]) < NO_STRESS_PA) & (q[mask] < NO_STRESS_PA)).mean()),
            "axial_velocity_median_m_s": med(vz)}


def study(run, ahead_mm):
    run = pathlib.Path(run)
    result = json.loads((run / "result.json").read_text())
    radius = result["inputs"]["projectile"]["radius_m"]
    h = history(run)
    rows = []
    with h5py.File(run / "fields.h5", "r") as f, h5py.File(run / "sphere.h5", "r") as s:
        steps = sorted(k for k in f.keys() if k.startswith("step_"))
        v0 = f[steps[0]]["volume"][...]
        t_last = -1.0
        for k in steps:
            g, sg = f[k], s[k]
            t = float(g.attrs["time_s"])
            xs = sg["position"][0]
            x = g["position"][...]
            rel = x - xs
            lateral = np.hypot(rel[:, 0], rel[:, 1])
            axial = rel[:, 2]
            rho = v0 / g["volume"][...]
            args = (g["damage_tension"][...], g["damage_compression"][...], rho, g["pressure"][...],
                    g["equivalent_stress"][...], g["velocity"][:, 2])
            ahead = (lateral < 2 * radius) & (axial >= 0) & (axial <= radius + 1e-3 * ahead_mm)
            ring = (lateral >= radius) & (lateral <= 3 * radius) & (axial < radius) & (x[:, 2] >= 0)
            window = (h["time_s"] > t_last) & (h["time_s"] <= t)
            if not window.any():
                window = np.abs(h["time_s"] - t) == np.abs(h["time_s"] - t).min()
            rows.append({"time_us": 1e6 * t, "depth_mm": 1e3 * float(xs[2] + radius),
                         "velocity_m_s": float(sg["velocity"][0][2]),
                         "contact_force_N": float(h["contact_force_z_N"][window].mean()),
                         "contact_particles": float(h["contact_particles"][window].mean()),
                         "ahead": group_stats(ahead, *args), "ring": group_stats(ring, *args)})
            t_last = t
    return {"run": str(run), "impact_velocity_m_s": result["impact_velocity_m_s"], "outcome": result["outcome"],
            "final_velocity_m_s": result["final_velocity_m_s"], "ahead_mm": ahead_mm, "rows": rows}


def markdown(studies):
    md = []
    for st in studies:
        md += [f"### {st['run']} ({st['impact_velocity_m_s']:g} m/s: {st['outcome']}, "
               f"{st['final_velocity_m_s']:.1f} m/s at the end)", "",
               "depth: of the sphere's nose below the entry face. ahead: lateral < 2 R, 0 to R + "
               f"{st['ahead_mm']:g} mm in front of the centre; ring: lateral R-3 R beside the sphere. "
               "d+1: share with d+ >= 0.999; rho: median rho/rho0; free: share with |P|, q < 1 kPa.", "",
               "| t us | depth mm | v m/s | contact force N | in contact | ahead n | d+1 | rho (min) | P MPa | d- | free "
               "| vz m/s | ring n | d+1 | rho | P MPa | free |", "|" + "---|" * 17]
        for r in st["rows"]:
            a, g = r["ahead"], r["ring"]
            cells = [f"{r['time_us']:.0f}", f"{r['depth_mm']:.1f}", f"{r['velocity_m_s']:.1f}",
                     f"{r['contact_force_N']:.0f}", f"{r['contact_particles']:.1f}"]
            if a["count"]:
                cells += [f"{a['count']}", f"{a['share_d_plus_1']:.2f}",
                          f"{a['density_ratio_median']:.3f} ({a['density_ratio_min']:.2f})",
                          f"{a['pressure_median_MPa']:.2f}", f"{a['d_minus_median']:.2f}", f"{a['share_no_stress']:.2f}",
                          f"{a['axial_velocity_median_m_s']:.1f}"]
            else:
                cells += ["0"] + ["-"] * 6
            if g["count"]:
                cells += [f"{g['count']}", f"{g['share_d_plus_1']:.2f}", f"{g['density_ratio_median']:.3f}",
                          f"{g['pressure_median_MPa']:.2f}", f"{g['share_no_stress']:.2f}"]
            else:
                cells += ["0"] + ["-"] * 4
            md.append("| " + " | ".join(cells) + " |")
        md.append("")
    return "\n".join(md) + "\n"


def figure(studies, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 3, figsize=(15, 4.5))
    for st in studies:
        t = [r["time_us"] for r in st["rows"]]
        label = pathlib.Path(st["run"]).name
        ax[0].plot(t, [r["velocity_m_s"] for r in st["rows"]], label=label)
        ax[1].plot(t, [r["contact_force_N"] for r in st["rows"]], label=label)
        ax[2].plot(t, [r["ahead"].get("pressure_median_MPa", np.nan) for r in st["rows"]], label=label)
    for a, y in zip(ax, ("sphere velocity [m/s]", "contact force on the sphere [N]", "median pressure ahead [MPa]")):
        a.set_xlabel("time [us]")
        a.set_ylabel(y)
        a.grid(alpha=0.3)
    ax[1].set_yscale("symlog", linthresh=100)
    ax[0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--out", required=True)
    ap.add_argument("--ahead-mm", type=float, default=15.0)
    args = ap.parse_args()
    studies = [study(r, args.ahead_mm) for r in args.runs]
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "creep.json").write_text(json.dumps(studies, indent=1) + "\n")
    (out / "creep.md").write_text(markdown(studies))
    figure(studies, out / "creep.png")
    print(f"creep_study.py: {out / 'creep.md'}, creep.json, creep.png")


if __name__ == "__main__":
    main()
