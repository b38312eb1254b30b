#!/usr/bin/env python3
"""The uncertainty of the SDEL constants from two named sources, as a set of SDEL handoffs (issue 51 item 1).

  uq_sdel.py --source bootstrap|covariance --samples N --seed S --out DIR
             --micro uhpc-micro --calibrate uhpc-calibrate --micro-config data/micro_analysis_ensemble.json
             --cells CELLS_DIR [--micro-set "--set k=v ..."] [--calibrate-config data/calibrate.json]
             [--launch "srun ..."]

Both sources start from the base fit: the ensemble assembled from every finished cell in CELLS_DIR (each
realization once, `uhpc-micro ensemble --assemble-only --select`) and fitted by `uhpc-calibrate`
(DIR/base/sdel.json). Then, sample k (k = 0 .. N-1, seed S + k):

  bootstrap   per size, the realizations are drawn with replacement (as many as the size has, OpenTURNS'
              BootstrapExperiment.GenerateSelection); `uhpc-micro ensemble --assemble-only --select
              --assemble-to` assembles that ensemble with the project's own averaging (one sample at a time:
              the cells are locked while they are reloaded) and `uhpc-calibrate` fits it: DIR/samples/sample_<k>/.
  covariance  the constants (a, A, nu, chi) are drawn from the normal law of mean the base fit's constants
              and covariance its `fit.sdel.covariance` (ot.Normal). The handoff needs every constant > 0: a
              draw with a constant <= 0 is rejected and drawn again (the law is truncated to the admissible
              set, not clipped); each sample records how many draws it rejected, the summary the total.

Each sample is written as DIR/sdel_<k>.json (three digits), a handoff uhpc-macro --sdel reads, whose
`fit.uq_sample` block holds its provenance (source, index, seed, the realizations drawn per size or the
covariance and the base handoff it came from, the plan hash). A sample whose handoff is there with the same
plan is kept (resumable); one made from other inputs stops the run (exit 2: use another DIR). Then
DIR/summary.json and DIR/summary.md: per constant the base value and standard error, the samples' mean,
standard deviation, 5 % and 95 % quantiles and the std over the standard error; the samples' correlations
(Pearson and Spearman). Exit codes: 0; 1 a sample's fit failed (recorded, the others are written); 2 bad
input. Method: docs/uncertainty.md.
"""
import argparse
import hashlib
import json
import os
import shlex
import subprocess
import sys
import time

from ensemble_cells import sizes_and_realizations
from uq_inputs import BadInput, import_openturns, read_json

CONSTANTS = ("a", "A", "nu", "chi")
SOURCES = ("bootstrap", "covariance")
SELECTION_FORMAT = "uhpc-cell-selection/1"
SUMMARY_FORMAT = "uhpc-uq-sdel/1"



def digest(obj):
    return hashlib.sha256(json.dumps(obj, sort_keys=True).encode()).hexdigest()[:16]


def write_json(path, obj):
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        json.dump(obj, f, indent=2)
        f.write("\n")
    os.replace(tmp, path)


def run(cmd, launch, log):
    """Runs cmd (through the launcher); returns its exit code, its output appended to log."""
    full = shlex.split(launch) + cmd if launch else cmd
    with open(log, "a") as f:
        f.write("$ " + shlex.join(full) + "\n")
        f.flush()
        return subprocess.run(full, stdout=f, stderr=subprocess.STDOUT).returncode


def ensemble_sizes(micro_config, micro_set):
    """The config's cell sizes and realizations (with the --set overrides of those two keys)."""
    cfg = read_json(micro_config, "the microcell ensemble config")
    try:
        sizes, realizations = sizes_and_realizations(cfg, shlex.split(micro_set))
    except ValueError as e:
        raise BadInput(f"{micro_config}: an override of 'cell_sizes_m' or 'realizations' does not read: {e}")
    if not isinstance(sizes, list) or not sizes or not isinstance(realizations, int) or realizations < 1:
        raise BadInput(f"{micro_config}: keys 'cell_sizes_m' and 'realizations': expected a list of sizes and a "
                       f"positive count")
    return [float(s) for s in sizes], realizations


def selection_doc(sizes, draws, note):
    return {"format": SELECTION_FORMAT, "notes": note,
            "sizes": [{"cell_size_m": s, "realizations": [int(r) for r in d]} for s, d in zip(sizes, draws)]}


