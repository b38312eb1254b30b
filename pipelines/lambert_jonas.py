#!/usr/bin/env python3
"""Lambert-Jonas fits of residual against impact velocity, for a set of shots and for the experiments.

    vr = a (v^p - v_bl^p)^(1/p)  for v > v_bl,   vr = 0 otherwise

usage: lambert_jonas.py COMPARISON_JSON [--experiments TABLE5_CSV] [--bootstrap N [--seed S]] --out DIR
COMPARISON_JSON is uhpc-compare-shots' comparison.json (each shot's impact and residual velocity; a shot
that did not perforate counts as 0). Writes DIR/lambert_jonas.json and DIR/lambert_jonas.md.

--bootstrap N adds percentile 95 % confidence intervals of a, v_bl and p (bootstrap(), below): the
(impact velocity, residual velocity) pairs are resampled with replacement, as many as there are, N times
with a fixed seed (reproducible), each resample is fitted again, and the 2.5 and 97.5 percentiles of
each constant over the N fits are the interval. The resamples are fitted by fit_fast() (the same model
and bounds, a coarse-to-fine search instead of the full 0.5 m/s x 0.01 grid: 4 s a fit on 81 points).

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


def best_on(v, vr, vbl_grid, p_grid):
    """The least-squares (a, v_bl, p, sse) over a grid of (v_bl, p); a solved exactly for each and clipped to
    [0, 1] (vr / v -> a as v -> infinity: a residual faster than the impact is not physical)."""
    B, P = np.meshgrid(vbl_grid, p_grid, indexing="ij")
    X = np.clip(v[None, None, :] ** P[..., None] - B[..., None] ** P[..., None], 0.0, None) ** (1.0 / P[..., None])
    denom = (X * X).sum(axis=-1)
    A = np.where(denom > 0, (X * vr).sum(axis=-1) / np.where(denom > 0, denom, 1.0), 0.0)
    A = np.clip(A, 0.0, 1.0)
    sse = ((A[..., None] * X - vr) ** 2).sum(axis=-1)
    k = np.unravel_index(np.argmin(sse), sse.shape)
    return A[k], B[k], P[k], sse[k]


P_SEARCH = (0.5, 6.0)  # the range of p searched when p is free


def fit(v, vr, p_fixed=None):
    """The least-squares fit of (v, vr), with two flags a reader needs before trusting v_bl and p:
    v_bl_bracketed (some run did not perforate, so the data hold the limit from both sides; without one,
    v_bl is extrapolated from the perforating runs alone and the sweep does not constrain it) and
    p_at_search_edge (a free p within 0.01 of an end of P_SEARCH: the optimum lies outside the search)."""
    v = np.asarray(v, dtype=float)
    vr = np.asarray(vr, dtype=float)
    perforating = v[vr > 0]
    v_top = perforating.min() if perforating.size else v.max()

    p_grid = np.array([p_fixed]) if p_fixed else np.arange(P_SEARCH[0], P_SEARCH[1] + 1e-4, 0.01)
    a, vbl, p, sse = best_on(v, vr, np.arange(0.0, v_top, 0.5), p_grid)
    p_fine = np.array([p_fixed]) if p_fixed else np.linspace(max(0.3, p - 0.02), p + 0.02, 201)
    a, vbl, p, sse = best_on(v, vr, np.linspace(max(0.0, vbl - 1.0), min(v_top - 1e-6, vbl + 1.0), 201), p_fine)
    edge = not p_fixed and (p <= P_SEARCH[0] + 0.01 or p >= P_SEARCH[1] - 0.01)
    return {"a": float(a), "v_bl_m_s": float(vbl), "p": float(p), "points": int(v.size),
            "rms_m_s": float(math.sqrt(sse / v.size)),
            "v_bl_bracketed": bool(np.any(vr <= 0)), "p_at_search_edge": bool(edge)}


def fit_fast(v, vr, p_fixed=None):
    """fit() by a coarse-to-fine search: (v_bl, p) on a 5 m/s x 0.05 grid, then two refinements of 21 x 21
    points around the best, each 1/10 of the last step; the same model, a clipped to [0, 1], v_bl below the
    slowest perforating shot. For the bootstrap's many fits."""
    v = np.asarray(v, dtype=float)
    vr = np.asarray(vr, dtype=float)
    perforating = v[vr > 0]
    v_top = perforating.min() if perforating.size else v.max()

    db, dp = 5.0, 0.05
    p_grid = np.array([p_fixed]) if p_fixed else np.arange(P_SEARCH[0], P_SEARCH[1] + 1e-4, dp)
    a, vbl, p, sse = best_on(v, vr, np.arange(0.0, v_top, db), p_grid)
    for _ in range(2):
        b_grid = np.clip(vbl + np.linspace(-db, db, 21), 0.0, v_top - 1e-6)
        p_grid = np.array([p_fixed]) if p_fixed else np.clip(p + np.linspace(-dp, dp, 21), 0.3, None)
        a, vbl, p, sse = best_on(v, vr, np.unique(b_grid), np.unique(p_grid))
        db, dp = db / 10.0, dp / 10.0
    return {"a": float(a), "v_bl_m_s": float(vbl), "p": float(p), "points": int(v.size),
            "rms_m_s": float(math.sqrt(sse / v.size))}


