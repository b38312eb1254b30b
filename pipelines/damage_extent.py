#!/usr/bin/env python3
"""How much of a disc target is fully cracked: the volume share with d+ >= 0.999 (and with d+ >= 0.5) by
ring of reference radius, at the output step closest to the sphere's exit (or the last one).

usage: damage_extent.py RUN_DIR [RUN_DIR ...] [--rings-mm 0,50,100,150,203.2] [--out FILE.json]
RUN_DIR holds uhpc-macro's fields.h5 and result.json (an AFC run: the field damage_tension). Rings are
taken in the reference configuration (the first output step), with the particles' reference volumes.
Prints one table row per run and writes the figures as JSON with --out.
"""
import argparse
import json
import pathlib
import sys

import h5py
import numpy as np


def extent(run, rings_mm):
    run = pathlib.Path(run)
    r = json.loads((run / "result.json").read_text())
    with h5py.File(run / "fields.h5", "r") as f:
        steps = sorted(k for k in f.keys() if k.startswith("step_"))
        times = np.array([f[k].attrs["time_s"] for k in steps])
        t_exit = r.get("outcome_time_s") or r.get("exit_time_s")
        k = int(np.argmin(np.abs(times - t_exit))) if t_exit else len(steps) - 1
        x0 = f[steps[0]]["position"][...]
        v0 = f[steps[0]]["volume"][...]
        d = f[steps[k]]["damage_tension"][...]
        time = float(times[k])
    radius = np.hypot(x0[:, 0], x0[:, 1]) * 1e3
    rows = []
    for lo, hi in zip(rings_mm[:-1], rings_mm[1:]):
        m = (radius >= lo) & (radius < hi + (1e-9 if hi == rings_mm[-1] else 0))
        vol = v0[m].sum()
        rows.append({"ring_mm": [lo, hi], "volume_m3": float(vol),
                     "share_full": float(v0[m][d[m] >= 0.999].sum() / vol) if vol > 0 else None,
                     "share_half": float(v0[m][d[m] >= 0.5].sum() / vol) if vol > 0 else None})
    return {"run": str(run), "time_s": time, "outcome": r.get("outcome"),
            "impact_velocity_m_s": r["impact_velocity_m_s"], "rings": rows}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--rings-mm", default="0,50,100,150,203.2")
    ap.add_argument("--out")
    a = ap.parse_args()
    rings = [float(x) for x in a.rings_mm.split(",")]
    if len(rings) < 2 or any(b <= c for c, b in zip(rings[:-1], rings[1:])):
        sys.exit("damage_extent.py: --rings-mm must be increasing radii, at least two")
    results = [extent(run, rings) for run in a.runs]
    head = " | ".join(f"{lo:g}-{hi:g} mm" for lo, hi in zip(rings[:-1], rings[1:]))
    print(f"| run | t us | d+ = 1 share by ring: {head} |")
    print("|---|---|" + "---|" * (len(rings) - 1))
    for res in results:
        cells = " | ".join(f"{row['share_full']:.2f} ({row['share_half']:.2f})" for row in res["rings"])
        print(f"| {res['run']} | {res['time_s'] * 1e6:.0f} | {cells} |")
    print("(in brackets: share with d+ >= 0.5)")
    if a.out:
        pathlib.Path(a.out).write_text(json.dumps(results, indent=2) + "\n")


if __name__ == "__main__":
    main()
