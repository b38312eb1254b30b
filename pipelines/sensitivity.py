#!/usr/bin/env python3
"""Sobol indices of the residual velocity to the least certain AFC and SDEL constants, through a
polynomial chaos surrogate (OpenTURNS) fitted to a design of runs (issue 51 item 3).

usage: sensitivity.py design --afc AFC.json --sdel SDEL.json --samples N --range R --seed S --out DIR
       sensitivity.py analyse DIR --velocities V1 V2 ... [--degree 2] [--validation 0.2] [--out DIR]

design: the inputs (INPUTS below) vary independently and uniformly over [1 - R, 1 + R] times their
shipped value (R = 0.1: the issue's +-10 %, used for every input, as no published range for this UHPC's
constants was found); a Latin hypercube of N points (OpenTURNS' LHSExperiment, seed S). Point k gets
DIR/points/k<k>/afc.json (the constants file with its values) and sdel.json (the handoff with its
constants); DIR/design.json lists the inputs, ranges, seed and points. The same arguments write the same
bytes, so a rerun keeps every finished run (uhpc-macro --reuse); other arguments over a finished design
are refused (exit 2: use another DIR).

  C1 - C2 and not C2 is varied: the AFC law needs C1 > C2, which +-10 % on each would break (C1 - C2 is
  7 % of C1); C1 - C2 is the failure surface's strength at zero pressure (eq. 33, d- = 0), and C2 follows
  as C1 - (C1 - C2).

analyse: the runs DIR/points/k<k>/v<v>/result.json (a shot that does not perforate counts as 0, as
uhpc-compare-shots counts it). Per velocity, a polynomial chaos expansion of total degree --degree in the
inputs' uniform laws (sparse least squares: LARS with corrected leave-one-out) is fitted to the first (1 - validation) of the points, in design
order, and validated on the rest: Q2, the predictivity factor (1 is exact) on points the fit did not see.
Its first-order and total Sobol indices (FunctionalChaosSobolIndices) are written to
DIR/sensitivity.{json,md}. A Q2 below 0.8 is flagged: the indices of a surrogate that does not predict
are not to be read.
"""
import argparse
import hashlib
import json
import pathlib
import sys

from uq_inputs import BadInput, import_openturns, read_json

# (name, where, key, what): the constants the issue names as least certain. "afc" keys are those of the
# AFC constants file (SI units); "sdel" keys those of the handoff's "constants".
INPUTS = [
    ("C1", "afc", "C1_Pa", "eq. 33: the strength's cap at high pressure"),
    ("C1-C2", "afc", None, "eq. 33: the strength at zero pressure (C2 = C1 - (C1 - C2))"),
    ("An", "afc", "An_1_Pa", "eq. 33: how fast the strength rises with pressure"),
    ("Tmax", "afc", "Tmax_Pa", "the tensile cutoff"),
    ("D1", "afc", "D1_1_Pa", "d-: the compressive damage rate"),
    ("C3", "afc", "C3", "eq. 34: the rate factor's slope"),
    ("a", "sdel", "a", "SDEL: the size scaling of e_i"),
    ("A", "sdel", "A", "SDEL: the damage threshold strain"),
    ("nu", "sdel", "nu", "SDEL: the damage at the threshold"),
    ("chi", "sdel", "chi", "SDEL: the damage rate"),
]
Q2_TRUSTED = 0.8


def shipped_values(afc, sdel):
    values = []
    for name, where, key, _ in INPUTS:
        if name == "C1-C2":
            values.append(afc["C1_Pa"] - afc["C2_Pa"])
        elif where == "afc":
            values.append(afc[key])
        else:
            values.append(sdel["constants"][key])
    return values


