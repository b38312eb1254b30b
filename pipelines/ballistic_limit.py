#!/usr/bin/env python3
"""The ballistic limit of a case by bisection on the outcome of each run: the highest impact velocity
that does not perforate and the lowest that does, bracketed to a stated width.

usage: ballistic_limit.py --macro UHPC_MACRO --config CASE.json [--sdel SDEL.json] [--set key=value ...]
                          --low V_LOW --high V_HIGH [--width 10] [--end-time T] [--max-end-time T]
                          [--launch PREFIX] [--checkpoint-every-min M] --out DIR

Each run is uhpc-macro at one velocity (rounded to 1 m/s) in DIR/v<velocity>/, made, kept or carried on
as pipelines/carried_shot.py says: a run whose result.json exists is read, not rerun, so an interrupted
bisection resumes, but only if it was made from the same inputs (the case with every --set, the end time
and the files read; otherwise the bisection stops with exit 2 naming the run, rather than mix runs of
another case); a run still undecided at its end time (--end-time, else a --set run.end_time_s, else the
case's) is carried on from its checkpoint (uhpc-macro --restart) to twice that end time, and so on up to
--max-end-time (default: the end time, no extension), so that runs near the limit are decided by what the
sphere does rather than by when the run stops. The bracket's ends are run first: if the
low end perforates (or the high end does not) the bracket is widened by its own width on that side,
down to 50 m/s. A run counts as perforating when result.json says "perforated"; embedded, rebounded and
undecided runs do not perforate (an undecided one is flagged: its end time was too short to decide it).
A run that fails numerically (exit 1 with DIR/v<velocity>/diagnostic.json) is recorded as failed and the
bisection goes on around it (the bracket's midpoint, then a quarter of the bracket to either side), up to
--max-failures failed runs; the bracket it could establish is reported. A failed end of the bracket
stops the bisection; so does any other end of a run (bad input, a signal, a launcher's error).
Exit codes: 0 the bracket to --width; 1 no such bracket (failed runs left it wider, a failed end,
nothing perforating up to --max-velocity, everything perforating down to 50 m/s), the reports written
when a bracket exists; 2 bad input (the arguments, uhpc-macro's exit 2, a run made from other inputs);
3 a run that neither finished nor failed numerically (killed, or its launcher failed).
--launch puts a launcher before each run, split as a shell would (e.g. --launch "srun -N1 -n1 -c2
--exclusive" inside a Slurm allocation: docs/cluster.md); empty (default): the runs start here.
Writes DIR/ballistic_limit.json and DIR/ballistic_limit.md (the bracket, every run in the order it was
made, with its outcome and residual velocity, the failed runs with their diagnostics).
"""
import argparse
import json
import math
import pathlib
import sys

from carried_shot import Shot, add_shot_arguments, end_time_and_sets


def failed_run(runs, velocity, out, exit_code):
    diagnostic = out / "diagnostic.json"
    runs.append({"velocity_m_s": velocity, "outcome": "failed", "perforated": None, "exit_code": exit_code,
                 "residual_velocity_m_s": None, "final_velocity_m_s": None, "end_time_s": None,
                 "diagnostic": str(diagnostic) if diagnostic.is_file() else None, "run": str(out)})
    return runs[-1]


def run(args, velocity, runs):
    """The outcome at one velocity; a velocity is listed in runs once, however often the bisection asks."""
    for r in runs:
        if r["velocity_m_s"] == velocity:
            return r
    out = pathlib.Path(args.out) / f"v{velocity}"
    r, failure = args.shot.decide(velocity, out)
    if r is None:
        return failed_run(runs, velocity, out, failure)
    runs.append({"velocity_m_s": velocity, "outcome": r.get("outcome", "perforated" if r["perforated"] else "not perforated"),
                 "perforated": bool(r["perforated"]), "residual_velocity_m_s": r["residual_velocity_m_s"],
                 "final_velocity_m_s": r["final_velocity_m_s"], "end_time_s": r["end_time_s"],
                 "carried_on": r["end_time_s"] > args.end_time * (1.0 + 1e-9),
                 "run": str(out)})
    return runs[-1]


def end_of_bracket(args, velocity, runs):
    """A run at an end of the bracket, which must decide: a failed one stops the bisection."""
    r = run(args, velocity, runs)
    if r["outcome"] == "failed":
        sys.exit(f"ballistic_limit.py: the run at {velocity} m/s failed at an end of the bracket; see {r['run']}")
    return r


