#!/usr/bin/env python3
"""Which geometric property of the microcells goes with their peak stress, and does it explain the size effect?

usage: size_effect_factors.py --analysed DIR --generated DIR --out DIR

DIR/size_<L>mm/cell_<k>/ of an analysed ensemble (uhpc-micro ensemble: summary.json, its peak stress) and
of the same cells generated (uhpc-micro generate-ensemble with the same base seed: cell.json, the pores),
joined cell by cell (the seeds and porosities must agree). Only the cells the ensemble averages are used
(not failed, bridged, their strain grid complete), so the sizes' means are ensemble.h5's. For each cell, four descriptors of its pores:
  largest_pore   the largest pore's diameter in mm (a weakest-flaw argument: the largest flaw grows with
                 the cell, up to the Burr law's truncation),
  pore_count     the number of pores,
  porosity       the pores' area fraction,
  worst_section  the largest pore fraction of a cross-section normal to the load (a net-section argument).
Per size the mean peak and descriptors with standard errors; per descriptor the Pearson r with the peak
inside each size and pooled (size means removed), the pooled within-size slope, and the size effect that
slope predicts from the descriptor's change of mean between the smallest and the largest size, beside the
measured one. This is a correlation across the cells as they were drawn, not an experiment that changes
one property: a descriptor with no within-size correlation cannot be what makes the smaller cells
stronger; one with a correlation is a candidate for a run that changes it alone.
Also the boundary-layer form peak(L) = P_inf + C / L fitted to the size means (weighted by 1 / se^2; with
three sizes or more). Needs two sizes of at least three averaged cells each.
Writes size_effect_factors.{json,md}; exit 2 on missing, unreadable or mismatched cells (the file and key named).
"""
import argparse
import json
import pathlib
import sys

import numpy as np

from uq_inputs import BadInput, read_json

DESCRIPTORS = ("largest_pore", "pore_count", "porosity", "worst_section")
SECTION_SAMPLES = 4001  # cross-sections per cell side: the chord sum is sampled, pores are >= 8 spacings wide


def worst_section(cell):
    """The largest sum of pore chords on a line normal to the load, over the cell side (images ignored)."""
    side = cell["cell_size_m"]
    axis = 0 if cell["loading_direction"] == "x" else 1
    s = np.linspace(0.0, side, SECTION_SAMPLES)
    chords = np.zeros_like(s)
    for pore in cell["pores"]:
        r = 0.5 * pore["diameter_m"]
        d = np.abs(s - pore["center_m"][axis])
        inside = d < r
        chords[inside] += 2.0 * np.sqrt(r * r - d[inside] ** 2)
    return float(chords.max() / side)


def averaged(summary):
    """The ensemble's own rule (ensemble_commands.cpp, averaged()): not failed, bridged, its grid complete."""
    grid = summary.get("grid")
    return summary.get("status") != "failed" and isinstance(grid, dict) and grid.get("complete") is True


def read_cells(analysed, generated):
    cells, left_out = [], 0
    for size_dir in sorted(analysed.glob("size_*")):
        for cell_dir in sorted(size_dir.glob("cell_*")):
            summary_file = cell_dir / "summary.json"
            if not summary_file.is_file():
                continue  # an unfinished cell
            cell_file = generated / size_dir.name / cell_dir.name / "cell.json"
            summary = read_json(summary_file, "an analysed cell")
            cell = read_json(cell_file, "the same cell generated: uhpc-micro generate-ensemble with the same base seed")
            try:
                if summary["cell"]["seed"] != cell["seed"]:
                    raise BadInput(f"{cell_file}: key 'seed' is {cell['seed']}, the analysed cell's is {summary['cell']['seed']}")
                if abs(cell["porosity"]["achieved"] - summary["cell"]["porosity"]) > 1e-12:
                    raise BadInput(f"{cell_file}: key 'porosity.achieved' is {cell['porosity']['achieved']}, the analysed "
                                   f"cell's is {summary['cell']['porosity']}: not the same pores (another pore law or generator)")
                if not averaged(summary):
                    left_out += 1
                    continue
                cells.append({"size_m": summary["cell"]["size_m"], "peak_MPa": summary["peak_stress_Pa"] / 1e6,
                              "largest_pore": 1e3 * cell["largest_pore_diameter_m"],
                              "pore_count": float(cell["pore_count"]), "porosity": summary["cell"]["porosity"],
                              "worst_section": worst_section(cell)})
            except KeyError as e:
                raise BadInput(f"{summary_file} or {cell_file}: no key {e}")
    sizes = {}
    for c in cells:
        sizes[c["size_m"]] = sizes.get(c["size_m"], 0) + 1
    if len(sizes) < 2 or min(sizes.values()) < 3:
        raise BadInput(f"{analysed}: needs two sizes of at least three averaged cells each "
                       f"(cells per size: {sizes or 'none'}; {left_out} left out as the ensemble leaves them)")
    return cells, left_out


def pearson(x, y):
    """Pearson's r, None where either is constant (no correlation to speak of, and no NaN in the JSON)."""
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    return float(np.corrcoef(x, y)[0, 1]) if len(x) > 2 and x.std() > 0 and y.std() > 0 else None


def mean_se(x):
    x = np.asarray(x, dtype=float)
    return float(x.mean()), float(x.std(ddof=1) / np.sqrt(len(x))) if len(x) > 1 else float("nan")


