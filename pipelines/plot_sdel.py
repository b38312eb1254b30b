#!/usr/bin/env python3
"""Plots uhpc-sdel's output: damage and uniaxial stress against strain, one curve per length scale.

usage: plot_sdel.py DIR      (reads DIR/sdel_curves.h5, writes DIR/sdel_curves.png)
"""
import sys
from pathlib import Path

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(directory: Path) -> None:
    with h5py.File(directory / "sdel_curves.h5", "r") as f:
        lengths = f["lengths"][:]
        strain = f["strain"][:]
        damage = f["damage"][:]
        stress = f["stress"][:]
    fig, (ax_d, ax_s) = plt.subplots(1, 2, figsize=(10, 4))
    for i, length in enumerate(lengths):
        label = f"{length * 1e3:.1f} mm"
        ax_d.plot(strain * 1e3, damage[i], label=label)
        ax_s.plot(strain * 1e3, stress[i] * 1e-6, label=label)
    ax_d.set(xlabel="strain (1e-3)", ylabel="tensile damage d+", title="SDEL damage")
    ax_s.set(xlabel="strain (1e-3)", ylabel="stress (MPa)", title="uniaxial stress (1 - d+) E e")
    for ax in (ax_d, ax_s):
        ax.grid(True, alpha=0.3)
        ax.legend(title="length scale")
    fig.tight_layout()
    out = directory / "sdel_curves.png"
    fig.savefig(out, dpi=120)
    print(f"wrote {out}")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(Path(sys.argv[1]))
