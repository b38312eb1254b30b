#!/usr/bin/env python3
"""The velocity sweep and the thickness study: tables, plots and Lambert-Jonas fits of uhpc-macro runs.

usage: sweep_report.py sweep COMPARISON_JSON [--experiments TABLE5] [--paper TABLE8] [--bootstrap N]
                             [--seed S] --out DIR
       sweep_report.py thickness --runs T DIR... [--runs T DIR...] [--measured SHOTS_MEASURED_DIR]
                             [--experiments TABLE5] --out DIR

sweep: COMPARISON_JSON is uhpc-compare-shots' comparison.json over the sweep's runs (every run, matched to
a Table 5 shot or not). Writes DIR/sweep.csv, sweep.md, sweep.json (per run: impact velocity, outcome,
residual velocity as counted (0 when not perforated), the Table 5 shot it matched, the plug that left with
a perforating sphere and the a = m / (m + m_plug) it implies; the fits) and
sweep.png (residual against impact velocity: the runs, Table 5, the paper's Table 8, the fitted curves
with the bootstrap band). The Lambert-Jonas fits are pipelines/lambert_jonas.py's (free a, v_bl, p and p
held at 1), with percentile bootstrap intervals over the runs (resampled with replacement); the
experiments are fitted the same way. An `undecided` run (the sphere still in the target at the end time)
has no residual velocity: it is listed and left out of the fit.

thickness: each --runs T DIR... gives the runs of one thickness T (m). Per thickness: the residual
velocity of each run and the ballistic limit, estimated two ways: the bracket of the runs (the fastest
run that did not perforate, the slowest that did) and v_bl of the Lambert-Jonas fit with p held at 2
(vr = a (v^2 - v_bl^2)^(1/2): two constants, fitted when at least two runs perforate; undecided runs
left out). --measured adds the runs of `make shots-measured` (each at its shot's measured thickness) and
the experiments at theirs. Writes DIR/thickness.{md,json,png}.
"""
import argparse
import csv
import json
import pathlib
import sys

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import lambert_jonas as lj  # noqa: E402

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_table(path, columns):
    """Rows of a data/ CSV (comment lines '#', header 'name [unit]') as lists of the named columns."""
    with open(path) as f:
        rows = list(csv.reader(line for line in f if not line.startswith("#")))
    names = [h.split("[")[0].strip() for h in rows[0]]
    idx = [names.index(c) for c in columns]
    return [[float(r[i]) for i in idx] for r in rows[1:] if r]


def run_row(result_file):
    """What the tables need of one uhpc-macro result.json."""
    r = json.loads(pathlib.Path(result_file).read_text())
    outcome = r.get("outcome", "perforated" if r["perforated"] else "not perforated")
    vr = r["residual_velocity_m_s"] if r["perforated"] else 0.0
    return {"impact_velocity_m_s": r["impact_velocity_m_s"], "outcome": outcome,
            "residual_velocity_m_s": None if outcome == "undecided" else float(vr),
            "thickness_m": r.get("inputs", {}).get("target", {}).get("thickness_m"),
            "wall_time_s": r.get("wall_time_s"), "run": str(pathlib.Path(result_file).parent)}


def plug_share(result_file, comparison):
    """The plug that leaves with a perforating sphere (result.json's panel.plug: target material moving with
    at least half the sphere's speed at the end) and the Lambert-Jonas a it implies if sphere and plug share
    their momentum, a = m / (m + m_plug); None for both when the run did not perforate or has no panel (a
    result.json of an earlier build)."""
    path = pathlib.Path(result_file)
    if not path.is_file():
        print(f"error: {comparison}: key 'result_file': {result_file} not found from {pathlib.Path.cwd()} "
              "(uhpc-compare-shots records --results as given: run this from where it ran, or give it absolute "
              "paths)", file=sys.stderr)
        sys.exit(2)
    r = json.loads(path.read_text())
    plug = (r.get("panel") or {}).get("plug")
    mass = r.get("inputs", {}).get("projectile", {}).get("mass_kg")
    if not r.get("perforated") or plug is None or not mass:
        return None, None
    return plug["mass_kg"], mass / (mass + plug["mass_kg"])


