#!/usr/bin/env python3
"""Lambert-Jonas fits of residual against impact velocity, for a set of shots and for the experiments.

    vr = a (v^p - v_bl^p)^(1/p)  for v > v_bl,   vr = 0 otherwise

usage: lambert_jonas.py COMPARISON_JSON [--experiments TABLE5_CSV] --out DIR
COMPARISON_JSON is uhpc-compare-shots' comparison.json (each shot's impact and residual velocity; a shot
that did not perforate counts as 0). Writes DIR/lambert_jonas.json and DIR/lambert_jonas.md.

The fit minimises the sum of squared residual-velocity errors. For fixed (v_bl, p), a is linear and
solved exactly and bounded to [0, 1] (vr / v -> a as v grows: a residual faster than the impact is not
physical); (v_bl, p) are found on a grid (v_bl in 0.5 m/s steps below the slowest perforating shot, p in
0.01 steps over [0.5, 6]) and refined by a finer grid around the best point. With seven shots the three
constants are strongly correlated (the same curve is matched by several (a, p) pairs), so the fit with p
held at 1 is given too, and the experiments' fits made the same way stand beside them.
"""
import argparse
import csv
import json
import math
import pathlib

import numpy as np


def model(v, a, v_bl, p):
    v = np.asarray(v, dtype=float)
    x = np.clip(v ** p - v_bl ** p, 0.0, None)
    return a * x ** (1.0 / p)


def fit(v, vr, p_fixed=None):
    v = np.asarray(v, dtype=float)
    vr = np.asarray(vr, dtype=float)
    perforating = v[vr > 0]
    v_top = perforating.min() if perforating.size else v.max()

    def best_on(vbl_grid, p_grid):
        B, P = np.meshgrid(vbl_grid, p_grid, indexing="ij")
        X = np.clip(v[None, None, :] ** P[..., None] - B[..., None] ** P[..., None], 0.0, None) ** (1.0 / P[..., None])
        denom = (X * X).sum(axis=-1)
        A = np.where(denom > 0, (X * vr).sum(axis=-1) / np.where(denom > 0, denom, 1.0), 0.0)
        A = np.clip(A, 0.0, 1.0)  # vr / v -> a as v -> infinity: a residual faster than the impact is not physical
        sse = ((A[..., None] * X - vr) ** 2).sum(axis=-1)
        k = np.unravel_index(np.argmin(sse), sse.shape)
        return A[k], B[k], P[k], sse[k]

    p_grid = np.array([p_fixed]) if p_fixed else np.arange(0.5, 6.0001, 0.01)
    a, vbl, p, sse = best_on(np.arange(0.0, v_top, 0.5), p_grid)
    p_fine = np.array([p_fixed]) if p_fixed else np.linspace(max(0.3, p - 0.02), p + 0.02, 201)
    a, vbl, p, sse = best_on(np.linspace(max(0.0, vbl - 1.0), min(v_top - 1e-6, vbl + 1.0), 201), p_fine)
    return {"a": float(a), "v_bl_m_s": float(vbl), "p": float(p), "points": int(v.size),
            "rms_m_s": float(math.sqrt(sse / v.size))}


def shots_from_comparison(path):
    c = json.loads(pathlib.Path(path).read_text())
    v, vr = [], []
    for s in c["shots"]:
        sim = s["simulation"]
        v.append(float(sim["impact_velocity_m_s"]))
        vr.append(float(sim["residual_velocity_m_s"] or 0.0))
    return v, vr


def experiments_from_table(path):
    v, vr = [], []
    with open(path) as f:
        rows = [line for line in f if not line.startswith("#")]
    for row in list(csv.reader(rows))[1:]:
        v.append(float(row[2]))
        vr.append(float(row[3]))
    return v, vr


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("comparison")
    ap.add_argument("--experiments")
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    fits = {"simulation": fit(*shots_from_comparison(args.comparison)),
            "simulation, p = 1": fit(*shots_from_comparison(args.comparison), p_fixed=1.0)}
    if args.experiments:
        fits["experiments"] = fit(*experiments_from_table(args.experiments))
        fits["experiments, p = 1"] = fit(*experiments_from_table(args.experiments), p_fixed=1.0)
    (out / "lambert_jonas.json").write_text(json.dumps(fits, indent=2) + "\n")
    md = ["| data | points | a | v_bl m/s | p | RMS of the fit m/s |", "|---|---|---|---|---|---|"]
    for name, f in fits.items():
        md.append(f"| {name} | {f['points']} | {f['a']:.3f} | {f['v_bl_m_s']:.1f} | {f['p']:.2f} | {f['rms_m_s']:.1f} |")
    (out / "lambert_jonas.md").write_text("\n".join(md) + "\n")
    print("\n".join(md))


if __name__ == "__main__":
    main()
