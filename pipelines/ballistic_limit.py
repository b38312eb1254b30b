#!/usr/bin/env python3
"""The ballistic limit of a case by bisection on the outcome of each run: the highest impact velocity
that does not perforate and the lowest that does, bracketed to a stated width.

usage: ballistic_limit.py --macro UHPC_MACRO --config CASE.json [--sdel SDEL.json] [--set key=value ...]
                          --low V_LOW --high V_HIGH [--width 10] [--end-time 1e-3] [--launch PREFIX] --out DIR

Each run is uhpc-macro at one velocity (rounded to 1 m/s) in DIR/v<velocity>/; a run whose result.json
exists is read, not rerun, so an interrupted bisection resumes. The bracket's ends are run first: if the
low end perforates (or the high end does not) the bracket is widened by its own width on that side,
down to 50 m/s. A run counts as perforating when result.json says "perforated"; embedded, rebounded and
undecided runs do not perforate (an undecided one is flagged: its end time was too short to decide it).
--launch puts a launcher before each run, split as a shell would (e.g. --launch "srun -N1 -n1 -c2
--exclusive" inside a Slurm allocation: docs/cluster.md); empty (default): the runs start here.
Writes DIR/ballistic_limit.json and DIR/ballistic_limit.md (the bracket, every run in the order it was
made, with its outcome and residual velocity).
"""
import argparse
import json
import math
import pathlib
import shlex
import subprocess
import sys


def run(args, velocity, runs):
    """The outcome at one velocity; a velocity is listed in runs once, however often the bisection asks."""
    for r in runs:
        if r["velocity_m_s"] == velocity:
            return r
    out = pathlib.Path(args.out) / f"v{velocity}"
    result = out / "result.json"
    if not result.is_file():
        cmd = shlex.split(args.launch) + [args.macro, "--config", args.config, "-q", "--out", str(out),
               "--set", f"projectile.velocity_m_s={velocity}", "--set", f"run.end_time_s={args.end_time}"]
        if args.sdel:
            cmd += ["--sdel", args.sdel]
        for s in args.set or []:
            cmd += ["--set", s]
        print("ballistic_limit.py:", " ".join(cmd), flush=True)
        done = subprocess.run(cmd)
        if done.returncode != 0:
            sys.exit(f"ballistic_limit.py: the run at {velocity} m/s failed (exit {done.returncode}); see {out}")
    r = json.loads(result.read_text())
    runs.append({"velocity_m_s": velocity, "outcome": r.get("outcome", "perforated" if r["perforated"] else "not perforated"),
                 "perforated": bool(r["perforated"]), "residual_velocity_m_s": r["residual_velocity_m_s"],
                 "final_velocity_m_s": r["final_velocity_m_s"], "end_time_s": r["end_time_s"], "run": str(out)})
    return runs[-1]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--macro", required=True)
    ap.add_argument("--launch", default="", help="launcher prefix of each run, e.g. \"srun -N1 -n1 -c2 --exclusive\"")
    ap.add_argument("--config", required=True)
    ap.add_argument("--sdel")
    ap.add_argument("--set", action="append")
    ap.add_argument("--low", type=float, required=True)
    ap.add_argument("--high", type=float, required=True)
    ap.add_argument("--width", type=float, default=10.0)
    ap.add_argument("--end-time", type=float, default=1e-3)
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    if not (0 < args.low < args.high) or args.width <= 0:
        sys.exit("ballistic_limit.py: need 0 < --low < --high and --width > 0")
    pathlib.Path(args.out).mkdir(parents=True, exist_ok=True)
    runs = []
    lo, hi = int(round(args.low)), int(round(args.high))
    step = hi - lo
    while True:  # the low end must not perforate
        r = run(args, lo, runs)
        if not r["perforated"]:
            break
        hi, lo = lo, max(50, lo - step)
        if hi == 50:
            sys.exit("ballistic_limit.py: every velocity down to 50 m/s perforates")
    while True:  # the high end must perforate
        r = run(args, hi, runs)
        if r["perforated"]:
            break
        lo, hi = hi, hi + step
    while hi - lo > args.width:
        mid = int(round(0.5 * (lo + hi)))
        if mid in (lo, hi):
            break
        r = run(args, mid, runs)
        if r["perforated"]:
            hi = mid
        else:
            lo = mid
    undecided = [r["velocity_m_s"] for r in runs if r["outcome"] == "undecided"]
    summary = {"highest_not_perforating_m_s": lo, "lowest_perforating_m_s": hi, "bracket_width_m_s": hi - lo,
               "estimate_m_s": 0.5 * (lo + hi), "runs": runs, "undecided_runs_m_s": undecided,
               "config": args.config, "sdel": args.sdel, "overrides": args.set or [], "end_time_s": args.end_time}
    out = pathlib.Path(args.out)
    (out / "ballistic_limit.json").write_text(json.dumps(summary, indent=2) + "\n")
    md = [f"Ballistic limit between {lo} m/s (does not perforate) and {hi} m/s (perforates): "
          f"{0.5 * (lo + hi):.0f} +- {0.5 * (hi - lo):.0f} m/s, {len(runs)} runs.", "",
          "| order | v0 m/s | outcome | residual m/s | final m/s | end us |", "|---|---|---|---|---|---|"]
    for k, r in enumerate(runs, 1):
        vr = r["residual_velocity_m_s"]
        md.append(f"| {k} | {r['velocity_m_s']} | {r['outcome']} | {'-' if vr is None else f'{vr:.1f}'} | "
                  f"{r['final_velocity_m_s']:.1f} | {r['end_time_s'] * 1e6:.0f} |")
    if undecided:
        md += ["", f"Undecided at the end time (counted as not perforating): {undecided} m/s."]
    (out / "ballistic_limit.md").write_text("\n".join(md) + "\n")
    print("\n".join(md))


if __name__ == "__main__":
    main()
