#!/usr/bin/env python3
"""The band of the residual velocity and of the Lambert-Jonas fit over a set of SDEL samples (issue 51 item 2).

usage: uq_band.py RUNS_DIR --sdels SDEL_DIR [--samples N] [--velocities "V1 V2 ..."]
                  [--experiments TABLE5_CSV] [--paper TABLE8_CSV] [--stable-to 5] --out DIR

RUNS_DIR holds one directory per SDEL sample, s<k>/ (k = 000 ...), each with one run per impact velocity,
v<v>/result.json (uhpc-macro); SDEL_DIR the handoffs sdel_<k>.json they were run with (make -C pipelines
uq-sdel); --samples N takes the samples s000 ... s<N-1> only and --velocities those impact velocities
only (the make target's UQ_SAMPLES and UQ_VELOCITIES: a folder that also holds the runs of an earlier,
larger study is read as asked). Per velocity, the residual velocity of every sample (0 for a shot that
did not perforate, as uhpc-compare-shots counts it; an undecided run is counted so and flagged) and its 5 %, 50 % and 95 %
quantiles (OpenTURNS' empirical quantiles); per sample the Lambert-Jonas fit with p = 1
(lambert_jonas.fit) and the same quantiles of a and v_bl.

Convergence: the band's ends with the first half of the samples against all of them. The band is stable
to --stable-to m/s (default 5) when no end of any velocity's band moves by more than that between the two;
the answer is written with the largest move. The same with the first 4, 8, 16, ... samples, each a doubling
of the row before, up to the largest not above the samples there (`by_samples`): the largest move of a band
end from one row to the next, and the number of samples from which no later doubling moves an end by more
than --stable-to (`samples_needed`: none with fewer than two rows or while the last doubling still does),
so the number of samples a stable band needs is read off one run (with UQ_SAMPLES 4 x 2^k the last row is
all the samples, and the two checks compare the same halves).

Writes DIR/uq_band.json (format uhpc-uq-band/1: the samples and their SDEL files' hashes, each run's
outcome and provenance hash, the bands, the fits, the convergence) and DIR/uq_band.md (the band beside
Tables 5 and 8). Exit 2 on bad input (a missing run or handoff, no sample).
"""
import argparse
import csv
import hashlib
import json
import pathlib
import sys

import numpy as np

import lambert_jonas
from uq_inputs import BadInput, import_openturns, read_json

QUANTILES = (0.05, 0.5, 0.95)


def quantiles(values):
    """5 %, 50 %, 95 % of `values` (OpenTURNS' empirical quantile of a one-dimensional sample)."""
    ot = import_openturns()
    sample = ot.Sample([[float(x)] for x in values])
    return [float(sample.computeQuantilePerComponent(q)[0]) for q in QUANTILES]


def residual_by_velocity(path):
    """Impact velocity -> residual velocity of a table of shots (Table 5 or Table 8: CSV with '#' comments,
    columns 'impact_velocity [m/s]' and 'residual_velocity [m/s]'; a velocity shot twice keeps its first)."""
    with open(path) as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    out = {}
    for row in rows:
        out.setdefault(float(row["impact_velocity [m/s]"]), float(row["residual_velocity [m/s]"]))
    return out


def nearest(table, v, tolerance):
    """The row of `table` (velocity -> value) at v, or nearest to it within `tolerance` m/s (Table 8 lists
    nominal velocities, 820 for the 817 m/s shot); None without one."""
    if not table:
        return None
    w = min(table, key=lambda x: abs(x - v))
    return table[w] if abs(w - v) <= tolerance else None