def point_files(afc, sdel, x, k, plan_hash):
    """The constants file and the handoff of design point k (x: the inputs' values, in INPUTS' order)."""
    a, s = dict(afc), json.loads(json.dumps(sdel))
    for (name, where, key, _), value in zip(INPUTS, x):
        if name == "C1-C2":
            continue
        if where == "afc":
            a[key] = value
        else:
            s["constants"][key] = value
    a["C2_Pa"] = a["C1_Pa"] - x[[i[0] for i in INPUTS].index("C1-C2")]
    a["source"] = f"sensitivity design point {k} ({plan_hash}): {afc.get('source', '')}"
    s["source"] = f"sensitivity design point {k} ({plan_hash}): {sdel.get('source', '')}"
    s["fit"] = {"sensitivity_point": {"point": k, "plan_hash": plan_hash,
                                      "inputs": {i[0]: v for i, v in zip(INPUTS, x)}}}
    s.pop("provenance", None)
    return a, s


def write_if_new(path, obj):
    text = json.dumps(obj, indent=2, sort_keys=True) + "\n"
    path = pathlib.Path(path)
    if not path.is_file() or path.read_text() != text:
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)


def design(args):
    ot = import_openturns()
    afc, sdel = read_json(args.afc, "the AFC constants file"), read_json(args.sdel, "the SDEL handoff")
    centre = shipped_values(afc, sdel)
    if not 0 < args.range < 1:
        raise BadInput(f"--range {args.range}: must be in (0, 1)")
    if args.samples < 4:
        raise BadInput(f"--samples {args.samples}: at least 4")
    laws = [ot.Uniform((1 - args.range) * c, (1 + args.range) * c) for c in centre]
    ot.RandomGenerator.SetSeed(args.seed)
    points = ot.LHSExperiment(ot.ComposedDistribution(laws), args.samples).generate()
    plan = {"format": "uhpc-sensitivity-design/1", "afc": str(args.afc), "sdel": str(args.sdel),
            "range": args.range, "seed": args.seed, "samples": args.samples,
            "inputs": [{"name": n, "file": w, "key": k, "what": t, "shipped": c, "low": (1 - args.range) * c,
                        "high": (1 + args.range) * c} for (n, w, k, t), c in zip(INPUTS, centre)]}
    plan_hash = hashlib.sha256(json.dumps(plan, sort_keys=True).encode()).hexdigest()[:16]
    plan["plan_hash"] = plan_hash
    plan["points"] = [list(p) for p in points]
    out = pathlib.Path(args.out)
    previous = out / "design.json"
    if previous.is_file() and read_json(previous, "a finished design").get("plan_hash") != plan_hash:
        raise BadInput(f"{previous}: a design of other inputs (another range, seed, sample count or file): use "
                       f"another OUT")
    for k, x in enumerate(plan["points"]):
        a, s = point_files(afc, sdel, x, k, plan_hash)
        write_if_new(out / "points" / f"k{k:03d}" / "afc.json", a)
        write_if_new(out / "points" / f"k{k:03d}" / "sdel.json", s)
    write_if_new(previous, plan)
    return 0


def fit_and_indices(x, y, names, lows, highs, degree, validation):
    """Polynomial chaos of total degree `degree` in the design's laws (independent uniforms on [lows, highs]:
    the indices are variances under these laws, so they must be the design's, not the points' extremes),
    fitted to the first rows and validated on the last `validation` share: (Q2, first-order, total)."""
    ot = import_openturns()
    x, y = [list(map(float, r)) for r in x], [[float(v)] for v in y]
    d, n = len(names), len(x)
    n_fit = n - max(int(round(validation * n)), 1)
    dist = ot.ComposedDistribution([ot.Uniform(lo, hi) for lo, hi in zip(lows, highs)])
    enum = ot.LinearEnumerateFunction(d)
    basis = ot.OrthogonalProductPolynomialFactory(
        [ot.StandardDistributionPolynomialFactory(dist.getMarginal(i)) for i in range(d)], enum)
    terms = enum.getStrataCumulatedCardinal(degree)
    if n_fit < d + 2:
        raise BadInput(f"{n} points: {n_fit} are left to fit after validation, fewer than the {d + 2} a chaos in {d} "
                       f"inputs needs at the least (more --samples)")
    # Sparse least squares (LARS, the basis chosen by corrected leave-one-out): the degree-2 basis in 10
    # inputs has 66 terms, more than a design of a few tens of runs can fit in full.
    selection = ot.LeastSquaresMetaModelSelectionFactory(ot.LARS(), ot.CorrectedLeaveOneOut())
    algo = ot.FunctionalChaosAlgorithm(ot.Sample(x[:n_fit]), ot.Sample(y[:n_fit]), dist,
                                       ot.FixedStrategy(basis, terms), ot.LeastSquaresStrategy(selection))
    algo.run()
    result = algo.getResult()
    q2 = float(ot.MetaModelValidation(ot.Sample(x[n_fit:]), ot.Sample(y[n_fit:]),
                                      result.getMetaModel()).computePredictivityFactor()[0])
    sobol = ot.FunctionalChaosSobolIndices(result)
    first = [float(sobol.getSobolIndex(i)) for i in range(d)]
    total = [float(sobol.getSobolTotalIndex(i)) for i in range(d)]
    return {"points_fitted": n_fit, "points_validated": n - n_fit, "terms": terms, "q2": q2,
            "trusted": q2 >= Q2_TRUSTED, "first_order": dict(zip(names, first)), "total": dict(zip(names, total))}


