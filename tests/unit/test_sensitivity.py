#!/usr/bin/env python3
"""pipelines/sensitivity.py: the surrogate's Sobol indices against a function whose indices are known, and
the design's files (issue 51 item 3).

f(x) = x0 + 2 x1^2 + 0.1 x2 + 0 x3 on x_i uniform in [-1, 1]: Var x0 = 1/3, Var 2 x1^2 = 4 (1/5 - 1/9) =
16/45, Var 0.1 x2 = 1/300, no interaction, so each first-order index equals its total one: 0.4815, 0.5137,
0.0048, 0. The design: the points' files carry their values, C2 follows C1 - (C1 - C2), the same arguments
write the same bytes, other arguments over a design are refused.
"""
import json
import pathlib
import tempfile

from pipeline_checks import check, finish  # puts pipelines/ on the path first
import openturns as ot  # noqa: E402
import sensitivity  # noqa: E402



ot.RandomGenerator.SetSeed(7)
x = ot.LHSExperiment(ot.ComposedDistribution([ot.Uniform(-1.0, 1.0)] * 4), 50).generate()
y = [p[0] + 2.0 * p[1] ** 2 + 0.1 * p[2] for p in x]
s = sensitivity.fit_and_indices([list(p) for p in x], y, ["x0", "x1", "x2", "x3"], [-1.0] * 4, [1.0] * 4, 2, 0.2)
total = 1 / 3 + 16 / 45 + 1 / 300
exact = {"x0": (1 / 3) / total, "x1": (16 / 45) / total, "x2": (1 / 300) / total, "x3": 0.0}
print(s)
check(s["q2"] > 0.999, f"Q2 of an exact degree-2 surrogate: {s['q2']:.6f}")
for n, e in exact.items():
    check(abs(s["first_order"][n] - e) < 1e-3 and abs(s["total"][n] - e) < 1e-3,
          f"{n}: first-order {s['first_order'][n]:.4f}, total {s['total'][n]:.4f}, exact {e:.4f}")

root = pathlib.Path(__file__).resolve().parents[2]
with tempfile.TemporaryDirectory() as tmp:
    args = ["design", "--afc", str(root / "data" / "afc_uhpc.json"), "--sdel", str(root / "data" / "sdel_paper.json"),
            "--samples", "6", "--range", "0.1", "--seed", "5", "--out", tmp]
    check(sensitivity.main(args) == 0, "design exits 0")
    plan = json.loads((pathlib.Path(tmp) / "design.json").read_text())
    names = [i["name"] for i in plan["inputs"]]
    afc0 = json.loads((pathlib.Path(tmp) / "points" / "k000" / "afc.json").read_text())
    sdel0 = json.loads((pathlib.Path(tmp) / "points" / "k000" / "sdel.json").read_text())
    x0 = dict(zip(names, plan["points"][0]))
    check(afc0["C1_Pa"] == x0["C1"] and afc0["Tmax_Pa"] == x0["Tmax"] and sdel0["constants"]["chi"] == x0["chi"],
          "point 0's files carry its values")
    check(abs(afc0["C1_Pa"] - afc0["C2_Pa"] - x0["C1-C2"]) < 1e-6 * afc0["C1_Pa"] and afc0["C1_Pa"] > afc0["C2_Pa"],
          "C2 = C1 - (C1 - C2), below C1")
    check(all(i["low"] <= v <= i["high"] for p in plan["points"] for i, v in zip(plan["inputs"], p)),
          "every point within its inputs' ranges")
    before = {p: p.read_bytes() for p in pathlib.Path(tmp).rglob("*.json")}
    check(sensitivity.main(args) == 0 and all(p.read_bytes() == b for p, b in before.items()),
          "the same arguments write the same bytes")
    other = list(args)
    other[other.index("--seed") + 1] = "6"
    check(sensitivity.main(other) == 2, "another seed over the design is refused (exit 2)")
finish()