def analyse(cells):
    sizes = sorted({c["size_m"] for c in cells})
    groups = {L: [c for c in cells if c["size_m"] == L] for L in sizes}
    per_size = []
    for L in sizes:
        row = {"size_m": L, "cells": len(groups[L])}
        for key in ("peak_MPa",) + DESCRIPTORS:
            row[key], row[key + "_se"] = mean_se([c[key] for c in groups[L]])
        per_size.append(row)
    measured = per_size[-1]["peak_MPa"] - per_size[0]["peak_MPa"]
    factors = {}
    for key in DESCRIPTORS:
        x, y, r_size = [], [], {}
        for L in sizes:
            xs = np.array([c[key] for c in groups[L]])
            ys = np.array([c["peak_MPa"] for c in groups[L]])
            r_size[f"{1e3 * L:g}"] = pearson(xs, ys)
            x += list(xs - xs.mean())
            y += list(ys - ys.mean())
        x, y = np.array(x), np.array(y)
        sxx = float(x @ x)
        slope = float(x @ y) / sxx if sxx > 0 else None
        dof = len(x) - len(sizes) - 1
        slope_se = float(np.sqrt((y - slope * x) @ (y - slope * x) / dof / sxx)) if slope is not None and dof > 0 else None
        change = per_size[-1][key] - per_size[0][key]
        se_change = float(np.hypot(per_size[-1][key + "_se"], per_size[0][key + "_se"]))
        factors[key] = {"r_within_size": r_size,
                        "r_pooled": pearson(x, y),
                        "slope_MPa": slope, "slope_se_MPa": slope_se, "mean_change": change,
                        "predicted_size_effect_MPa": None if slope is None else slope * change,
                        # both the slope's and the change of mean's errors
                        "predicted_size_effect_se_MPa": None if slope_se is None
                        else float(np.hypot(change * slope_se, slope * se_change))}
    boundary = None
    se = np.array([r["peak_MPa_se"] for r in per_size])
    if len(sizes) >= 3 and np.all(se > 0):
        inv_L = np.array([1.0 / r["size_m"] for r in per_size])
        peaks = np.array([r["peak_MPa"] for r in per_size])
        w = 1.0 / se ** 2
        A = np.c_[np.ones_like(inv_L), inv_L] * np.sqrt(w)[:, None]
        (p_inf, c), *_ = np.linalg.lstsq(A, peaks * np.sqrt(w), rcond=None)
        boundary = {"P_inf_MPa": float(p_inf), "C_MPa_m": float(c),
                    "chi2": float(np.sum(w * (peaks - p_inf - c * inv_L) ** 2)), "dof": len(sizes) - 2}
    return {"per_size": per_size, "measured_size_effect_MPa": measured,
            "measured_size_effect_se_MPa": float(np.hypot(per_size[-1]["peak_MPa_se"], per_size[0]["peak_MPa_se"])),
            "factors": factors, "boundary_layer_fit": boundary}


def fmt(value, spec):
    return "-" if value is None or value != value else format(value, spec)  # None or NaN: a constant descriptor


def markdown(result):
    lines = ["| size mm | cells | peak MPa | largest pore mm | pores | porosity | worst section |",
             "|---|---|---|---|---|---|---|"]
    for r in result["per_size"]:
        lines.append(f"| {1e3 * r['size_m']:g} | {r['cells']} | {r['peak_MPa']:.2f} +- {r['peak_MPa_se']:.2f} | "
                     f"{r['largest_pore']:.3f} | {r['pore_count']:.1f} | {r['porosity']:.4f} | {r['worst_section']:.3f} |")
    lines += ["", f"Measured size effect (largest minus smallest size): {result['measured_size_effect_MPa']:+.2f} +- "
                  f"{result['measured_size_effect_se_MPa']:.2f} MPa", "",
              "| descriptor | r inside each size | r pooled | slope MPa per unit | predicted size effect MPa |",
              "|---|---|---|---|---|"]
    for key, f in result["factors"].items():
        r_size = " / ".join(fmt(v, "+.2f") for v in f["r_within_size"].values())
        lines.append(f"| {key} | {r_size} | {fmt(f['r_pooled'], '+.2f')} | {fmt(f['slope_MPa'], '+.3g')} +- "
                     f"{fmt(f['slope_se_MPa'], '.2g')} | {fmt(f['predicted_size_effect_MPa'], '+.2f')} +- "
                     f"{fmt(f['predicted_size_effect_se_MPa'], '.2f')} |")
    b = result["boundary_layer_fit"]
    lines += ["", "Boundary-layer form peak = P_inf + C / L: " + (
        "not fitted (fewer than three sizes)" if b is None else
        f"P_inf {b['P_inf_MPa']:.2f} MPa, C {1e3 * b['C_MPa_m']:.2f} MPa mm, chi2 {b['chi2']:.2f} on {b['dof']} "
        "degrees of freedom")]
    if result["cells_left_out"]:
        lines += ["", f"{result['cells_left_out']} cell(s) left out as the ensemble leaves them (failed, not bridged "
                      "or an incomplete grid)."]
    return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--analysed", required=True, type=pathlib.Path)
    parser.add_argument("--generated", required=True, type=pathlib.Path)
    parser.add_argument("--out", required=True, type=pathlib.Path)
    args = parser.parse_args()
    try:
        for d in (args.analysed, args.generated):
            if not d.is_dir():
                raise BadInput(f"{d}: not a directory")
        cells, left_out = read_cells(args.analysed, args.generated)
    except BadInput as e:
        print(f"size_effect_factors: {e}", file=sys.stderr)
        sys.exit(2)
    result = analyse(cells)
    result["cells_left_out"] = left_out
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / "size_effect_factors.json").write_text(json.dumps(result, indent=2) + "\n")
    (args.out / "size_effect_factors.md").write_text(markdown(result))
    print(markdown(result), end="")


if __name__ == "__main__":
    main()