def collect(runs_dir, sdel_dir, count=None, only_velocities=None):
    samples = sorted(p for p in pathlib.Path(runs_dir).glob("s[0-9][0-9][0-9]") if p.is_dir())
    if not samples:
        raise BadInput(f"{runs_dir}: no sample directory s<k>")
    if count is not None:
        wanted = [pathlib.Path(runs_dir) / f"s{k:03d}" for k in range(count)]
        missing = [p.name for p in wanted if p not in samples]
        if missing:
            raise BadInput(f"{runs_dir}: --samples {count} asks for {', '.join(missing[:3])}"
                           f"{' ...' if len(missing) > 3 else ''}, not there")
        samples = wanted
    velocities = sorted(only_velocities) if only_velocities else sorted(
        {float(p.name[1:]) for s in samples for p in s.glob("v*") if p.is_dir()})
    table = []
    for s in samples:
        sdel = pathlib.Path(sdel_dir) / f"sdel_{s.name[1:]}.json"
        if not sdel.is_file():
            raise BadInput(f"{sdel}: no such file (the SDEL sample {s.name} was run with)")
        row = {"sample": int(s.name[1:]), "sdel": str(sdel),
               "sdel_sha256": hashlib.sha256(sdel.read_bytes()).hexdigest()[:16], "runs": []}
        for v in velocities:
            result = s / f"v{v:g}" / "result.json"
            r = read_json(result, f"sample {s.name}'s run at {v:g} m/s")
            perforated = r.get("outcome") == "perforated"
            row["runs"].append({"velocity_m_s": v, "outcome": r.get("outcome"),
                                "residual_velocity_m_s": float(r["residual_velocity_m_s"]) if perforated else 0.0,
                                "config_hash": r.get("provenance", {}).get("config_hash")})
        table.append(row)
    return velocities, table


