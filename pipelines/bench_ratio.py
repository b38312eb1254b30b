#!/usr/bin/python3
"""Our paper-disc speed over LAMMPS's at equal core counts (make -C pipelines bench-ratio).

Reads
  --macro   Google Benchmark JSON of uhpc_bench_macro (build/bench/macro.json from `make -C pipelines
            bench`: 3 repetitions, aggregates only, so the *_mean rows are used; when a run has no
            *_mean row, e.g. --benchmark_repetitions=1, its plain rows are used, averaged if several).
            The BM_PaperDisc* rows are taken: items_per_second is particle-steps/s, peak_rss_MiB the
            process's peak resident set so far (clean only when the configuration ran alone).
  --lammps  lammps.json of pipelines/bench_lammps.sh (make -C pipelines bench-lammps).
and writes a markdown table (printed, and <out>/ratio.md) and <out>/ratio.json: every paper-disc
configuration present with threads, particle-steps/s and peak memory, LAMMPS on 1 and 2 processes, and
ours / LAMMPS at the same number of cores (threads = processes).

Exit 0 on success; 2 on a missing or bad input file, with one line naming the file and the reason.
Debian's python3, standard library only.
"""
import argparse
import json
import os
import sys

PREFIX = "BM_PaperDisc"


class InputError(Exception):
    def __init__(self, path, reason):
        super().__init__(f"{path}: {reason}")


def load_json(path, hint):
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except FileNotFoundError:
        raise InputError(path, f"missing ({hint})")
    except json.JSONDecodeError as e:
        raise InputError(path, f"not JSON (line {e.lineno}, column {e.colno}: {e.msg})")
    except OSError as e:
        raise InputError(path, f"cannot read ({e.strerror})")


def number(row, key, path, what):
    value = row.get(key)
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise InputError(path, f"{what}: '{key}' missing or not a number")
    return float(value)


STRAIN = {0: "midpoint", 1: "end", 2: "endpoint average"}  # bench_solver.cpp's strain argument


def parse_arguments(run_name):
    """'BM_PaperDisc100/threads:2/support_x10:25/nsni:1' -> ('BM_PaperDisc100', {'threads': 2, ...})."""
    parts = run_name.split("/")
    args = {}
    for part in parts[1:]:
        key, sep, value = part.partition(":")
        if sep:
            try:
                args[key] = int(value)
            except ValueError:
                args[key] = value
    return parts[0], args


