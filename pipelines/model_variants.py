#!/usr/bin/env python3
"""The seven Table 5 shots of several model variants side by side, against Tables 5 and 8.

usage: model_variants.py --experiments TABLE5_CSV --paper TABLE8_CSV --out DIR RUN_DIR [RUN_DIR ...]

Each RUN_DIR is a `make shots` output root named <variant>--<sdel> (pipelines/Makefile, model-variants):
RUN_DIR/shots/v<velocity>/result.json for the seven impact velocities of Table 5. A shot that did not
perforate counts as 0 m/s (as in uhpc-compare-shots); an undecided one is listed as such and also counts
as 0. Table 8 (the paper's own simulations) is matched to Table 5 row by row, as the paper prints them.

Writes DIR/variants.json, DIR/variants.md (residual velocities, RMS against both tables, Lambert-Jonas
fits with p = 1 and free, the energy partition averaged over the seven shots) and DIR/variants.png
(residual against impact velocity for every variant beside both tables).
"""
import argparse
import json
import math
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import lambert_jonas  # noqa: E402
from sweep_report import read_table, run_row  # noqa: E402

# The energy partition's parts shown (result.json energy_partition.shares), in this order.
PARTS = [("plastic_J", "plastic"), ("crushing_J", "crushing"), ("opening_J", "opening"), ("contact_J", "contact"),
         ("stabilization_dissipated_J", "NSNI"), ("target_kinetic_J", "target KE"), ("released_J", "released")]


def rms(errors):
    return math.sqrt(sum(e * e for e in errors) / len(errors))


def variant(run_dir, v_exp, vr_exp, vr_paper):
    name = run_dir.name
    label, _, sdel = name.partition("--")
    shots, parts = [], {k: [] for k, _ in PARTS}
    for v in v_exp:
        result = run_dir / "shots" / f"v{v:g}" / "result.json"
        if not result.is_file():
            sys.exit(f"model_variants.py: {result}: missing (run `make -C pipelines model-variants`)")
        row = run_row(result)
        r = json.loads(result.read_text())
        shares = r.get("energy_partition", {}).get("shares", {})
        for k, _ in PARTS:
            parts[k].append(shares.get(k, 0.0))
        shots.append({"impact_velocity_m_s": v, "outcome": row["outcome"],
                      "residual_velocity_m_s": row["residual_velocity_m_s"] or 0.0,
                      "energy_balance_error": r["energy"]["balance_error"]})
    vr = [s["residual_velocity_m_s"] for s in shots]
    fits = {"p = 1": lambert_jonas.fit(v_exp, vr, p_fixed=1.0), "free": lambert_jonas.fit(v_exp, vr)}
    return {"name": name, "variant": label, "sdel": sdel, "shots": shots,
            "rms_vs_table5_m_s": rms([a - b for a, b in zip(vr, vr_exp)]),
            "rms_vs_table8_m_s": rms([a - b for a, b in zip(vr, vr_paper)]),
            "max_abs_vs_table8_m_s": max(abs(a - b) for a, b in zip(vr, vr_paper)),
            "lambert_jonas": fits,
            "energy_shares_mean": {k: sum(x) / len(x) for k, x in parts.items()}}


