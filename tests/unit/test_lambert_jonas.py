#!/usr/bin/env python3
"""pipelines/lambert_jonas.py: the model against values worked by hand; fit() and fit_fast() against a
least-squares answer worked by hand on data the model did not make (so the fit is not only checked against
itself); fit() on data made from its own model with known constants, which it must recover; and the flags
that say when v_bl is only extrapolated (no run below it) or a free p ran to the end of its search, in the
JSON and in the Markdown table."""

import numpy as np

from pipeline_checks import check, finish  # puts pipelines/ on the path first
import lambert_jonas as lj  # noqa: E402



# The model by hand: 0.8 sqrt(500^2 - 450^2) = 0.8 sqrt(47500) = 174.35595774...; 0.75 sqrt(500^2 - 300^2)
# = 0.75 x 400 = 300; 0.5 (1000 - 600) = 200 at p = 1; nothing below the limit.
hand = lj.model(np.array([500.0, 500.0, 1000.0, 400.0]), np.array([0.8, 0.75, 0.5, 0.8]),
                np.array([450.0, 300.0, 600.0, 450.0]), np.array([2.0, 2.0, 1.0, 2.0]))
check(np.allclose(hand, [174.35595774162695, 300.0, 200.0, 0.0], rtol=1e-14, atol=0.0),
      f"model against hand values: {hand.tolist()}")

# A least-squares answer by hand on data no model made: p held at 1, the runs at 500, 600 and 700 m/s with
# residuals 100, 170 and 260 m/s, and one at 350 m/s that stopped. With v_bl below 500 the three perforating
# runs lie on vr = a v - a v_bl, whose least-squares line has slope 16000 / 20000 = 0.8 and intercept
# 176.667 - 0.8 x 600 = -303.333: a = 0.8, v_bl = 303.333 / 0.8 = 379.1667 m/s, residuals +3.333, -6.667,
# +3.333, and 0 at 350 m/s (below v_bl the model is 0), so no v_bl under 350 m/s can do better: rms
# sqrt(66.667 / 4) = 4.0825 m/s.
hv = np.array([350.0, 500.0, 600.0, 700.0])
hr = np.array([0.0, 100.0, 170.0, 260.0])
for name, fitter, vbl_tol in (("fit", lj.fit, 0.01), ("fit_fast", lj.fit_fast, 0.05)):
    # fit() refines v_bl to a 0.01 m/s grid, fit_fast() to 0.05 m/s: the tolerances are those steps.
    k = fitter(hv, hr, p_fixed=1.0)
    check(abs(k["a"] - 0.8) < 1e-4 and abs(k["v_bl_m_s"] - 379.1667) < vbl_tol and abs(k["rms_m_s"] - 4.0825) < 1e-3
          and k["p"] == 1.0,
          f"{name} on hand data: a {k['a']:.5f} (0.8), v_bl {k['v_bl_m_s']:.3f} (379.167), rms {k['rms_m_s']:.4f} "
          "(4.0825)")

# Known curve a = 0.8, v_bl = 450 m/s, p = 2, sampled on both sides of the limit (exact data).
v = np.array([300.0, 400.0, 440.0, 500.0, 600.0, 700.0, 800.0, 900.0, 1000.0])
vr = lj.model(v, 0.8, 450.0, 2.0)
f = lj.fit(v, vr)
check(abs(f["a"] - 0.8) < 2e-3 and abs(f["v_bl_m_s"] - 450.0) < 1.0 and abs(f["p"] - 2.0) < 0.02,
      f"exact data recovered: a {f['a']:.4f}, v_bl {f['v_bl_m_s']:.2f}, p {f['p']:.3f}")
check(f["v_bl_bracketed"] and not f["p_at_search_edge"], "runs on both sides: bracketed, p inside its search")
# fit_fast (the bootstrap's search) finds the same constants on the same data, to its coarser grid.
ff = lj.fit_fast(v, vr)
check(abs(ff["a"] - 0.8) < 2e-3 and abs(ff["v_bl_m_s"] - 450.0) < 1.0 and abs(ff["p"] - 2.0) < 0.02,
      f"fit_fast on exact data: a {ff['a']:.4f}, v_bl {ff['v_bl_m_s']:.2f}, p {ff['p']:.3f}")
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

finish()
