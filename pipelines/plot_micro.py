#!/usr/bin/env python3
"""Plots uhpc-micro generate-ensemble's output.

usage: plot_micro.py DIR
  reads  DIR/statistics.json, DIR/pore_histogram.csv and DIR/<size>/cell_00/cell.json
  writes DIR/pore_histogram.png (pore-size densities per cell size against the truncated Burr pdf)
         DIR/cells.png          (the first cell of every size, like the paper's Fig. 5)
"""
import csv
import json
import sys
from collections import defaultdict
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Circle, Rectangle  # noqa: E402


def read_histogram(path: Path):
    rows = defaultdict(list)
    with open(path) as f:
        for row in csv.DictReader(line for line in f if not line.startswith("#")):
            rows[float(row["size_m"])].append({k: float(v) for k, v in row.items()})
    return rows


def plot_histogram(directory: Path, statistics) -> None:
    rows = read_histogram(directory / statistics["histogram_file"])
    sizes = statistics["sizes"]
    fig, axes = plt.subplots(1, len(sizes), figsize=(4 * len(sizes), 3.6), sharey=True, squeeze=False)
    for ax, size in zip(axes[0], sizes):
        bins = rows[size["cell_size_m"]]
        edges = [b["bin_lo_m"] * 1e6 for b in bins] + [bins[-1]["bin_hi_m"] * 1e6]
        for key, label in (("drawn_density_1_m", f"all draws ({size['burr_draws']['count']})"),
                           ("placed_density_1_m", f"placed pores ({size['placed_pores']['count']})")):
            ax.stairs([b[key] * 1e-6 for b in bins], edges, label=label)
        ax.stairs([b["burr_density_1_m"] * 1e-6 for b in bins], edges, color="black", linestyle="--",
                  label="truncated Burr XII")
        ax.set_yscale("log")
        ax.set(title=f"{size['cell_size_m'] * 1e3:.1f} mm, {size['cells']} cells, "
                     f"KS p(draws) = {size['burr_draws']['ks_p_value']:.2f}",
               xlabel="ESD (um)")
        ax.grid(True, alpha=0.3)
    axes[0][0].set_ylabel("density (1/um)")
    axes[0][0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(directory / "pore_histogram.png", dpi=130)


def plot_cells(directory: Path, statistics) -> None:
    sizes = statistics["sizes"]
    fig, axes = plt.subplots(1, len(sizes), figsize=(4 * len(sizes), 4.2), squeeze=False)
    for ax, size in zip(axes[0], sizes):
        cell = json.loads((directory / size["directory"] / "cell_00" / "cell.json").read_text())
        side = cell["cell_size_m"] * 1e3
        ax.add_patch(Rectangle((0, 0), side, side, facecolor="#d9d4c7", edgecolor="black"))
        for pore in cell["pores"]:
            x, y = pore["center_m"]
            ax.add_patch(Circle((x * 1e3, y * 1e3), pore["diameter_m"] * 0.5e3, facecolor="#1f4e79"))
        for seed in cell["seeds"]:
            (x0, y0), (x1, y1) = seed["root_m"], seed["tip_m"]
            ax.plot([x0 * 1e3, x1 * 1e3], [y0 * 1e3, y1 * 1e3], color="#d62728", linewidth=1)
        ax.set(xlim=(0, side), ylim=(0, side), aspect="equal", xlabel="x (mm)",
               title=f"{side:.1f} mm: {cell['pore_count']} pores, {100 * cell['porosity']['achieved']:.2f} %")
    fig.tight_layout()
    fig.savefig(directory / "cells.png", dpi=130)


def main(directory: Path) -> None:
    statistics = json.loads((directory / "statistics.json").read_text())
    plot_histogram(directory, statistics)
    plot_cells(directory, statistics)
    print(f"wrote {directory / 'pore_histogram.png'} and {directory / 'cells.png'}")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(Path(sys.argv[1]))