def sweep(args):
    c = json.loads(pathlib.Path(args.comparison).read_text())
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    rows = []
    for s in c["shots"]:
        sim = s["simulation"]
        undecided = sim.get("run_outcome") == "undecided"
        rows.append({"label": s["label"], "impact_velocity_m_s": sim["impact_velocity_m_s"],
                     "outcome": sim.get("run_outcome") or sim["outcome"],
                     "residual_velocity_m_s": None if undecided else sim["residual_velocity_m_s"],
                     "final_velocity_m_s": sim["final_velocity_m_s"], "end_time_s": sim["end_time_s"],
                     "experiment_row": s.get("experiment_row"),
                     "experiment_residual_velocity_m_s": s["experiment"]["residual_velocity_m_s"],
                     "wall_time_s": sim["wall_time_s"], "result_file": s["result_file"]})
        rows[-1]["plug_mass_kg"], rows[-1]["a_plug"] = plug_share(s["result_file"], args.comparison)
    rows.sort(key=lambda r: r["impact_velocity_m_s"])
    fitted = [r for r in rows if r["residual_velocity_m_s"] is not None]
    v = [r["impact_velocity_m_s"] for r in fitted]
    vr = [r["residual_velocity_m_s"] for r in fitted]
    fits, samples = {}, []
    if len(fitted) >= 2:
        both = lj.fits_with_bootstrap(v, vr, args.bootstrap, args.seed, samples)
        fits["sweep"], fits["sweep, p = 1"] = both["free"], both["p = 1"]
    experiments = read_table(args.experiments, ["impact_velocity", "residual_velocity", "thickness"]) \
        if args.experiments else []
    if experiments:
        both = lj.fits_with_bootstrap([e[0] for e in experiments], [e[1] for e in experiments], args.bootstrap,
                                      args.seed)
        fits["experiments"], fits["experiments, p = 1"] = both["free"], both["p = 1"]
    paper = read_table(args.paper, ["impact_velocity", "residual_velocity"]) if args.paper else []

    # The table.
    header = ["label", "impact_velocity_m_s", "outcome", "residual_velocity_m_s", "final_velocity_m_s",
              "end_time_s", "experiment_row", "experiment_residual_velocity_m_s", "plug_mass_kg", "a_plug",
              "wall_time_s", "result_file"]
    with open(out / "sweep.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        for r in rows:
            w.writerow(["" if r[k] is None else r[k] for k in header])
    undecided = [r for r in rows if r["residual_velocity_m_s"] is None]
    md = [f"Sweep of {len(rows)} runs, {min(r['impact_velocity_m_s'] for r in rows):g} .. "
          f"{max(r['impact_velocity_m_s'] for r in rows):g} m/s (runs in {pathlib.Path(args.comparison).parent}).", "",
          "| v0 m/s | outcome | vr m/s | Table 5 vr m/s | plug g | m / (m + m_plug) | wall s |",
          "|---|---|---|---|---|---|---|"]
    for r in rows:
        vr_cell = "" if r["residual_velocity_m_s"] is None else f"{r['residual_velocity_m_s']:.1f}"
        exp = r["experiment_residual_velocity_m_s"]
        plug = "" if r["plug_mass_kg"] is None else f"{1e3 * r['plug_mass_kg']:.1f}"
        a_plug = "" if r["a_plug"] is None else f"{r['a_plug']:.2f}"
        md.append(f"| {r['impact_velocity_m_s']:g} | {r['outcome']} | {vr_cell} | "
                  f"{'' if exp is None else f'{exp:g}'} | {plug} | {a_plug} | {r['wall_time_s']:.1f} |")
    md += ["", "vr: the residual velocity, 0 when the sphere did not perforate (embedded, rebounded). Plug: the "
           "target material that leaves with the sphere (moving at half its speed or more at the end; blank when "
           "the sphere did not perforate, or for a result.json of an earlier build); m / (m + m_plug) is the "
           "Lambert-Jonas a if sphere and plug shared their momentum, to set beside the fits' a below."]
    if undecided:
        md.append(f"{len(undecided)} run(s) undecided at their end time (no residual velocity; left out of the fit): "
                  + ", ".join(f"{r['impact_velocity_m_s']:g}" for r in undecided)
                  + " m/s. Carry them on with uhpc-macro --restart --set run.end_time_s=<later> in their"
                  " directories (or a later end time in SHOT_SET with another OUT) to decide them.")
    md += ["", "Lambert-Jonas fits, vr = a (v^p - v_bl^p)^(1/p):", "", lj.fit_markdown(fits)]
    (out / "sweep.md").write_text("\n".join(md))
    (out / "sweep.json").write_text(json.dumps({"runs": rows, "fits": fits,
                                                "undecided_runs_left_out_of_the_fit": len(undecided),
                                                "comparison": str(args.comparison)}, indent=2) + "\n")

    # The plot.
    fig, ax = plt.subplots(figsize=(7.5, 5))
    perf = [r for r in fitted if r["outcome"] == "perforated"]
    stop = [r for r in fitted if r["outcome"] != "perforated"]
    ax.plot([r["impact_velocity_m_s"] for r in perf], [r["residual_velocity_m_s"] for r in perf], "o", ms=4,
            color="C0", label="runs (perforated)")
    if stop:
        ax.plot([r["impact_velocity_m_s"] for r in stop], [0.0] * len(stop), "o", ms=4, mfc="none", color="C0",
                label="runs (not perforated: 0)")
    if undecided:
        ax.plot([r["impact_velocity_m_s"] for r in undecided], [0.0] * len(undecided), "x", color="0.5",
                label="runs (undecided, not fitted)")
    if experiments:
        ax.plot([e[0] for e in experiments], [e[1] for e in experiments], "s", color="C3", label="Table 5 experiments")
    if paper:
        ax.plot([p[0] for p in paper], [p[1] for p in paper], "^", color="C2", label="Table 8 (paper's simulations)")
    vmax = max([r["impact_velocity_m_s"] for r in rows] + [e[0] for e in experiments] + [1.0])
    grid = np.linspace(0.0, vmax * 1.02, 300)
    if "sweep" in fits:
        f = fits["sweep"]
        ax.plot(grid, lj.model(grid, f["a"], f["v_bl_m_s"], f["p"]), "-", color="C0",
                label=f"fit of the runs: a {f['a']:.2f}, v_bl {f['v_bl_m_s']:.0f} m/s, p {f['p']:.2f}")
        if samples:
            curves = np.array([lj.model(grid, *s) for s in samples])
            ax.fill_between(grid, np.percentile(curves, 2.5, axis=0), np.percentile(curves, 97.5, axis=0),
                            color="C0", alpha=0.2, lw=0, label="95 % bootstrap band")
    if "experiments" in fits:
        f = fits["experiments"]
        ax.plot(grid, lj.model(grid, f["a"], f["v_bl_m_s"], f["p"]), "--", color="C3",
                label=f"fit of Table 5: a {f['a']:.2f}, v_bl {f['v_bl_m_s']:.0f} m/s, p {f['p']:.2f}")
    ax.set_xlabel("impact velocity [m/s]")
    ax.set_ylabel("residual velocity [m/s]")
    ax.set_xlim(left=min([r["impact_velocity_m_s"] for r in rows] + [e[0] for e in experiments]) - 20)
    ax.set_ylim(bottom=-10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper left")
    fig.tight_layout()
    fig.savefig(out / "sweep.png", dpi=120)
    print("\n".join(md))


def thickness(args):
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    studies = []
    for group in args.runs:
        t, dirs = float(group[0]), group[1:]
        rows = sorted((run_row(pathlib.Path(d) / "result.json") for d in dirs),
                      key=lambda r: r["impact_velocity_m_s"])
        decided = [r for r in rows if r["residual_velocity_m_s"] is not None]
        below = [r["impact_velocity_m_s"] for r in decided if r["outcome"] != "perforated"]
        above = [r["impact_velocity_m_s"] for r in decided if r["outcome"] == "perforated"]
        bracket = [max(below) if below else None, min(above) if above else None]
        fit = None
        if len(above) >= 2:  # two constants: at least two perforating runs determine them
            fit = lj.fit([r["impact_velocity_m_s"] for r in decided], [r["residual_velocity_m_s"] for r in decided],
                         p_fixed=2.0)
            # a and v_bl from as many runs leave nothing to test the fit against: its RMS is 0 by construction
            fit["degrees_of_freedom"] = len(decided) - 2
        studies.append({"thickness_m": t, "runs": rows, "ballistic_limit_bracket_m_s": bracket,
                        "lambert_jonas_p2": fit,
                        "undecided": [r["impact_velocity_m_s"] for r in rows if r["residual_velocity_m_s"] is None]})
    studies.sort(key=lambda s: s["thickness_m"])
    measured = []
    if args.measured and pathlib.Path(args.measured).is_dir():
        for res in sorted(pathlib.Path(args.measured).glob("v*/result.json")):
            measured.append(run_row(res))
    experiments = read_table(args.experiments, ["impact_velocity", "residual_velocity", "thickness"]) \
        if args.experiments else []

    md = ["| thickness mm | runs | residual velocity m/s at v0 m/s | ballistic limit bracket m/s | "
          "v_bl (Lambert-Jonas, p = 2) m/s | a | RMS of the fit m/s |", "|---|---|---|---|---|---|---|"]
    for s in studies:
        vr_cells = ", ".join(f"{r['impact_velocity_m_s']:g}: " + ("undecided" if r["residual_velocity_m_s"] is None
                                                                  else f"{r['residual_velocity_m_s']:.0f}")
                             for r in s["runs"])
        lo, hi = s["ballistic_limit_bracket_m_s"]
        br = f"{'' if lo is None else f'{lo:g}'} .. {'' if hi is None else f'{hi:g}'}"
        f = s["lambert_jonas_p2"]
        md.append(f"| {s['thickness_m'] * 1e3:.2f} | {len(s['runs'])} | {vr_cells} | {br} | "
                  + (f"{f['v_bl_m_s']:.1f}{'' if f['v_bl_bracketed'] else ' (extrapolated)'} | {f['a']:.3f} | "
                     + (f"{f['rms_m_s']:.1f} |" if f["degrees_of_freedom"] > 0 else "exact: 2 runs, 2 constants |")
                     if f else "fewer than 2 perforating runs | | |"))
    md += ["", "Ballistic limit: the bracket is the fastest run that did not perforate .. the slowest that did "
           "(empty end: none); v_bl is the Lambert-Jonas fit of that thickness's runs with p held at 2 "
           "(vr = a (v^2 - v_bl^2)^(1/2); at least two perforating runs), undecided runs left out; with few "
           "velocities trust the bracket first. exact: the fit passes through its two runs and tests nothing. (extrapolated): every run of that thickness perforated, so v_bl "
           "is the fitted curve's foot, not bracketed by the runs."]
    if measured:
        md += ["", "The seven shots at their measured thickness (`make shots-measured`) and the experiments:", "",
               "| v0 m/s | thickness mm | outcome | vr m/s | Table 5 vr m/s |", "|---|---|---|---|---|"]
        exp_at = {round(e[0]): e for e in experiments}
        for r in sorted(measured, key=lambda r: r["impact_velocity_m_s"]):
            e = exp_at.get(round(r["impact_velocity_m_s"]))
            vr_cell = "" if r["residual_velocity_m_s"] is None else f"{r['residual_velocity_m_s']:.0f}"
            md.append(f"| {r['impact_velocity_m_s']:g} | {r['thickness_m'] * 1e3:.2f} | {r['outcome']} | {vr_cell} | "
                      f"{'' if e is None else f'{e[1]:g}'} |")
    (out / "thickness.md").write_text("\n".join(md) + "\n")
    (out / "thickness.json").write_text(json.dumps({"thicknesses": studies, "measured_shots": measured,
                                                    "ballistic_limit": "bracket of the runs and v_bl of the "
                                                    "Lambert-Jonas fit with p = 2"}, indent=2) + "\n")

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.5))
    velocities = sorted({r["impact_velocity_m_s"] for s in studies for r in s["runs"]})
    for k, v in enumerate(velocities):
        pts = [(s["thickness_m"] * 1e3, r["residual_velocity_m_s"]) for s in studies for r in s["runs"]
               if r["impact_velocity_m_s"] == v and r["residual_velocity_m_s"] is not None]
        if pts:
            ax1.plot(*zip(*pts), "o-", color=f"C{k % 10}", label=f"{v:g} m/s")
    if measured:
        m = [(r["thickness_m"] * 1e3, r["residual_velocity_m_s"]) for r in measured
             if r["residual_velocity_m_s"] is not None and r["thickness_m"]]
        if m:
            ax1.plot(*zip(*m), "D", mfc="none", color="k", label="shots at measured thickness")
    if experiments:
        ax1.plot([e[2] for e in experiments], [e[1] for e in experiments], "s", color="C3", ms=5,
                 label="Table 5 experiments")
    ax1.set_xlabel("thickness [mm]")
    ax1.set_ylabel("residual velocity [m/s]")
    ax1.grid(alpha=0.3)
    ax1.legend(fontsize=7)
    t_mm = [s["thickness_m"] * 1e3 for s in studies]
    vbl = [s["lambert_jonas_p2"]["v_bl_m_s"] if s["lambert_jonas_p2"] else np.nan for s in studies]
    ax2.plot(t_mm, vbl, "o-", color="C0", label="v_bl, Lambert-Jonas fit (p = 2)")
    for s, x in zip(studies, t_mm):
        lo, hi = s["ballistic_limit_bracket_m_s"]
        if lo is not None or hi is not None:
            ax2.plot([x, x], [lo if lo is not None else 0.0, hi if hi is not None else max(velocities)], "-",
                     color="0.5", lw=6, alpha=0.4)
    ax2.plot([], [], "-", color="0.5", lw=6, alpha=0.4, label="bracket of the runs")
    ax2.set_xlabel("thickness [mm]")
    ax2.set_ylabel("ballistic limit [m/s]")
    ax2.grid(alpha=0.3)
    ax2.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out / "thickness.png", dpi=120)
    print("\n".join(md))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = ap.add_subparsers(dest="command", required=True)
    a = sub.add_parser("sweep")
    a.add_argument("comparison")
    a.add_argument("--experiments")
    a.add_argument("--paper")
    a.add_argument("--bootstrap", type=int, default=1000)
    a.add_argument("--seed", type=int, default=20261205)
    a.add_argument("--out", required=True)
    b = sub.add_parser("thickness")
    b.add_argument("--runs", nargs="+", action="append", required=True, metavar="T DIR",
                   help="a thickness in m, then its run directories")
    b.add_argument("--measured")
    b.add_argument("--experiments")
    b.add_argument("--out", required=True)
    args = ap.parse_args()
    sweep(args) if args.command == "sweep" else thickness(args)


if __name__ == "__main__":
    main()