def assemble_and_fit(args, selection, where, launch):
    """Assembles the selection's ensemble from the cells, then fits it; returns the fit's exit code."""
    os.makedirs(where, exist_ok=True)
    log = os.path.join(where, "log.txt")
    sel_path = os.path.join(where, "selection.json")
    write_json(sel_path, selection)
    rc = run([args.micro, "-q", "ensemble", "--config", args.micro_config, *shlex.split(args.micro_set),
              "--assemble-only", "--select", sel_path, "--assemble-to", os.path.join(where, "ensemble"),
              "--out", args.cells], launch, log)
    if rc == 2:
        raise BadInput(f"uhpc-micro ensemble --assemble-only --select {sel_path}: bad input (exit 2), see {log}")
    if rc != 0:
        return rc
    rc = run([args.calibrate, "--ensemble", os.path.join(where, "ensemble", "ensemble.h5"),
              "--config", args.calibrate_config, "--out", os.path.join(where, "sdel.json")], launch, log)
    if rc == 2:
        raise BadInput(f"uhpc-calibrate on {where}/ensemble/ensemble.h5: bad input (exit 2), see {log}")
    return rc


def base_fit(args, sizes, realizations):
    where = os.path.join(args.out, "base")
    draws = [list(range(realizations)) for _ in sizes]
    rc = assemble_and_fit(args, selection_doc(sizes, draws, "every realization once: the ensemble itself"),
                          where, args.launch)
    if rc != 0:
        raise SystemExit(f"uq_sdel: the base fit failed (exit {rc}), see {where}/log.txt")
    return read_json(os.path.join(where, "sdel.json"), "the base fit")


def covariance_of(base, path):
    s = base.get("fit", {}).get("sdel", {})
    if not s.get("covariance_available"):
        raise BadInput(f"{path}: key 'fit.sdel.covariance_available': the fit carries no covariance (rank-deficient "
                       f"fit, e.g. fewer than 3 sizes): the covariance source needs it")
    cov = s.get("covariance", {})
    if cov.get("order") != list(CONSTANTS):
        raise BadInput(f"{path}: key 'fit.sdel.covariance.order': expected {list(CONSTANTS)}, got {cov.get('order')}")
    return cov["matrix"]


def draw_plan(ot, args, sizes, realizations, base, base_path):
    """Every sample's inputs, decided before any runs: sample k depends on S + k only (resumable for any N)."""
    plans = []
    base_hash = digest({"constants": base["constants"], "covariance": base["fit"]["sdel"].get("covariance")})
    if args.source == "covariance":
        cov = covariance_of(base, base_path)
        mean = [base["constants"][c] for c in CONSTANTS]
        sigma = [cov[i][i] ** 0.5 for i in range(4)]
        corr = ot.CorrelationMatrix(4)
        for i in range(4):
            for j in range(4):
                corr[i, j] = cov[i][j] / (sigma[i] * sigma[j])
        law = ot.Normal(ot.Point(mean), ot.Point(sigma), corr)
    for k in range(args.samples):
        seed = args.seed + k
        ot.RandomGenerator.SetSeed(seed)
        p = {"source": args.source, "sample": k, "seed": seed, "base_handoff": os.path.relpath(base_path, args.out),
             "base_hash": base_hash}
        if args.source == "bootstrap":
            p["draws"] = [[int(r) for r in ot.BootstrapExperiment.GenerateSelection(realizations, realizations)]
                          for _ in sizes]
            p["cell_sizes_m"] = sizes
            p["cells_directory"] = args.cells
            p["micro_config"] = args.micro_config
            p["micro_set"] = args.micro_set
            p["calibrate_config"] = args.calibrate_config
        else:
            rejected = 0
            while True:
                x = [float(v) for v in law.getRealization()]
                if all(v > 0.0 for v in x):
                    break
                rejected += 1
                if rejected > 1000:
                    raise SystemExit(f"uq_sdel: sample {k}: 1000 draws in a row had a constant <= 0: the covariance "
                                     f"leaves almost no admissible constants")
            p["constants"] = dict(zip(CONSTANTS, x))
            p["rejected_draws"] = rejected
            p["covariance"] = {"order": list(CONSTANTS), "matrix": cov}
            p["admissibility"] = "every constant > 0 (the handoff's rule); other draws rejected and drawn again"
        p["plan_hash"] = digest(p)
        plans.append(p)
    return plans