def bootstrap(v, vr, resamples=1000, seed=20261205, p_fixed=None, level=95.0):
    """Percentile bootstrap of the fit: the (v, vr) pairs resampled with replacement (n of n), each resample
    fitted by fit_fast(); returns the intervals of a, v_bl_m_s and p and the fitted constants of every
    resample (for the band of the curve)."""
    v = np.asarray(v, dtype=float)
    vr = np.asarray(vr, dtype=float)
    rng = np.random.default_rng(seed)
    samples = []
    for _ in range(resamples):
        k = rng.integers(0, v.size, v.size)
        f = fit_fast(v[k], vr[k], p_fixed=p_fixed)
        samples.append((f["a"], f["v_bl_m_s"], f["p"]))
    samples = np.array(samples)
    lo, hi = (100.0 - level) / 2.0, 100.0 - (100.0 - level) / 2.0
    ci = {}
    for j, name in enumerate(("a", "v_bl_m_s", "p")):
        ci[name] = [float(np.percentile(samples[:, j], lo)), float(np.percentile(samples[:, j], hi))]
    return {"resamples": int(resamples), "seed": int(seed), "level_percent": level,
            "resampled": "the (impact velocity, residual velocity) pairs, with replacement, as many as there are",
            "interval": "percentile", "search": "fit_fast (coarse-to-fine grid)", "ci": ci,
            "samples": samples.tolist()}


def fits_with_bootstrap(v, vr, resamples, seed, samples=None):
    """The free fit and the p = 1 fit of (v, vr), each with its bootstrap intervals; the free fit's
    resampled constants go into the list `samples` when one is given (for the band of the curve)."""
    out = {}
    for name, p_fixed in (("free", None), ("p = 1", 1.0)):
        f = fit(v, vr, p_fixed=p_fixed)
        if resamples:
            b = bootstrap(v, vr, resamples, seed, p_fixed=p_fixed)
            f["bootstrap"] = {k: val for k, val in b.items() if k != "samples"}
            if p_fixed is None and samples is not None:
                samples.extend(b["samples"])
        out[name] = f
    return out


def fit_markdown(fits):
    """A Markdown table of fits {name: fit}, with the bootstrap intervals when present."""
    md = ["| data | points | a | v_bl m/s | p | RMS of the fit m/s |", "|---|---|---|---|---|---|"]
    for name, f in fits.items():
        ci = f.get("bootstrap", {}).get("ci")
        cell = (lambda k, fmt: f"{f[k]:{fmt}}" + (f" [{ci[k][0]:{fmt}}, {ci[k][1]:{fmt}}]" if ci else ""))
        vbl_mark = "" if f.get("v_bl_bracketed", True) else " (extrapolated)"
        p_mark = " (search edge)" if f.get("p_at_search_edge") else ""
        md.append(f"| {name} | {f['points']} | {cell('a', '.3f')} | {cell('v_bl_m_s', '.1f')}{vbl_mark} "
                  f"| {cell('p', '.2f')}{p_mark} | {f['rms_m_s']:.1f} |")
    if any(not f.get("v_bl_bracketed", True) for f in fits.values()):
        md += ["", "(extrapolated): every run of these data perforated, so v_bl is the fitted curve's foot below "
               "the slowest run, not a limit the data bracket; run slower shots (or `make ballistic-limit`) to "
               "bracket it."]
    if any(f.get("p_at_search_edge") for f in fits.values()):
        md += ["", f"(search edge): the free p ended at an end of its search [{P_SEARCH[0]:g}, {P_SEARCH[1]:g}]: "
               "the data do not fix p; read the p = 1 fit instead."]
    boot = next((f["bootstrap"] for f in fits.values() if "bootstrap" in f), None)
    if boot:
        md.append("")
        md.append(f"[lo, hi]: {boot['level_percent']:g} % {boot['interval']} bootstrap intervals, {boot['resamples']} "
                  f"resamples of {boot['resampled']} (seed {boot['seed']}), each refitted.")
    return "\n".join(md) + "\n"


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
    ap.add_argument("--bootstrap", type=int, default=0, help="resamples for the 95 %% intervals (0: none)")
    ap.add_argument("--seed", type=int, default=20261205)
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    fits = {}
    sources = [("simulation", shots_from_comparison(args.comparison))]
    if args.experiments:
        sources.append(("experiments", experiments_from_table(args.experiments)))
    for name, (v, vr) in sources:
        both = fits_with_bootstrap(v, vr, args.bootstrap, args.seed)
        fits[name] = both["free"]
        fits[name + ", p = 1"] = both["p = 1"]
    (out / "lambert_jonas.json").write_text(json.dumps(fits, indent=2) + "\n")
    md = fit_markdown(fits)
    (out / "lambert_jonas.md").write_text(md)
    print(md, end="")


if __name__ == "__main__":
    main()
