#!/usr/bin/env python3
"""pipelines/lambert_jonas.py against data made from its own model with known constants: the fit must
recover them, and must say when v_bl is only extrapolated (no run below it) or a free p ran to the end of
its search, in the JSON and in the Markdown table."""
import pathlib
import sys

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "pipelines"))
import lambert_jonas as lj  # noqa: E402

failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


# Known curve a = 0.8, v_bl = 450 m/s, p = 2, sampled on both sides of the limit (exact data).
v = np.array([300.0, 400.0, 440.0, 500.0, 600.0, 700.0, 800.0, 900.0, 1000.0])
vr = lj.model(v, 0.8, 450.0, 2.0)
f = lj.fit(v, vr)
check(abs(f["a"] - 0.8) < 2e-3 and abs(f["v_bl_m_s"] - 450.0) < 1.0 and abs(f["p"] - 2.0) < 0.02,
      f"exact data recovered: a {f['a']:.4f}, v_bl {f['v_bl_m_s']:.2f}, p {f['p']:.3f}")
check(f["v_bl_bracketed"] and not f["p_at_search_edge"], "runs on both sides: bracketed, p inside its search")
md = lj.fit_markdown({"runs": f})
check("(extrapolated)" not in md and "(search edge)" not in md, "the table flags nothing")

# The same curve seen only above the limit: v_bl is the curve's foot, extrapolated.
above = v > 450.0
g = lj.fit(v[above], vr[above], p_fixed=2.0)
check(not g["v_bl_bracketed"], f"every run perforates: v_bl {g['v_bl_m_s']:.1f} flagged as extrapolated")
md = lj.fit_markdown({"runs": g})
check("(extrapolated)" in md and "every run of these data perforated" in md, "the table says so, with the reason")

# A curve of p = 0.35, below the searched range: the free p ends at the range's low end and says so.
w = np.array([300.0, 400.0, 500.0, 600.0, 700.0, 800.0, 900.0, 1000.0])
h = lj.fit(w, lj.model(w, 0.9, 200.0, 0.35))
check(h["p_at_search_edge"] and h["p"] < lj.P_SEARCH[0] + 0.01, f"p {h['p']:.2f} at the search's low end, flagged")
e = dict(f, p=lj.P_SEARCH[0], p_at_search_edge=True)
check("(search edge)" in lj.fit_markdown({"runs": e}), "a p at the edge is marked in the table")

print(f"{len(failures)} failed")
sys.exit(1 if failures else 0)