def analyse(args):
    root = pathlib.Path(args.dir)
    plan = read_json(root / "design.json", "the design (sensitivity.py design)")
    names = [i["name"] for i in plan["inputs"]]
    x = plan["points"]
    out = {"format": "uhpc-sensitivity/1", "design": str(root / "design.json"), "plan_hash": plan["plan_hash"],
           "range": plan["range"], "inputs": plan["inputs"], "degree": args.degree, "velocities": []}
    md = [f"# Sobol indices of the residual velocity ({len(x)} runs a velocity, inputs +-{plan['range'] * 100:g} %, "
          f"chaos of degree {args.degree})", ""]
    for v in args.velocities:
        y, outcomes = [], []
        for k in range(len(x)):
            r = read_json(root / "points" / f"k{k:03d}" / f"v{v:g}" / "result.json", f"design point {k} at {v:g} m/s")
            y.append(float(r["residual_velocity_m_s"]) if r.get("outcome") == "perforated" else 0.0)
            outcomes.append(r.get("outcome"))
        s = fit_and_indices(x, y, names, [i["low"] for i in plan["inputs"]], [i["high"] for i in plan["inputs"]],
                            args.degree, args.validation)
        s.update({"velocity_m_s": v, "residual_velocity_m_s": {"min": min(y), "max": max(y),
                  "mean": sum(y) / len(y)}, "not_perforated": sum(o != "perforated" for o in outcomes)})
        out["velocities"].append(s)
        md += [f"## {v:g} m/s: residual velocity {min(y):.1f}-{max(y):.1f} m/s over the design, "
               f"Q2 {s['q2']:.3f} on {s['points_validated']} points left out"
               + ("" if s["trusted"] else f" (below {Q2_TRUSTED}: the surrogate does not predict; do not read the indices)"),
               "", "| input | first-order | total |", "|---|---|---|"]
        for n in sorted(names, key=lambda n: -s["total"][n]):
            md.append(f"| {n} | {s['first_order'][n]:.3f} | {s['total'][n]:.3f} |")
        md.append("")
    dest = pathlib.Path(args.out or root)
    dest.mkdir(parents=True, exist_ok=True)
    (dest / "sensitivity.json").write_text(json.dumps(out, indent=2) + "\n")
    (dest / "sensitivity.md").write_text("\n".join(md))
    print("\n".join(md))
    return 0


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = ap.add_subparsers(dest="command", required=True)
    d = sub.add_parser("design")
    d.add_argument("--afc", required=True)
    d.add_argument("--sdel", required=True)
    d.add_argument("--samples", type=int, required=True)
    d.add_argument("--range", type=float, default=0.1)
    d.add_argument("--seed", type=int, default=20261208)
    d.add_argument("--out", required=True)
    a = sub.add_parser("analyse")
    a.add_argument("dir")
    a.add_argument("--velocities", type=float, nargs="+", required=True)
    a.add_argument("--degree", type=int, default=2)
    a.add_argument("--validation", type=float, default=0.2)
    a.add_argument("--out")
    args = ap.parse_args(argv)
    try:
        return design(args) if args.command == "design" else analyse(args)
    except BadInput as e:
        print(f"sensitivity.py: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
