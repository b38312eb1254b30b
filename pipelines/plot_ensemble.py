#!/usr/bin/env python3
"""Plots a microcell ensemble (uhpc-micro ensemble): the paper's Figs. 8 and 9.

usage: plot_ensemble.py DIR [--sdel SDEL.json]
  reads DIR/ensemble.h5 (calibrate/README.md, the ensemble file) and writes
  DIR/fig8_stress_strain.png  mean homogenized stress against imposed strain per cell size, +- one
                              standard deviation over the cells
  DIR/fig9_damage.png         mean damage per cell size, +- one standard deviation, and (dashed) the
                              SDEL of --sdel at the same sizes for reference (default: none)
  DIR/size_table.md           per size (from DIR/summary.json): cells, peak stress, nominal strength,
                              strain at d = 0.5, beside the --sdel law's peak ((1 - d) E0_bar e with the
                              cells' E0_bar) and strain at d = 0.5; bridging check; then per size from
                              the cells' summary.json: status, wall time, work balance, operator check,
                              growth unloads and jumps, DOFs; also printed
"""
import argparse
import json
import math
from collections import Counter
from pathlib import Path
from statistics import mean, median

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def sdel_damage(sdel: dict, size_m: float, strain) -> list:
    """d+ = 1 / (1 + nu exp(-lambda chi (e - e_i))), e_i = A / sqrt(1 + a lambda) (docs/physics.md section 3)."""
    c = sdel["constants"]
    lam = size_m / sdel["l_mac_m"]
    e_i = c["A"] / math.sqrt(1.0 + c["a"] * lam)
    return [1.0 / (1.0 + c["nu"] * math.exp(-lam * c["chi"] * (e - e_i))) for e in strain]


def sdel_half_damage_strain(sdel: dict, size_m: float) -> float:
    """The strain where the SDEL gives d+ = 0.5: e_i + ln(nu) / (lambda chi)."""
    c = sdel["constants"]
    lam = size_m / sdel["l_mac_m"]
    return c["A"] / math.sqrt(1.0 + c["a"] * lam) + math.log(c["nu"]) / (lam * c["chi"])


def sdel_peak_stress(sdel: dict, size_m: float, e0_bar: float) -> float:
    """max over e of (1 - d+(e)) E0_bar e: the uniaxial peak the SDEL implies with the cells' stiffness."""
    strain = [k * 1e-7 for k in range(1, 30001)]
    return max((1.0 - d) * e0_bar * e for d, e in zip(sdel_damage(sdel, size_m, strain), strain))


def size_table(summary: dict, sdel) -> str:
    """Markdown table of the per-size figures in an ensemble's summary.json."""
    sdel_col = " SDEL: peak MPa, e(d = 0.5) |" if sdel else ""
    lines = [
        "| size | cells ok / failed / incomplete / suspect | peak stress mean +- std (min-max) MPa"
        " | its standard error | nominal strength MPa | e(d = 0.5) mean +- std |" + sdel_col + " E0_bar GPa | bridging max |",
        "|---" * (8 + (1 if sdel else 0)) + "|",
    ]
    for s in summary["sizes"]:
        pk, eh, e0 = s["peak_stress_Pa"], s["strain_at_half_damage"], s["E0_bar_Pa"]
        row = (
            f"| {s['cell_size_m'] * 1e3:.1f} mm | {s['cells_ok']} / {s['cells_failed']} / {s['cells_incomplete']}"
            f" / {s['cells_suspect']} | {pk['mean'] * 1e-6:.2f} +- {pk['std'] * 1e-6:.2f}"
            f" ({pk['min'] * 1e-6:.2f}-{pk['max'] * 1e-6:.2f}) | {pk['std'] * 1e-6 / math.sqrt(max(pk['count'], 1)):.2f}"
            f" | {s['nominal_strength_Pa'] * 1e-6:.2f}"
            f" | {eh['mean'] * 1e4:.2f}e-4 +- {eh['std'] * 1e4:.2f}e-4 |"
        )
        if sdel:
            row += (
                f" {sdel_peak_stress(sdel, s['cell_size_m'], e0['mean']) * 1e-6:.1f},"
                f" {sdel_half_damage_strain(sdel, s['cell_size_m']) * 1e4:.2f}e-4 |"
            )
        row += f" {e0['mean'] * 1e-9:.2f} | {s['bridging_max_abs_difference']:.1e} |"
        lines.append(row)
    return "\n".join(lines) + "\n"


