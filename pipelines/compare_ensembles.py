#!/usr/bin/env python3
"""Compare an analysed microcell ensemble with a reference one, size by size (issue 50 item 2: a faster
crack algorithm must give the same ensemble as the reference algorithm).

usage: compare_ensembles.py REFERENCE CANDIDATE [--tolerance 0.02] [--out DIR]

REFERENCE and CANDIDATE are `uhpc-micro ensemble` output directories (size_*mm/cell_NN/ with summary.json
and curves.h5; the archive data/micro_analysis_ensemble_cells/cells.tar.xz unpacked is one). The cells
compared are those of the candidate that the reference also holds, paired by size and index (a cell of
the candidate with another seed than the reference's is refused). Per size, over the pairs that both
runs bridged (status not failed and a complete strain grid):
  - the mean peak stress, strain at d = 0.5 and dissipated energy density, and the relative difference
    of the candidate's mean from the reference's;
  - the mean damage curve on the common strain grid (resampled/damage), and the largest difference of
    the candidate's from the reference's (damage is in [0, 1], so this is absolute);
  - the wall time and the crack geometries (enriched models built) of both.
Each cell's own differences are listed too. The verdict holds when every mean is within the tolerance
(relative) and every mean damage curve within it (absolute). Writes DIR/ensemble_comparison.{json,md}
with --out. Exit 0 when the verdict holds, 1 when not, 2 on bad input (a missing directory, a cell of
the candidate the reference does not hold at all, a seed that differs).
"""
import argparse
import json
import math
import pathlib
import re
import sys

import h5py
import numpy as np

MEASURES = {  # name in the tables: summary.json key
    "peak": "peak_stress_Pa",
    "e50": "strain_at_half_damage",
    "dissipation": "dissipated_energy_density_J_m3",
}


def fail(msg):
    print(f"error: {msg}", file=sys.stderr)
    sys.exit(2)


def cells_of(root):
    """{(size_mm, index): directory} of the finished cells (a summary.json) under root."""
    if not root.is_dir():
        fail(f"{root}: not a directory")
    out = {}
    for d in sorted(root.glob("size_*mm/cell_*")):
        m = re.fullmatch(r"size_([0-9.]+)mm", d.parent.name)
        n = re.fullmatch(r"cell_(\d+)", d.name)
        if m and n and (d / "summary.json").is_file():
            out[(float(m.group(1)), int(n.group(1)))] = d
    return out


def read_cell(d):
    try:
        s = json.loads((d / "summary.json").read_text())
    except (OSError, ValueError) as e:
        fail(f"{d / 'summary.json'}: cannot be read ({e})")
    bridged = s.get("status") != "failed" and isinstance(s.get("grid"), dict) and s["grid"].get("complete") is True
    cell = {"seed": s.get("cell", {}).get("seed"), "bridged": bridged, "status": s.get("status"),
            "wall_s": s.get("wall_s"), "crack_geometries": s.get("crack_geometries"),
            "factorizations": s.get("factorizations")}
    for name, key in MEASURES.items():
        v = s.get(key)
        cell[name] = float(v) if bridged and v is not None else math.nan
    cell["damage"] = None
    if bridged:
        with h5py.File(d / "curves.h5", "r") as f:
            cell["damage"] = np.asarray(f["resampled/damage"][...], dtype=float)
            cell["strain"] = np.asarray(f["resampled/strain"][...], dtype=float)
    return cell


def relative(candidate, reference):
    return (candidate - reference) / abs(reference) if reference != 0.0 and math.isfinite(reference) else math.nan


