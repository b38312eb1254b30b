#!/usr/bin/env python3
"""pipelines/uq_sdel.py's draws against cases with a known spread (no program runs; seconds).

1. bootstrap: the realizations drawn per size resample n of n with replacement, each size on its own; the
   bootstrap standard deviation of the mean of 25 fixed values (per size, the statistic the ensemble's mean
   curve is) matches its exact value sqrt(sum (x - xbar)^2) / n to within the Monte Carlo error of 2000
   samples; sample k's draws do not depend on how many samples are planned (a larger N resumes).
2. covariance: the draws' mean and covariance match the law's; where the law reaches below 0 (a = 1 +- 1),
   every written constant is > 0 and the rejected draws are counted, at the normal's own rate.
"""
import math
import os
import sys
import types

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "pipelines"))
import uq_sdel  # noqa: E402

ot = uq_sdel.import_openturns()
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def args(source, samples, seed=11):
    return types.SimpleNamespace(source=source, samples=samples, seed=seed, cells="/cells", micro_config="m.json",
                                 micro_set="", calibrate_config="c.json", out="/tmp/uq")


def base(mean, cov):
    sd = [math.sqrt(cov[i][i]) for i in range(4)]
    return {"constants": dict(zip(uq_sdel.CONSTANTS, mean)),
            "fit": {"sdel": {"covariance_available": True,
                             "covariance": {"order": list(uq_sdel.CONSTANTS), "matrix": cov},
                             "standard_errors": dict(zip(uq_sdel.CONSTANTS, sd))}}}


# --- 1. bootstrap -----------------------------------------------------------------------------------
n, B, sizes = 25, 2000, [0.003, 0.0045, 0.005, 0.0065]
b0 = base([1, 1, 1, 1], [[1 if i == j else 0 for j in range(4)] for i in range(4)])
plans = uq_sdel.draw_plan(ot, args("bootstrap", B), sizes, n, b0, "/tmp/uq/base/sdel.json")
check(all(len(p["draws"]) == 4 and all(len(d) == n and all(0 <= r < n for r in d) for d in p["draws"]) for p in plans),
      "every sample draws n = 25 realizations in [0, 25) for each of the 4 sizes")
check(any(len(set(d)) < n for p in plans for d in p["draws"]), "the draws repeat realizations (with replacement)")
check(all(p["seed"] == 11 + p["sample"] for p in plans), "sample k has seed S + k")
# The per-size draws are not the same list (each size resampled on its own).
check(sum(p["draws"][0] == p["draws"][1] for p in plans) == 0, "the sizes are resampled independently")
# Known spread: 25 fixed values; the bootstrap std of their mean is sqrt(sum (x - xbar)^2) / n exactly (B -> inf).
ot.RandomGenerator.SetSeed(3)
x = [v[0] for v in ot.Normal(5.0, 2.0).getSample(n)]
xbar = sum(x) / n
exact = math.sqrt(sum((v - xbar) ** 2 for v in x)) / n
for size in range(4):
    means = [sum(x[r] for r in p["draws"][size]) / n for p in plans]
    m = sum(means) / B
    sd = math.sqrt(sum((v - m) ** 2 for v in means) / (B - 1))
    # Monte Carlo: the relative error of a std from B normal-ish samples is about 1 / sqrt(2 B) = 1.6 %.
    check(abs(sd / exact - 1) < 0.05 and abs(m - xbar) < 4 * exact / math.sqrt(B),
          f"size {size}: bootstrap std of the mean {sd:.5f} vs exact {exact:.5f} (sigma/sqrt(n) {2 / math.sqrt(n):.3f}), "
          f"mean {m:.4f} vs {xbar:.4f}")
few = uq_sdel.draw_plan(ot, args("bootstrap", 5), sizes, n, b0, "/tmp/uq/base/sdel.json")
check(all(few[k]["draws"] == plans[k]["draws"] and few[k]["plan_hash"] == plans[k]["plan_hash"] for k in range(5)),
      "sample k's draws and plan hash do not depend on the number of samples")
other = uq_sdel.draw_plan(ot, args("bootstrap", 5, seed=12), sizes, n, b0, "/tmp/uq/base/sdel.json")
check(other[0]["draws"] == plans[1]["draws"] and other[0]["plan_hash"] != plans[1]["plan_hash"],
      "seed 12's sample 0 draws as seed 11's sample 1 but is another plan")

# --- 2. covariance ----------------------------------------------------------------------------------
mean = [40.0, 6e-4, 2.4, 7e5]
sd = [2.0, 1e-5, 0.05, 7e3]
rho = [[1, 0.9, -0.5, 0], [0.9, 1, -0.6, 0], [-0.5, -0.6, 1, 0.1], [0, 0, 0.1, 1]]
cov = [[rho[i][j] * sd[i] * sd[j] for j in range(4)] for i in range(4)]
N = 4000
plans = uq_sdel.draw_plan(ot, args("covariance", N), sizes, n, base(mean, cov), "/tmp/uq/base/sdel.json")
vals = [[p["constants"][c] for c in uq_sdel.CONSTANTS] for p in plans]
s = ot.Sample(vals)
m, v = s.computeMean(), s.computeCovariance()
check(all(abs(m[i] - mean[i]) < 4 * sd[i] / math.sqrt(N) for i in range(4)), f"draws' mean {list(m)} vs {mean}")
check(all(abs(math.sqrt(v[i, i]) / sd[i] - 1) < 0.05 for i in range(4)), "draws' standard deviations within 5 %")
check(all(abs(v[i, j] / math.sqrt(v[i, i] * v[j, j]) - rho[i][j]) < 0.05 for i in range(4) for j in range(4)),
      "draws' correlations within 0.05")
check(sum(p["rejected_draws"] for p in plans) == 0, "no draw rejected when the law is far from 0")
# a = 1 +- 1: P(a <= 0) = Phi(-1) = 0.1587; rejected / (accepted + rejected) must be that rate.
near = [[1.0 if i == j == 0 else (cov[i][j] if i and j else 0.0) for j in range(4)] for i in range(4)]
plans = uq_sdel.draw_plan(ot, args("covariance", N), sizes, n, base([1.0] + mean[1:], near), "/tmp/uq/base/sdel.json")
rej = sum(p["rejected_draws"] for p in plans)
rate = rej / (rej + N)
check(all(p["constants"]["a"] > 0 for p in plans), "every written a > 0 when the law reaches below 0")
check(abs(rate - 0.158655) < 4 * math.sqrt(0.16 * 0.84 / (rej + N)), f"rejection rate {rate:.4f} vs Phi(-1) 0.1587")
try:
    bad = base(mean, cov)
    bad["fit"]["sdel"]["covariance_available"] = False
    uq_sdel.draw_plan(ot, args("covariance", 2), sizes, n, bad, "/x/sdel.json")
    check(False, "a fit without covariance is refused")
except uq_sdel.BadInput as e:
    check("/x/sdel.json: key 'fit.sdel.covariance_available'" in str(e), f"a fit without covariance is refused: {e}")

print(f"{len(failures)} failures")
sys.exit(1 if failures else 0)
