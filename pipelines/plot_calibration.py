#!/usr/bin/env python3
"""Plots uhpc-calibrate's figure data (the paper's Fig. 11 and Fig. 10).

usage: plot_calibration.py DIR      (reads DIR/calibration_figures.h5 and DIR/fit_report.json,
                                     writes DIR/fig11_damage_fit.png and DIR/fig10_size_effect.png)

Fig. 11: ensemble-mean damage (with +- one standard deviation band) and the fitted SDEL per cell size;
samples left out of the fit (strain or damage window) are drawn faded.
Fig. 10: nominal strength against cell size with the fitted size effect law, log-log.
"""
import json
import sys
from pathlib import Path

import h5py
import matplotlib
import matplotlib.ticker

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def fig11(f, report, out: Path) -> None:
    sizes = f["fig11/sizes"][:]
    strain = f["fig11/strain"][:]
    mean = f["fig11/damage_mean"][:]
    std = f["fig11/damage_std"][:]
    law = f["fig11/damage_fit"][:]
    fitted = f["fig11/fitted"][:].astype(bool)
    c = report["sdel"]["constants"]
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    for k, size in enumerate(sizes):
        colour = f"C{k}"
        label = f"{size * 1e3:.1f} mm"
        ax.fill_between(strain * 1e3, mean[k] - std[k], mean[k] + std[k], color=colour, alpha=0.15, lw=0)
        ax.plot(strain[fitted[k]] * 1e3, mean[k][fitted[k]], ".", color=colour, ms=3, label=f"ensemble {label}")
        if (~fitted[k]).any():
            ax.plot(strain[~fitted[k]] * 1e3, mean[k][~fitted[k]], ".", color=colour, ms=3, alpha=0.25)
        ax.plot(strain * 1e3, law[k], "-", color=colour, lw=1.5, label=f"SDEL fit {label}")
    ax.set(xlabel="imposed strain (1e-3)", ylabel="damage d",
           title=f"SDEL fit: a={c['a']:.3g}, A={c['A']:.4g}, nu={c['nu']:.4g}, chi={c['chi']:.4g}")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    print(f"wrote {out}")


def fig10(f, report, out: Path) -> None:
    sizes = f["fig10/sizes"][:]
    strength = f["fig10/nominal_strength"][:]
    grid = f["fig10/size_grid"][:]
    law = f["fig10/law"][:]
    se = report["size_effect"]
    fig, ax = plt.subplots(figsize=(5.5, 4.2))
    ax.loglog(sizes * 1e3, strength * 1e-6, "o", label="ensemble nominal strength")
    if se["size_effect"]:
        label = f"B f_t / sqrt(1 + D/D0): B={se['B']:.3g}, D0={se['D0_m'] * 1e3:.3g} mm"
    else:
        label = "no size effect: mean strength"
    ax.loglog(grid * 1e3, law * 1e-6, "-", label=label)
    ax.set(xlabel="cell size D (mm)", ylabel="nominal strength (MPa)", title="size effect law")
    for axis in (ax.xaxis, ax.yaxis):  # plain numbers on the log axes (the range is a factor of a few)
        axis.set_major_formatter(matplotlib.ticker.ScalarFormatter())
        axis.set_minor_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    print(f"wrote {out}")


def main(directory: Path) -> None:
    report = json.loads((directory / "fit_report.json").read_text())
    with h5py.File(directory / "calibration_figures.h5", "r") as f:
        fig11(f, report, directory / "fig11_damage_fit.png")
        fig10(f, report, directory / "fig10_size_effect.png")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(Path(sys.argv[1]))