def band(velocities, table, stable_to):
    vr = np.array([[run["residual_velocity_m_s"] for run in row["runs"]] for row in table])  # samples x velocities
    n = vr.shape[0]
    half = max(n // 2, 1)
    out = []
    worst_move = 0.0
    for j, v in enumerate(velocities):
        q_all, q_half = quantiles(vr[:, j]), quantiles(vr[:half, j])
        move = max(abs(q_all[0] - q_half[0]), abs(q_all[2] - q_half[2]))
        worst_move = max(worst_move, move)
        out.append({"velocity_m_s": v, "q05": q_all[0], "median": q_all[1], "q95": q_all[2],
                    "mean": float(vr[:, j].mean()), "std": float(vr[:, j].std(ddof=1)) if n > 1 else 0.0,
                    "undecided": sum(row["runs"][j]["outcome"] == "undecided" for row in table),
                    "not_perforated": sum(row["runs"][j]["outcome"] != "perforated" for row in table),
                    "band_end_move_from_first_half_m_s": move})
    by_samples = band_by_samples(vr)
    needed = None  # the first row from which no later row moves an end by more than stable_to
    for i in range(len(by_samples) - 1, 0, -1):
        if by_samples[i]["largest_move_from_previous_m_s"] > stable_to:
            break
        needed = by_samples[i - 1]["samples"]
    convergence = {"samples": n, "first_half": half, "stable_to_m_s": stable_to,
                   "largest_band_end_move_m_s": worst_move, "stable": bool(n >= 4 and worst_move <= stable_to),
                   "by_samples": by_samples, "samples_needed": needed}
    return vr, out, convergence


def band_by_samples(vr):
    """The band's ends of every velocity with the first 4, 8, 16, ... samples (doublings, up to n; n alone
    below 4), and the largest move of an end from the row before (None in the first row)."""
    n = vr.shape[0]
    counts = []
    k = 4
    while k <= n:
        counts.append(k)
        k *= 2
    counts = counts or [n]
    rows, previous = [], None
    for k in counts:
        ends = [quantiles(vr[:k, j]) for j in range(vr.shape[1])]
        q05, q95 = [e[0] for e in ends], [e[2] for e in ends]
        move = None if previous is None else max(
            max(abs(a - b) for a, b in zip(q05, previous[0])), max(abs(a - b) for a, b in zip(q95, previous[1])))
        rows.append({"samples": k, "q05": q05, "q95": q95, "largest_move_from_previous_m_s": move})
        previous = (q05, q95)
    return rows


def fits(velocities, vr):
    """The Lambert-Jonas fit (p = 1) of each sample and the quantiles of a and v_bl."""
    v = np.array(velocities)
    per_sample = [lambert_jonas.fit(v, row, p_fixed=1.0) for row in vr]
    summary = {}
    for key in ("a", "v_bl_m_s"):
        q = quantiles([f[key] for f in per_sample])
        summary[key] = {"q05": q[0], "median": q[1], "q95": q[2]}
    return per_sample, summary


def markdown(bands, fit_summary, convergence, experiments, paper, source):
    md = [f"# The residual velocity over {convergence['samples']} SDEL samples" + (f" ({source})" if source else ""), "",
          "| v0 m/s | vr 5 % | median | 95 % | experiment (Table 5) | inside | paper (Table 8) | not perforated |",
          "|---|---|---|---|---|---|---|---|"]
    for b in bands:
        e, p = nearest(experiments, b["velocity_m_s"], 0.5), nearest(paper, b["velocity_m_s"], 10.0)
        inside = "-" if e is None else ("yes" if b["q05"] <= e <= b["q95"] else "no")
        md.append(f"| {b['velocity_m_s']:g} | {b['q05']:.1f} | {b['median']:.1f} | {b['q95']:.1f} | "
                  f"{'-' if e is None else f'{e:g}'} | {inside} | {'-' if p is None else f'{p:g}'} | "
                  f"{b['not_perforated']} |")
    md += ["", "Lambert-Jonas fit of each sample, p = 1: "
           f"a {fit_summary['a']['q05']:.3f} / {fit_summary['a']['median']:.3f} / {fit_summary['a']['q95']:.3f}, "
           f"v_bl {fit_summary['v_bl_m_s']['q05']:.0f} / {fit_summary['v_bl_m_s']['median']:.0f} / "
           f"{fit_summary['v_bl_m_s']['q95']:.0f} m/s (5 % / median / 95 %).", "",
           f"Convergence: the band's ends move by at most {convergence['largest_band_end_move_m_s']:.1f} m/s from "
           f"the first {convergence['first_half']} samples to all {convergence['samples']}: "
           + ("stable" if convergence["stable"] else "not stable")
           + f" to {convergence['stable_to_m_s']:g} m/s"
           + ("" if convergence["stable"] else " (run more samples: UQ_SAMPLES)") + "."]
    if len(convergence["by_samples"]) > 1:
        md += ["", "| samples | " + " | ".join(f"{b['velocity_m_s']:g} m/s: 5-95 %" for b in bands)
               + " | largest end move from the row above, m/s |",
               "|---|" + "---|" * len(bands) + "---|"]
        for row in convergence["by_samples"]:
            move = row["largest_move_from_previous_m_s"]
            md.append(f"| {row['samples']} | " + " | ".join(f"{a:.1f}-{b:.1f}" for a, b in zip(row["q05"], row["q95"]))
                      + f" | {'-' if move is None else f'{move:.1f}'} |")
        needed = convergence["samples_needed"]
        md += ["", f"No later doubling moves a band end by more than {convergence['stable_to_m_s']:g} m/s from "
               f"{needed} samples on." if needed is not None else
               f"The last doubling still moves a band end by more than {convergence['stable_to_m_s']:g} m/s."]
    else:
        md += ["", "Fewer than two doublings of 4 samples: the band against the samples needs 8 or more."]
    return "\n".join(md) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("runs")
    ap.add_argument("--sdels", required=True)
    ap.add_argument("--experiments")
    ap.add_argument("--paper")
    ap.add_argument("--source", default="")
    ap.add_argument("--samples", type=int, help="the first N samples only (default: every s<k> there)")
    ap.add_argument("--velocities", help="these impact velocities only, m/s, comma- or space-separated "
                                         "(default: every v<v> there)")
    ap.add_argument("--stable-to", type=float, default=5.0)
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    try:
        if args.samples is not None and args.samples < 1:
            raise BadInput(f"--samples {args.samples}: must be at least 1")
        only = None
        if args.velocities:
            try:
                only = [float(v) for v in args.velocities.replace(",", " ").split()]
            except ValueError:
                raise BadInput(f"--velocities '{args.velocities}': not a list of numbers (m/s)")
        velocities, table = collect(args.runs, args.sdels, args.samples, only)
        experiments = residual_by_velocity(args.experiments) if args.experiments else {}
        paper = residual_by_velocity(args.paper) if args.paper else {}
        vr, bands, convergence = band(velocities, table, args.stable_to)
        per_sample, fit_summary = fits(velocities, vr)
    except (BadInput, KeyError) as e:
        print(f"uq_band.py: {e}", file=sys.stderr)
        return 2
    for row, f in zip(table, per_sample):
        row["lambert_jonas_p1"] = f
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    doc = {"format": "uhpc-uq-band/1", "source": args.source, "runs": str(args.runs), "sdels": str(args.sdels),
           "velocities_m_s": velocities, "band": bands, "lambert_jonas_p1": fit_summary,
           "convergence": convergence, "samples": table}
    (out / "uq_band.json").write_text(json.dumps(doc, indent=2) + "\n")
    md = markdown(bands, fit_summary, convergence, experiments, paper, args.source)
    (out / "uq_band.md").write_text(md)
    print(md, end="")
    return 0


if __name__ == "__main__":
    sys.exit(main())