def next_velocity(lo, hi, failed):
    """The bracket's midpoint, or a quarter of the bracket to either side of it if the midpoint failed."""
    mid = int(round(0.5 * (lo + hi)))
    quarter = max(1, int(round(0.25 * (hi - lo))))
    for v in (mid, mid + quarter, mid - quarter):
        if lo < v < hi and v not in failed:
            return v
    return None


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_shot_arguments(ap)
    ap.add_argument("--low", type=float, required=True)
    ap.add_argument("--high", type=float, required=True)
    ap.add_argument("--width", type=float, default=10.0)
    ap.add_argument("--end-time", type=float, help="default: a --set run.end_time_s, else the case's")
    ap.add_argument("--max-end-time", type=float, help="an undecided run is carried on up to it (default: --end-time)")
    ap.add_argument("--max-failures", type=int, default=3, help="failed runs inside the bracket before it stops")
    ap.add_argument("--max-velocity", type=float, default=3000.0, help="the bracket's high end is widened up to it")
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    args.end_time, sets = end_time_and_sets("ballistic_limit.py", args.set, args.end_time, args.config)
    if args.max_end_time is None:
        args.max_end_time = args.end_time
    if not (0 < args.low < args.high <= args.max_velocity) or args.width <= 0 or args.max_failures < 0 \
            or not 0 < args.end_time <= args.max_end_time or not 0 <= args.checkpoint_every_min < math.inf:
        print("ballistic_limit.py: need 0 < --low < --high <= --max-velocity, --width > 0, --max-failures >= 0, "
              "0 < --end-time <= --max-end-time, --checkpoint-every-min >= 0", file=sys.stderr)
        sys.exit(2)
    pathlib.Path(args.out).mkdir(parents=True, exist_ok=True)
    args.shot = Shot("ballistic_limit.py", args.macro, args.launch, args.config, args.sdel, sets, args.end_time,
                     args.max_end_time, args.checkpoint_every_min)
    runs = []
    lo, hi = int(round(args.low)), int(round(args.high))
    step = hi - lo
    while True:  # the low end must not perforate
        r = end_of_bracket(args, lo, runs)
        if not r["perforated"]:
            break
        hi, lo = lo, max(50, lo - step)
        if hi == 50:
            sys.exit("ballistic_limit.py: every velocity down to 50 m/s perforates")
    while True:  # the high end must perforate
        r = end_of_bracket(args, hi, runs)
        if r["perforated"]:
            break
        if hi + step > args.max_velocity:
            sys.exit(f"ballistic_limit.py: nothing perforates up to {hi} m/s (--max-velocity {args.max_velocity:g})")
        lo, hi = hi, hi + step
    failed = []
    while hi - lo > args.width and len(failed) < args.max_failures:
        mid = next_velocity(lo, hi, failed)
        if mid is None or mid in (lo, hi):
            break
        r = run(args, mid, runs)
        if r["outcome"] == "failed":
            failed.append(mid)
        elif r["perforated"]:
            hi = mid
        else:
            lo = mid
    undecided = [r["velocity_m_s"] for r in runs if r["outcome"] == "undecided"]
    summary = {"highest_not_perforating_m_s": lo, "lowest_perforating_m_s": hi, "bracket_width_m_s": hi - lo,
               "estimate_m_s": 0.5 * (lo + hi), "runs": runs, "undecided_runs_m_s": undecided, "failed_runs_m_s": failed,
               "width_reached": hi - lo <= args.width,
               "config": args.config, "sdel": args.sdel, "overrides": sets, "end_time_s": args.end_time,
               "max_end_time_s": args.max_end_time}
    out = pathlib.Path(args.out)
    (out / "ballistic_limit.json").write_text(json.dumps(summary, indent=2) + "\n")
    md = [f"Ballistic limit between {lo} m/s (does not perforate) and {hi} m/s (perforates): "
          f"{0.5 * (lo + hi):.0f} +- {0.5 * (hi - lo):.0f} m/s, {len(runs)} runs.", "",
          "| order | v0 m/s | outcome | residual m/s | final m/s | end us |", "|---|---|---|---|---|---|"]
    for k, r in enumerate(runs, 1):
        vr, vf, end = r["residual_velocity_m_s"], r["final_velocity_m_s"], r["end_time_s"]
        md.append(f"| {k} | {r['velocity_m_s']} | {r['outcome']} | {'-' if vr is None else f'{vr:.1f}'} | "
                  f"{'-' if vf is None else f'{vf:.1f}'} | {'-' if end is None else f'{end * 1e6:.0f}'} |")
    carried = [r["velocity_m_s"] for r in runs if r.get("carried_on")]
    if carried:
        md += ["", f"Carried on past {args.end_time * 1e6:.0f} us because undecided there: {carried} m/s "
               f"(up to {args.max_end_time * 1e6:.0f} us)."]
    if undecided:
        md += ["", f"Undecided at {args.max_end_time * 1e6:.0f} us (counted as not perforating): {undecided} m/s."]
    if failed:
        md += ["", f"Failed runs (numerical failure; their diagnostic.json beside them), bisected around: {failed} m/s."]
    if not summary["width_reached"]:
        md += ["", f"The bracket is {hi - lo} m/s wide, wider than the {args.width:g} m/s asked: the runs inside it failed."]
    (out / "ballistic_limit.md").write_text("\n".join(md) + "\n")
    print("\n".join(md))
    sys.exit(0 if summary["width_reached"] else 1)


if __name__ == "__main__":
    main()
