#!/usr/bin/env python3
"""The refinement study's report: residual velocity per axis spacing and support, the observed order of
convergence and the extrapolated limit (Richardson, from the three finest spacings), wall time and memory.

usage: refinement_study.py RUNS_DIR --out DIR
RUNS_DIR holds one directory per run named v<impact m/s>_h<axis spacing mm>_s<support factor> with the
result.json of uhpc-macro. Writes DIR/refinement.json, DIR/refinement.md and DIR/refinement.png.

Order and limit: with vr(h) = v_inf + C h^p through three spacings h1 > h2 > h3, p solves
(vr1 - vr2) / (vr2 - vr3) = (h1^p - h2^p) / (h2^p - h3^p) (bisection on p in (0, 8]); when the
differences change sign (no monotone convergence) no order is claimed and the spread is given instead.
"""
import argparse
import json
import math
import pathlib
import re
import sys

NAME = re.compile(r"^v(?P<v>[0-9.]+)_h(?P<h>[0-9.]+)_s(?P<s>[0-9.]+)$")


def load(runs_dir, failed):
    runs = []
    for d in sorted(pathlib.Path(runs_dir).iterdir()):
        m = NAME.match(d.name)
        if not m:
            continue
        if not (d / "result.json").is_file():
            if (d / "diagnostic.json").is_file():  # a run that failed: reported, not fitted
                g = json.loads((d / "diagnostic.json").read_text())
                failed.append({"run": d.name, "reason": g.get("reason"),
                               "time_s": g.get("last_good_state", {}).get("time_s")})
            continue
        r = json.loads((d / "result.json").read_text())
        runs.append({
            "run": d.name, "velocity_m_s": float(m["v"]), "axis_spacing_mm": float(m["h"]),
            "support_factor": float(m["s"]), "outcome": r.get("outcome", "perforated" if r["perforated"] else "?"),
            "residual_velocity_m_s": r["residual_velocity_m_s"] if r["perforated"] else 0.0,
            "particles": r["particle_count"], "steps": r["steps"], "wall_time_s": r["wall_time_s"],
            "peak_memory_MB": r.get("peak_memory_MB"), "energy_balance_error": r["energy"]["balance_error"],
            "worst_energy_balance_error": r["energy"]["worst_balance_error"],
            "contact_share": r.get("energy_partition", {}).get("shares", {}).get("contact_J"),
        })
    return runs


def observed_order(h, v):
    """(p, v_inf) for v = v_inf + C h^p through three points, h descending; None when not monotone."""
    d1, d2 = v[0] - v[1], v[1] - v[2]
    if d2 == 0 or d1 == 0 or (d1 > 0) != (d2 > 0):
        return None
    ratio = d1 / d2
    f = lambda p: (h[0] ** p - h[1] ** p) / (h[1] ** p - h[2] ** p) - ratio
    lo, hi = 1e-6, 8.0
    if f(lo) * f(hi) > 0:
        return None
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        (lo, hi) = (lo, mid) if f(lo) * f(mid) <= 0 else (mid, hi)
    p = 0.5 * (lo + hi)
    c = d2 / (h[1] ** p - h[2] ** p)
    return p, v[2] - c * h[2] ** p


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("runs_dir")
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    failed = []
    runs = load(a.runs_dir, failed)
    if not runs:
        sys.exit(f"refinement_study.py: no runs in {a.runs_dir}")
    out = pathlib.Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    series = []
    for v in sorted({r["velocity_m_s"] for r in runs}):
        for s in sorted({r["support_factor"] for r in runs}):
            pts = sorted((r for r in runs if r["velocity_m_s"] == v and r["support_factor"] == s),
                         key=lambda r: -r["axis_spacing_mm"])
            if not pts:
                continue
            entry = {"velocity_m_s": v, "support_factor": s,
                     "axis_spacing_mm": [r["axis_spacing_mm"] for r in pts],
                     "residual_velocity_m_s": [r["residual_velocity_m_s"] for r in pts],
                     "observed_order": None, "extrapolated_m_s": None}
            if len(pts) >= 3:
                fit = observed_order([r["axis_spacing_mm"] for r in pts[-3:]],
                                     [r["residual_velocity_m_s"] for r in pts[-3:]])
                if fit:
                    entry["observed_order"], entry["extrapolated_m_s"] = fit
            vr = entry["residual_velocity_m_s"]
            entry["spread_m_s"] = max(vr) - min(vr)
            entry["finest_minus_extrapolated_m_s"] = (vr[-1] - entry["extrapolated_m_s"]
                                                      if entry["extrapolated_m_s"] is not None else None)
            series.append(entry)
    (out / "refinement.json").write_text(json.dumps({"runs": runs, "series": series, "failed": failed}, indent=2) + "\n")

    md = ["| run | outcome | vr m/s | particles | steps | wall min | peak MB | energy balance (worst) | contact share |",
          "|---|---|---|---|---|---|---|---|---|"]
    for r in runs:
        md.append(f"| {r['run']} | {r['outcome']} | {r['residual_velocity_m_s']:.1f} | {r['particles']} | {r['steps']} | "
                  f"{r['wall_time_s'] / 60:.1f} | {r['peak_memory_MB'] or float('nan'):.0f} | "
                  f"{r['energy_balance_error']:.1e} ({r['worst_energy_balance_error']:.1e}) | "
                  f"{(r['contact_share'] or float('nan')):.3f} |")
    md += ["", "| v0 m/s | support | vr at axis spacing 3.0 / 2.25 / 1.5 mm | spread m/s | observed order | "
           "extrapolated m/s | finest - extrapolated m/s |", "|---|---|---|---|---|---|---|"]
    for e in series:
        vr = " / ".join(f"{x:.1f}" for x in e["residual_velocity_m_s"])
        p = f"{e['observed_order']:.2f}" if e["observed_order"] is not None else "not monotone"
        vx = f"{e['extrapolated_m_s']:.1f}" if e["extrapolated_m_s"] is not None else "-"
        dx = f"{e['finest_minus_extrapolated_m_s']:.1f}" if e["finest_minus_extrapolated_m_s"] is not None else "-"
        md.append(f"| {e['velocity_m_s']:.0f} | {e['support_factor']:.1f} h | {vr} | {e['spread_m_s']:.1f} | {p} | {vx} | {dx} |")
    if failed:
        md += ["", "Failed runs (stopped by a numerical check; the last good state is in the run's fields.h5):", ""]
        md += [f"- {f['run']}: {f['reason']} after {f['time_s'] * 1e6:.1f} us" for f in failed]
    (out / "refinement.md").write_text("\n".join(md) + "\n")

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("refinement_study.py: matplotlib missing, no figure", file=sys.stderr)
        return
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    for e in series:
        style = "-o" if e["support_factor"] == 2.0 else "--s"
        ax.plot(e["axis_spacing_mm"], e["residual_velocity_m_s"], style,
                label=f"{e['velocity_m_s']:.0f} m/s, {e['support_factor']:.1f} h")
        if e["extrapolated_m_s"] is not None:
            ax.plot([0.0], [e["extrapolated_m_s"]], "kx")
    ax.set_xlim(left=0)
    ax.set_xlabel("axis spacing h (mm)")
    ax.set_ylabel("residual velocity (m/s)")
    ax.set_title("Refinement: residual velocity against particle spacing (x: extrapolated)")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out / "refinement.png", dpi=130)


if __name__ == "__main__":
    main()