def cell_table(directory: Path, summary: dict) -> str:
    """Markdown table of the ensemble's cells per size, from each cell's summary.json: status, cost,
    work balance at the last state, operator check, growth unloads and jumps, size of the system."""
    lines = [
        "| size | status | wall s mean (min-max) | \\|balance\\| median / max | operator mismatch max"
        " | cells with growth unloads / jumps | DOFs mean |",
        "|---" * 7 + "|",
    ]
    for s in summary["sizes"]:
        cells = [json.loads((directory / s["directory"] / f"cell_{r:02d}" / "summary.json").read_text())
                 for r in range(len(s["seeds"]))]
        # step_limit is the earlier name of reached_end (the archived cells).
        status = ", ".join(f"{n} {k}" for k, n in sorted(Counter(
            "reached_end" if c["status"] == "step_limit" else c["status"] for c in cells).items()))
        wall = [c["wall_s"] for c in cells]
        balance = [abs(c["energy_balance_relative"]) for c in cells if c["energy_balance_relative"] is not None]
        balance_text = f"{median(balance):.1e} / {max(balance):.1e}" if balance else "-"
        lines.append(
            f"| {s['cell_size_m'] * 1e3:.1f} mm | {status} | {mean(wall):.0f} ({min(wall):.0f}-{max(wall):.0f})"
            f" | {balance_text} | {max(c['operator_energy_mismatch'] for c in cells):.1e}"
            f" | {sum(1 for c in cells if c['growth_unloads'])} / {sum(1 for c in cells if c['jumps'])}"
            f" | {mean(c['dofs'] for c in cells):.0f} |"
        )
    return "\n".join(lines) + "\n"


def draw_bands(ax, strain, mean, std, labels) -> None:
    """One line per size (row of mean) with a +- one standard deviation band."""
    for k, label in enumerate(labels):
        ax.fill_between(strain * 1e3, mean[k] - std[k], mean[k] + std[k], color=f"C{k}", alpha=0.15, lw=0)
        ax.plot(strain * 1e3, mean[k], "-", color=f"C{k}", label=label)


def save(fig, ax, out: Path) -> None:
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    print(f"wrote {out}")


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

    labels = [f"{size * 1e3:.1f} mm ({cells[k]} cells)" for k, size in enumerate(sizes)]
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    mean, std = curves["stress"]
    peaks = [f"{label[:-1]}, peak {strength[k] * 1e-6:.2f} MPa)" for k, label in enumerate(labels)]
    draw_bands(ax, strain, mean * 1e-6, std * 1e-6, peaks)
    ax.set(xlabel="imposed strain (1e-3)", ylabel="homogenized stress (MPa)", title="microcell ensembles (Fig. 8)")
    save(fig, ax, args.directory / "fig8_stress_strain.png")

    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    mean, std = curves["damage"]
    draw_bands(ax, strain, mean, std, labels)
    if sdel:
        for k, size in enumerate(sizes):
            ax.plot(strain * 1e3, sdel_damage(sdel, size, strain), "--", color=f"C{k}", lw=1)
    title = "microcell damage (Fig. 9)" + (f"; dashed: SDEL of {args.sdel.name}" if sdel else "")
    ax.set(xlabel="imposed strain (1e-3)", ylabel="damage d", title=title, ylim=(-0.02, 1.02))
    save(fig, ax, args.directory / "fig9_damage.png")

    summary = json.loads((args.directory / "summary.json").read_text())
    table = size_table(summary, sdel) + "\n" + cell_table(args.directory, summary)
    (args.directory / "size_table.md").write_text(table)
    print(table, end="")
    print(f"wrote {args.directory / 'size_table.md'}")


if __name__ == "__main__":
    main()