def sample_handoff(args, plan, base):
    """Runs (or keeps) one sample; returns its handoff or None when its fit failed."""
    path = os.path.join(args.out, f"sdel_{plan['sample']:03d}.json")
    if os.path.exists(path):
        old = read_json(path, "a finished sample").get("fit", {}).get("uq_sample", {})
        if old.get("plan_hash") == plan["plan_hash"]:
            return read_json(path, "a finished sample")
        raise BadInput(f"{path}: made from other inputs (plan hash {old.get('plan_hash')}, now {plan['plan_hash']}): "
                       f"use another OUT")
    if args.source == "bootstrap":
        where = os.path.join(args.out, "samples", f"sample_{plan['sample']:03d}")
        sel = selection_doc(plan["cell_sizes_m"], plan["draws"],
                            f"bootstrap sample {plan['sample']}, seed {plan['seed']}")
        rc = assemble_and_fit(args, sel, where, args.launch)
        if rc != 0:
            write_json(os.path.join(where, "failed.json"), {"exit_code": rc, "plan": plan})
            return None
        handoff = read_json(os.path.join(where, "sdel.json"), "a sample's fit")
        handoff["source"] = (f"uq-sdel bootstrap sample {plan['sample']} (seed {plan['seed']}): " + handoff["source"])
        handoff["fit"]["uq_sample"] = dict(plan, fit_directory=os.path.relpath(where, args.out))
    else:
        handoff = {k: base[k] for k in ("format", "law", "l_mac_m", "strain_measure", "cell_sizes_m")}
        handoff["constants"] = plan["constants"]
        handoff["source"] = (f"uq-sdel covariance sample {plan['sample']} (seed {plan['seed']}): constants drawn "
                             f"from the normal law of the base fit's constants and covariance ({plan['base_handoff']})")
        handoff["fit"] = {"uq_sample": plan}
        bp = base.get("provenance", {})
        handoff["provenance"] = {"program": "pipelines/uq_sdel.py (covariance draw)", "version": bp.get("version", ""),
                                 "git_commit": bp.get("git_commit", ""), "config_hash": plan["plan_hash"],
                                 "date_utc": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()), "seed": plan["seed"]}
    write_json(path, handoff)
    return handoff