def read_macro(path):
    doc = load_json(path, "run `make -C pipelines bench` first, or uhpc_bench_macro --benchmark_out=...")
    if not isinstance(doc, dict) or not isinstance(doc.get("benchmarks"), list):
        raise InputError(path, "no 'benchmarks' list (not Google Benchmark JSON output)")
    groups = {}  # run name -> {"mean": row or None, "plain": [rows]}
    order = []
    for row in doc["benchmarks"]:
        if not isinstance(row, dict) or not isinstance(row.get("name"), str):
            raise InputError(path, "a 'benchmarks' entry without a 'name'")
        aggregate = row.get("aggregate_name")
        run_name = row.get("run_name")
        if not run_name:  # older Google Benchmark: the aggregate's name carries the suffix
            run_name = row["name"]
            if aggregate and run_name.endswith("_" + aggregate):
                run_name = run_name[: -len("_" + aggregate)]
        if not run_name.startswith(PREFIX):
            continue
        if run_name not in groups:
            groups[run_name] = {"mean": None, "plain": []}
            order.append(run_name)
        if row.get("run_type") == "aggregate":
            if aggregate == "mean":
                groups[run_name]["mean"] = row
        else:
            groups[run_name]["plain"].append(row)
    if not order:
        raise InputError(path, f"no {PREFIX}* rows (was the disc benchmark filtered out?)")

    runs = []
    for run_name in order:
        group = groups[run_name]
        family, args = parse_arguments(run_name)
        entry = {"name": run_name, "benchmark": family, "threads": args.get("threads"),
                 "support_factor": args["support_x10"] / 10.0 if isinstance(args.get("support_x10"), int) else None,
                 "nsni": bool(args["nsni"]) if isinstance(args.get("nsni"), int) else None,
                 "strain": STRAIN.get(args.get("strain")),
                 # lazy RK rows: shape_reuse_tolerance x 1e4 (0 or absent: every row rebuilt every step)
                 "shape_reuse_tolerance": 1e-4 * args["reuse_e4"] if isinstance(args.get("reuse_e4"), int) else 0.0}
        rows = [group["mean"]] if group["mean"] is not None else group["plain"]
        entry["source"] = "mean of repetitions" if group["mean"] is not None else (
            "single run" if len(rows) == 1 else f"average of {len(rows)} runs")
        failed = [r for r in rows if r.get("error_occurred")]
        if not rows or failed:
            message = failed[0].get("error_message", "error") if failed else "no rows"
            entry.update({"error": message})
            runs.append(entry)
            continue
        if not isinstance(entry["threads"], int):
            raise InputError(path, f"{run_name}: no 'threads:<n>' argument in the name")
        rate = sum(number(r, "items_per_second", path, run_name) for r in rows) / len(rows)
        entry["particle_steps_per_s"] = rate
        # Timed steps per run: the fixed Iterations(N) is in the name ('iterations:100'); an aggregate
        # row's own 'iterations' is the number of repetitions, so a plain row's is used only as a fallback.
        if isinstance(args.get("iterations"), int):
            entry["steps"] = args["iterations"]
        elif group["mean"] is None:
            entry["steps"] = int(number(rows[0], "iterations", path, run_name))
        else:
            entry["steps"] = None
        entry["particles"] = int(number(rows[0], "particles", path, run_name)) if "particles" in rows[0] else None
        if "peak_rss_MiB" in rows[0]:
            entry["peak_rss_MiB"] = max(number(r, "peak_rss_MiB", path, run_name) for r in rows)
        else:
            entry["peak_rss_MiB"] = None
        runs.append(entry)
    context = doc.get("context", {}) if isinstance(doc.get("context"), dict) else {}
    return runs, {k: context.get(k) for k in ("date", "host_name", "num_cpus", "load_avg") if k in context}


def read_lammps(path):
    doc = load_json(path, "run `make -C pipelines bench-lammps` first")
    if not isinstance(doc, dict) or not isinstance(doc.get("runs"), list) or not doc["runs"]:
        raise InputError(path, "no 'runs' list or no runs in it (not written by pipelines/bench_lammps.sh?)")
    runs = {}
    for row in doc["runs"]:
        if not isinstance(row, dict):
            raise InputError(path, "a 'runs' entry is not an object")
        processes = int(number(row, "processes", path, "run"))
        what = f"the {processes}-process run"
        runs[processes] = {
            "processes": processes,
            "atoms": int(number(row, "atoms", path, what)),
            "steps": int(number(row, "steps", path, what)),
            "loop_time_s": number(row, "loop_time_s", path, what),
            "particle_steps_per_s": number(row, "particle_steps_per_s", path, what),
            "cpu_use_percent": row.get("cpu_use_percent"),  # LAMMPS's "% CPU use" (newer lammps.json)
        }
    return runs, doc.get("version", ""), doc.get("load_average_1min_at_start")


def fmt_load(load):
    if isinstance(load, list) and load and all(isinstance(x, (int, float)) for x in load):
        return " / ".join(f"{x:.2f}" for x in load)
    return "?"


def fmt_rate(x):
    return f"{x / 1e3:,.1f}k"


