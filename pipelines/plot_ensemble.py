#!/usr/bin/env python3
"""Plots a microcell ensemble (uhpc-micro ensemble): the paper's Figs. 8 and 9.

usage: plot_ensemble.py DIR [--sdel SDEL.json]
  reads DIR/ensemble.h5 (calibrate/README.md, the ensemble file) and writes
  DIR/fig8_stress_strain.png  mean homogenized stress against imposed strain per cell size, +- one
                              standard deviation over the cells
  DIR/fig9_damage.png         mean damage per cell size, +- one standard deviation, and (dashed) the
                              SDEL of --sdel at the same sizes for reference (default: none)
"""
import argparse
import json
import math
from pathlib import Path

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def sdel_damage(sdel: dict, size_m: float, strain) -> list:
    """d+ = 1 / (1 + nu exp(-lambda chi (e - e_i))), e_i = A / sqrt(1 + a lambda) (PHYSICS.md section 3)."""
    c = sdel["constants"]
    lam = size_m / sdel["l_mac_m"]
    e_i = c["A"] / math.sqrt(1.0 + c["a"] * lam)
    return [1.0 / (1.0 + c["nu"] * math.exp(-lam * c["chi"] * (e - e_i))) for e in strain]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("directory", type=Path)
    parser.add_argument("--sdel", type=Path, help="an SDEL handoff to draw beside the damage curves")
    args = parser.parse_args()
    sdel = json.loads(args.sdel.read_text()) if args.sdel else None
    with h5py.File(args.directory / "ensemble.h5", "r") as f:
        sizes = f["sizes"][:]
        strain = f["strain"][:]
        cells = f["cells"][:]
        curves = {name: (f[f"{name}/mean"][:], f[f"{name}/std"][:]) for name in ("stress", "damage")}
        strength = f["nominal_strength"][:]

    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    mean, std = curves["stress"]
    for k, size in enumerate(sizes):
        label = f"{size * 1e3:.1f} mm ({cells[k]} cells, peak {strength[k] * 1e-6:.2f} MPa)"
        ax.fill_between(strain * 1e3, (mean[k] - std[k]) * 1e-6, (mean[k] + std[k]) * 1e-6, color=f"C{k}", alpha=0.15, lw=0)
        ax.plot(strain * 1e3, mean[k] * 1e-6, "-", color=f"C{k}", label=label)
    ax.set(xlabel="imposed strain (1e-3)", ylabel="homogenized stress (MPa)", title="microcell ensembles (Fig. 8)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    out = args.directory / "fig8_stress_strain.png"
    fig.savefig(out, dpi=120)
    print(f"wrote {out}")

    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    mean, std = curves["damage"]
    for k, size in enumerate(sizes):
        ax.fill_between(strain * 1e3, mean[k] - std[k], mean[k] + std[k], color=f"C{k}", alpha=0.15, lw=0)
        ax.plot(strain * 1e3, mean[k], "-", color=f"C{k}", label=f"{size * 1e3:.1f} mm ({cells[k]} cells)")
        if sdel:
            ax.plot(strain * 1e3, sdel_damage(sdel, size, strain), "--", color=f"C{k}", lw=1)
    title = "microcell damage (Fig. 9)" + (f"; dashed: SDEL of {args.sdel.name}" if sdel else "")
    ax.set(xlabel="imposed strain (1e-3)", ylabel="damage d", title=title, ylim=(-0.02, 1.02))
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    out = args.directory / "fig9_damage.png"
    fig.savefig(out, dpi=120)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