def summarize(ot, args, base, handoffs, plans, failed):
    values = [[h["constants"][c] for c in CONSTANTS] for h in handoffs]
    s = base["fit"]["sdel"]
    out = {"format": SUMMARY_FORMAT, "source": args.source, "samples_planned": args.samples,
           "samples_written": len(handoffs), "samples_failed": failed, "seed": args.seed,
           "base": {"handoff": "base/sdel.json", "constants": base["constants"],
                    "standard_errors": s.get("standard_errors"), "correlation": s.get("correlation")},
           "constants": {}, "correlation": None}
    if args.source == "covariance":
        out["rejected_draws"] = sum(p["rejected_draws"] for p in plans)
        out["admissibility"] = plans[0]["admissibility"] if plans else None
    if args.source == "bootstrap":
        out["a_at_lower_bound"] = sum(1 for h in handoffs if h["fit"]["sdel"].get("a_at_lower_bound"))
    if len(values) >= 2:
        sample = ot.Sample(values)
        mean, std = sample.computeMean(), sample.computeStandardDeviation()
        q05, q95 = sample.computeQuantilePerComponent(0.05), sample.computeQuantilePerComponent(0.95)
        for i, c in enumerate(CONSTANTS):
            se = (s.get("standard_errors") or {}).get(c)
            out["constants"][c] = {"base": base["constants"][c], "base_standard_error": se, "mean": mean[i],
                                   "std": std[i], "q05": q05[i], "q95": q95[i],
                                   "std_over_standard_error": std[i] / se if se else None}
        pearson, spearman = sample.computePearsonCorrelation(), sample.computeSpearmanCorrelation()
        out["correlation"] = {"order": list(CONSTANTS),
                              "pearson": [[pearson[i, j] for j in range(4)] for i in range(4)],
                              "spearman": [[spearman[i, j] for j in range(4)] for i in range(4)]}
    write_json(os.path.join(args.out, "summary.json"), out)
    lines = [f"# SDEL uncertainty: {args.source}, {len(handoffs)} samples (seed {args.seed})", "",
             f"Base fit `base/sdel.json`; samples `sdel_000.json` ...; {failed and len(failed) or 'no'} failed fits."]
    if args.source == "covariance":
        lines.append(f"Draws rejected (a constant <= 0, drawn again): {out['rejected_draws']}.")
    if args.source == "bootstrap":
        lines.append(f"Refits with a at its lower bound: {out['a_at_lower_bound']}.")
    if out["constants"]:
        lines += ["", "| constant | base | base s.e. | mean | std | 5 % | 95 % | std / s.e. |", "|---|---|---|---|---|---|---|---|"]
        for c, r in out["constants"].items():
            ratio = f"{r['std_over_standard_error']:.2f}" if r["std_over_standard_error"] is not None else "-"
            se = f"{r['base_standard_error']:.4g}" if r["base_standard_error"] is not None else "-"
            lines.append(f"| {c} | {r['base']:.4g} | {se} | {r['mean']:.4g} | {r['std']:.4g} | {r['q05']:.4g} | "
                         f"{r['q95']:.4g} | {ratio} |")
        lines += ["", "Correlations of the samples (Pearson; the base fit's in brackets):", "",
                  "| | " + " | ".join(CONSTANTS) + " |", "|---" * 5 + "|"]
        bc = (s.get("correlation") or {}).get("matrix")
        for i, c in enumerate(CONSTANTS):
            cells = [f"{out['correlation']['pearson'][i][j]:.3f}" + (f" ({bc[i][j]:.3f})" if bc else "")
                     for j in range(4)]
            lines.append(f"| {c} | " + " | ".join(cells) + " |")
    with open(os.path.join(args.out, "summary.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--source", required=True, choices=SOURCES)
    ap.add_argument("--samples", type=int, required=True)
    ap.add_argument("--seed", type=int, default=20261207)
    ap.add_argument("--out", required=True)
    ap.add_argument("--micro", required=True)
    ap.add_argument("--calibrate", required=True)
    ap.add_argument("--micro-config", required=True)
    ap.add_argument("--micro-set", default="")
    ap.add_argument("--cells", required=True, help="the finished cells' directory (e.g. OUT/micro)")
    ap.add_argument("--calibrate-config", required=True)
    ap.add_argument("--launch", default="")
    args = ap.parse_args(argv)
    try:
        if args.samples < 1:
            raise BadInput(f"--samples {args.samples}: must be at least 1")
        if not 0 <= args.seed < 2**32 - args.samples:
            raise BadInput(f"--seed {args.seed}: must be in [0, 2^32 - samples) (OpenTURNS' seeds are 32-bit)")
        for p, what in ((args.micro_config, "--micro-config"), (args.calibrate_config, "--calibrate-config")):
            if not os.path.isfile(p):
                raise BadInput(f"{p}: no such file ({what})")
        if not os.path.isdir(args.cells):
            raise BadInput(f"{args.cells}: no such directory (--cells, the finished cells)")
        args.out = os.path.abspath(args.out)
        os.makedirs(args.out, exist_ok=True)
        ot = import_openturns()
        sizes, realizations = ensemble_sizes(args.micro_config, args.micro_set)
        base = base_fit(args, sizes, realizations)
        base_path = os.path.join(args.out, "base", "sdel.json")
        plans = draw_plan(ot, args, sizes, realizations, base, base_path)
        handoffs, failed = [], []
        for p in plans:
            h = sample_handoff(args, p, base)
            if h is None:
                failed.append(p["sample"])
                print(f"uq_sdel: sample {p['sample']}: the fit failed (recorded; see samples/sample_"
                      f"{p['sample']:03d}/)", file=sys.stderr)
            else:
                handoffs.append(h)
        out = summarize(ot, args, base, handoffs, plans, failed)
    except BadInput as e:
        print(f"uq_sdel: error: {e}", file=sys.stderr)
        return 2
    with open(os.path.join(args.out, "summary.md")) as f:
        print(f.read(), end="")
    print(f"uq_sdel: {out['samples_written']} handoffs in {args.out}/sdel_*.json, summary.{{json,md}} beside them")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