def markdown(variants, v_exp, vr_exp, vr_paper):
    head = "| variant | SDEL | " + " | ".join(f"{v:g}" for v in v_exp) + " | RMS vs T5 | RMS vs T8 | max vs T8 |"
    md = ["Residual velocities, m/s (a shot that did not perforate counts as 0; u: undecided at the end time).", "",
          head, "|" + "---|" * (len(v_exp) + 5)]
    md.append("| experiments (Table 5) | - | " + " | ".join(f"{x:g}" for x in vr_exp) + " | - | - | - |")
    md.append("| the paper's simulations (Table 8) | - | " + " | ".join(f"{x:g}" for x in vr_paper)
              + f" | {rms([a - b for a, b in zip(vr_paper, vr_exp)]):.1f} | - | - |")
    for r in variants:
        cells = [f"{s['residual_velocity_m_s']:.1f}" + ("u" if s["outcome"] == "undecided" else "") for s in r["shots"]]
        md.append(f"| {r['variant']} | {r['sdel']} | " + " | ".join(cells)
                  + f" | {r['rms_vs_table5_m_s']:.1f} | {r['rms_vs_table8_m_s']:.1f} | {r['max_abs_vs_table8_m_s']:.1f} |")
    exp_fits = {"p = 1": lambert_jonas.fit(v_exp, vr_exp, p_fixed=1.0), "free": lambert_jonas.fit(v_exp, vr_exp)}
    md += ["", "Lambert-Jonas fits vr = a (v^p - v_bl^p)^(1/p) of the seven shots (v_bl extrapolated unless a shot "
           "stopped the sphere).", "",
           "| variant | SDEL | a (p = 1) | v_bl m/s (p = 1) | a | v_bl m/s | p |", "|---|---|---|---|---|---|---|"]
    for label, sdel, fits in [("experiments (Table 5)", "-", exp_fits)] + [(r["variant"], r["sdel"], r["lambert_jonas"])
                                                                          for r in variants]:
        f1, ff = fits["p = 1"], fits["free"]
        md.append(f"| {label} | {sdel} | {f1['a']:.3f} | {f1['v_bl_m_s']:.0f} | {ff['a']:.3f} | {ff['v_bl_m_s']:.0f} "
                  f"| {ff['p']:.2f} |")
    md += ["", "Where the sphere's lost kinetic energy went, mean share over the seven shots.", "",
           "| variant | SDEL | " + " | ".join(n for _, n in PARTS) + " | worst balance |",
           "|" + "---|" * (len(PARTS) + 3)]
    for r in variants:
        worst = max(abs(s["energy_balance_error"]) for s in r["shots"])
        md.append(f"| {r['variant']} | {r['sdel']} | " + " | ".join(f"{r['energy_shares_mean'][k]:.3f}" for k, _ in PARTS)
                  + f" | {worst:.1e} |")
    return "\n".join(md) + "\n"


def figure(variants, v_exp, vr_exp, vr_paper, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(12, 5), sharey=True)
    sdels = sorted({r["sdel"] for r in variants})
    for ax, sdel in zip(axes if len(sdels) > 1 else [axes[0]], sdels):
        ax.plot(v_exp, vr_exp, "ks", ms=8, label="experiments (Table 5)")
        ax.plot(v_exp, vr_paper, "kx", ms=9, mew=2, label="paper's simulations (Table 8)")
        for r in variants:
            if r["sdel"] != sdel:
                continue
            ax.plot(v_exp, [s["residual_velocity_m_s"] for s in r["shots"]], "o-",
                    label=f"{r['variant']} (RMS {r['rms_vs_table5_m_s']:.0f} / {r['rms_vs_table8_m_s']:.0f})")
        ax.set_title(f"SDEL: {sdel}")
        ax.set_xlabel("impact velocity [m/s]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, title="RMS vs Table 5 / Table 8, m/s", title_fontsize=8)
    axes[0].set_ylabel("residual velocity [m/s]")
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--experiments", required=True)
    ap.add_argument("--paper", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("runs", nargs="+")
    args = ap.parse_args()
    exp = read_table(args.experiments, ["impact_velocity", "residual_velocity"])
    paper = read_table(args.paper, ["residual_velocity"])
    if len(paper) != len(exp):
        sys.exit(f"model_variants.py: {args.paper}: {len(paper)} rows, Table 5 has {len(exp)}")
    v_exp, vr_exp = [r[0] for r in exp], [r[1] for r in exp]
    vr_paper = [r[0] for r in paper]
    variants = [variant(pathlib.Path(d), v_exp, vr_exp, vr_paper) for d in args.runs]
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "variants.json").write_text(json.dumps({"impact_velocities_m_s": v_exp, "table5_m_s": vr_exp,
                                                   "table8_m_s": vr_paper, "variants": variants}, indent=2) + "\n")
    (out / "variants.md").write_text(markdown(variants, v_exp, vr_exp, vr_paper))
    figure(variants, v_exp, vr_exp, vr_paper, out / "variants.png")
    print(f"model_variants.py: {out / 'variants.md'}, variants.json, variants.png")


if __name__ == "__main__":
    main()