def compare(reference_root, candidate_root, tolerance):
    ref_cells, cand_cells = cells_of(reference_root), cells_of(candidate_root)
    if not cand_cells:
        fail(f"{candidate_root}: no analysed cell (size_*mm/cell_*/summary.json)")
    sizes = []
    for size in sorted({k[0] for k in cand_cells}):
        pairs, per_cell, unpaired = [], [], []
        for key in sorted(k for k in cand_cells if k[0] == size):
            if key not in ref_cells:
                fail(f"{cand_cells[key]}: the reference {reference_root} holds no cell {key[1]} of {size:.1f} mm")
            r, c = read_cell(ref_cells[key]), read_cell(cand_cells[key])
            if r["seed"] != c["seed"]:
                fail(f"{cand_cells[key] / 'summary.json'}: key 'cell.seed' is {c['seed']}, the reference's "
                     f"{r['seed']}: not the same cell")
            row = {"cell": key[1], "reference_status": r["status"], "candidate_status": c["status"],
                   "wall_s": [r["wall_s"], c["wall_s"]], "crack_geometries": [r["crack_geometries"], c["crack_geometries"]]}
            if r["bridged"] and c["bridged"]:
                if r["strain"].shape != c["strain"].shape or not np.allclose(r["strain"], c["strain"], rtol=1e-12, atol=0):
                    fail(f"{cand_cells[key] / 'curves.h5'}: its strain grid differs from the reference's")
                pairs.append((r, c))
                for name in MEASURES:
                    row[name] = relative(c[name], r[name])
                row["damage"] = float(np.max(np.abs(c["damage"] - r["damage"])))
            else:
                unpaired.append(key[1])
            per_cell.append(row)
        entry = {"size_mm": size, "cells": len(per_cell), "paired": len(pairs), "not_bridged_in_one": unpaired,
                 "per_cell": per_cell}
        if pairs:
            for name in MEASURES:
                rv = np.array([p[0][name] for p in pairs])
                cv = np.array([p[1][name] for p in pairs])
                ok = np.isfinite(rv) & np.isfinite(cv)
                rm, cm = (float(np.mean(rv[ok])), float(np.mean(cv[ok]))) if ok.any() else (math.nan, math.nan)
                entry[name] = {"reference": rm, "candidate": cm, "relative": relative(cm, rm), "cells": int(ok.sum())}
            rd = np.mean([p[0]["damage"] for p in pairs], axis=0)
            cd = np.mean([p[1]["damage"] for p in pairs], axis=0)
            entry["damage_curve_max_difference"] = float(np.max(np.abs(cd - rd)))
        walls = [[row["wall_s"][i] for row in per_cell if row["wall_s"][i] is not None] for i in (0, 1)]
        entry["wall_s"] = {"reference": float(sum(walls[0])), "candidate": float(sum(walls[1]))}
        geoms = [[row["crack_geometries"][i] for row in per_cell] for i in (0, 1)]
        entry["crack_geometries"] = {"reference": sum(geoms[0]) if None not in geoms[0] else None,
                                     "candidate": sum(geoms[1]) if None not in geoms[1] else None}
        within = bool(pairs) and all(
            math.isfinite(entry[n]["relative"]) and abs(entry[n]["relative"]) <= tolerance for n in MEASURES)
        within = within and entry["damage_curve_max_difference"] <= tolerance
        entry["within_tolerance"] = within
        sizes.append(entry)
    return {"reference": str(reference_root), "candidate": str(candidate_root), "tolerance": tolerance,
            "sizes": sizes, "within_tolerance": all(s["within_tolerance"] for s in sizes)}


def pct(x):
    return "n/a" if x is None or not math.isfinite(x) else f"{100.0 * x:+.2f} %"


def count(n):
    return "n/a" if n is None else str(n)


def markdown(result):
    lines = ["| size mm | pairs | peak MPa ref / new | e(d=0.5) ref / new | dissipation kJ/m^3 ref / new | "
             "mean damage curve max diff | wall s ref / new | geometries ref / new | within |",
             "|---|---|---|---|---|---|---|---|---|"]
    for s in result["sizes"]:
        if not s["paired"]:
            lines.append(f"| {s['size_mm']:.1f} | 0 | | | | | | | no |")
            continue
        pk, e5, di = s["peak"], s["e50"], s["dissipation"]
        g = s["crack_geometries"]
        lines.append(
            f"| {s['size_mm']:.1f} | {s['paired']} | {pk['reference'] * 1e-6:.3f} / {pk['candidate'] * 1e-6:.3f} "
            f"({pct(pk['relative'])}) | {e5['reference'] * 1e3:.4f}e-3 / {e5['candidate'] * 1e3:.4f}e-3 "
            f"({pct(e5['relative'])}) | {di['reference'] * 1e-3:.2f} / {di['candidate'] * 1e-3:.2f} "
            f"({pct(di['relative'])}) | {s['damage_curve_max_difference']:.4f} | "
            f"{s['wall_s']['reference']:.0f} / {s['wall_s']['candidate']:.0f} | {count(g['reference'])} / {count(g['candidate'])} | "
            f"{'yes' if s['within_tolerance'] else 'no'} |")
    lines += ["", "Per cell (relative differences of the candidate from the reference; damage: largest absolute "
              "difference of the curves):", "",
              "| size mm | cell | peak | e(d=0.5) | dissipation | damage | status ref / new |", "|---|---|---|---|---|---|---|"]
    for s in result["sizes"]:
        for c in s["per_cell"]:
            dmg = f"{c['damage']:.4f}" if "damage" in c else "n/a"
            lines.append(f"| {s['size_mm']:.1f} | {c['cell']} | {pct(c.get('peak'))} | {pct(c.get('e50'))} | "
                         f"{pct(c.get('dissipation'))} | {dmg} | {c['reference_status']} / {c['candidate_status']} |")
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("reference", type=pathlib.Path)
    ap.add_argument("candidate", type=pathlib.Path)
    ap.add_argument("--tolerance", type=float, default=0.02)
    ap.add_argument("--out", type=pathlib.Path)
    a = ap.parse_args()
    if not (a.tolerance > 0.0):
        fail(f"--tolerance: {a.tolerance} is not positive")
    result = compare(a.reference, a.candidate, a.tolerance)
    table = markdown(result)
    print(table, end="")
    if a.out:
        a.out.mkdir(parents=True, exist_ok=True)
        (a.out / "ensemble_comparison.json").write_text(json.dumps(result, indent=1, allow_nan=True) + "\n")
        (a.out / "ensemble_comparison.md").write_text(table)
    print("verdict: " + ("within" if result["within_tolerance"] else "NOT within") +
          f" {a.tolerance:g} of the reference at every size")
    return 0 if result["within_tolerance"] else 1


if __name__ == "__main__":
    sys.exit(main())