def describe(run):
    label = run["benchmark"]
    parts = []
    if run["support_factor"] is not None:
        parts.append(f"{run['support_factor']:.1f} h")
    if run["nsni"] is not None:
        parts.append("NSNI" if run["nsni"] else "no NSNI")
    if run.get("strain"):
        parts.append(run["strain"])
    if run.get("shape_reuse_tolerance"):
        parts.append(f"lazy rows {run['shape_reuse_tolerance']:.0e}")
    return f"{label} ({', '.join(parts)})" if parts else label


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--macro", required=True, help="uhpc_bench_macro JSON (build/bench/macro.json)")
    parser.add_argument("--lammps", required=True, help="lammps.json of bench_lammps.sh")
    parser.add_argument("--out", required=True, help="directory for ratio.md and ratio.json")
    a = parser.parse_args()

    try:
        ours, context = read_macro(a.macro)
        lammps, version, lammps_load = read_lammps(a.lammps)
    except InputError as e:
        print(f"bench_ratio: {e}", file=sys.stderr)
        return 2

    # The figure (BM_PaperDisc100) first, then the 8-step product; within each by threads.
    ours.sort(key=lambda r: (r["benchmark"] != PREFIX + "100", r["support_factor"] or 0,
                             not r["nsni"], r.get("shape_reuse_tolerance") or 0, r["threads"] or 0))
    lines = ["| code | configuration | cores | steps | particles | particle-steps/s | peak RSS MiB | ours / LAMMPS |",
             "|---|---|---|---|---|---|---|---|"]
    for r in ours:
        if "error" in r:
            lines.append(f"| ours | {describe(r)} | {r['threads']} | | | failed: {r['error']} | | |")
            continue
        peer = lammps.get(r["threads"])
        r["lammps_particle_steps_per_s"] = peer["particle_steps_per_s"] if peer else None
        r["ratio_to_lammps"] = r["particle_steps_per_s"] / peer["particle_steps_per_s"] if peer else None
        ratio = f"{r['ratio_to_lammps']:.3f}" if peer else "no LAMMPS run"
        peak = f"{r['peak_rss_MiB']:.0f}" if r["peak_rss_MiB"] is not None else "-"
        particles = f"{r['particles']:,}" if r["particles"] is not None else "-"
        steps = r["steps"] if r["steps"] is not None else "-"
        lines.append(f"| ours | {describe(r)} | {r['threads']} | {steps} | {particles} | "
                     f"{fmt_rate(r['particle_steps_per_s'])} | {peak} | {ratio} |")
    for p in sorted(lammps):
        l = lammps[p]
        cpu = l["cpu_use_percent"]
        label = f"peri/pmb (CPU use {cpu} %)" if isinstance(cpu, (int, float)) else "peri/pmb"
        lines.append(f"| LAMMPS | {label} | {p} | {l['steps']} | {l['atoms']:,} | "
                     f"{fmt_rate(l['particle_steps_per_s'])} | - | |")
    notes = [
        "",
        "cores: OpenMP threads for ours, MPI processes for LAMMPS; ratio = ours / LAMMPS at the same count.",
        f"LAMMPS: {version or 'version unknown'}; 1-min load average at its start {lammps_load or '?'}. "
        f"Ours: {context.get('date', '?')}, load average {fmt_load(context.get('load_avg'))} "
        f"on {context.get('num_cpus', '?')} CPUs.",
        "Peak RSS is the benchmark process's peak so far: clean only for a configuration run alone.",
    ]
    table = "\n".join(lines + notes) + "\n"
    print(table, end="")

    result = {"macro": os.path.abspath(a.macro), "lammps": os.path.abspath(a.lammps),
              "macro_context": context, "lammps_version": version, "ours": ours,
              "lammps_runs": [lammps[p] for p in sorted(lammps)]}
    try:
        os.makedirs(a.out, exist_ok=True)
        with open(os.path.join(a.out, "ratio.md"), "w", encoding="utf-8") as f:
            f.write(table)
        with open(os.path.join(a.out, "ratio.json"), "w", encoding="utf-8") as f:
            json.dump(result, f, indent=2)
            f.write("\n")
    except OSError as e:
        print(f"bench_ratio: {e.filename or a.out}: cannot write ({e.strerror})", file=sys.stderr)
        return 2
    print(f"bench_ratio: {os.path.join(a.out, 'ratio.md')}, {os.path.join(a.out, 'ratio.json')}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
