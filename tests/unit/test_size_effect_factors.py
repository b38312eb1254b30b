#!/usr/bin/env python3
"""pipelines/size_effect_factors.py on hand-made cells whose answer is known: two sizes of four cells, each
cell's peak 20 - 10 d_max (d_max its largest pore in mm) exactly, so the within-size slope on the largest
pore is -10 MPa/mm with r = -1 in each size and zero standard error, and the size effect it predicts from
the change of the mean d_max equals the measured one; the pore count is unrelated (r ~ 0 by construction).
The worst cross-section of a cell with one pore of diameter d in a side L is d / L. A cell the ensemble
does not average (no peak, not bridged) is left out and counted.
A noisy case on three sizes: the slope and its standard error equal those of an ordinary least-squares fit
with one intercept per size (computed here independently, with numpy's lstsq and n - k - 1 degrees of
freedom), and size means made exactly 10 + 3/L MPa (L in mm) give P_inf = 10 MPa, C = 3 MPa mm, chi2 0.
A cell generated with another seed or other pores is refused with exit 2, naming the file and the key."""
import numpy as np
import json
import pathlib
import subprocess
import sys
import tempfile

SCRIPT = pathlib.Path(__file__).resolve().parents[2] / "pipelines" / "size_effect_factors.py"
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def make_cell(root, size_mm, k, diameters_mm, peak_MPa, seed, porosity):
    side = size_mm / 1e3
    name = f"size_{size_mm:.1f}mm/cell_{k:02d}"
    analysed = root / "analysed" / name
    analysed.mkdir(parents=True)
    averaged = peak_MPa is not None
    (analysed / "summary.json").write_text(json.dumps({
        "cell": {"size_m": side, "seed": seed, "porosity": porosity}, "status": "reached_end",
        "peak_stress_Pa": peak_MPa * 1e6 if averaged else None, "grid": {"complete": True} if averaged else None}))
    generated = root / "generated" / name
    generated.mkdir(parents=True)
    pores = [{"center_m": [side * (0.2 + 0.6 * i / max(1, len(diameters_mm) - 1)), 0.5 * side], "diameter_m": d / 1e3}
             for i, d in enumerate(diameters_mm)]
    (generated / "cell.json").write_text(json.dumps({
        "cell_size_m": side, "loading_direction": "x", "seed": seed, "porosity": {"achieved": porosity},
        "largest_pore_diameter_m": max(diameters_mm) / 1e3, "pore_count": len(diameters_mm), "pores": pores}))
    return generated / "cell.json"


def run(root):
    r = subprocess.run([sys.executable, str(SCRIPT), "--analysed", str(root / "analysed"), "--generated",
                        str(root / "generated"), "--out", str(root / "out")], capture_output=True, text=True)
    return r.returncode, r.stderr


with tempfile.TemporaryDirectory() as tmp:
    root = pathlib.Path(tmp)
    cells = {3.0: [0.20, 0.30, 0.40, 0.50], 6.0: [0.40, 0.50, 0.60, 0.70]}
    counts = [1, 2, 2, 1]  # symmetric against d_max inside each size: no correlation
    for size_mm, dmax in cells.items():
        for k, d in enumerate(dmax):
            diameters = [d] + [0.1] * (counts[k] - 1)
            make_cell(root, size_mm, k, diameters, 20.0 - 10.0 * d, seed=100 * k + int(size_mm), porosity=0.034)
    make_cell(root, 6.0, 9, [0.3], None, seed=9, porosity=0.034)  # not bridged: no peak
    code, err = run(root)
    check(code == 0, f"exit 0 ({code}: {err.strip()})")
    result = json.loads((root / "out" / "size_effect_factors.json").read_text())
    f = result["factors"]["largest_pore"]
    check(abs(f["slope_MPa"] + 10.0) < 1e-9, f"slope on the largest pore -10 MPa/mm ({f['slope_MPa']})")
    check(f["slope_se_MPa"] < 1e-9, f"its standard error 0 ({f['slope_se_MPa']})")
    check(all(abs(r + 1.0) < 1e-12 for r in f["r_within_size"].values()), f"r = -1 in each size ({f['r_within_size']})")
    measured = result["measured_size_effect_MPa"]
    check(abs(measured + 2.0) < 1e-9, f"measured size effect -2 MPa ({measured})")
    check(abs(f["predicted_size_effect_MPa"] - measured) < 1e-9,
          f"the largest pore predicts the whole size effect ({f['predicted_size_effect_MPa']})")
    r_count = result["factors"]["pore_count"]["r_pooled"]
    check(abs(r_count) < 1e-9, f"the pore count is unrelated (r {r_count})")
    ws = result["per_size"][0]["worst_section"]
    check(abs(ws - 0.35 / 3.0) < 2e-3 * 0.35 / 3.0, f"worst section of the 3 mm cells: mean d / L ({ws})")
    check((root / "out" / "size_effect_factors.md").read_text().startswith("| size mm |"), "markdown table written")
    check(result["cells_left_out"] == 1 and result["per_size"][1]["cells"] == 4, "the unbridged cell left out and counted")
    check(result["boundary_layer_fit"] is None, "no C / L fit with two sizes")

    # Noisy, three sizes: the slope and its error against a fit with one intercept per size.
    noisy = root / "noisy"
    rng = np.random.default_rng(7)
    rows = []
    for size_mm in (3.0, 4.5, 6.0):
        d = rng.uniform(0.2, 0.6, 6)
        e = rng.normal(0.0, 0.3, 6)
        peaks = 10.0 + 3.0 / size_mm - 2.0 * (d - d.mean()) + (e - e.mean())  # size mean exactly 10 + 3 / L
        for k in range(6):
            make_cell(noisy, size_mm, k, [d[k]], peaks[k], seed=1000 * k + int(10 * size_mm), porosity=0.034)
            rows.append((size_mm, d[k], peaks[k]))
    code, err = run(noisy)
    check(code == 0, f"noisy case: exit 0 ({code}: {err.strip()})")
    result = json.loads((noisy / "out" / "size_effect_factors.json").read_text())
    rows = np.array(rows)
    X = np.c_[rows[:, 1], *(rows[:, 0:1] == L for L in (3.0, 4.5, 6.0))].astype(float)
    beta, ss, *_ = np.linalg.lstsq(X, rows[:, 2], rcond=None)
    sigma2 = ss[0] / (len(rows) - X.shape[1])
    se = np.sqrt(sigma2 * np.linalg.inv(X.T @ X)[0, 0])
    f = result["factors"]["largest_pore"]
    check(abs(f["slope_MPa"] - beta[0]) < 1e-10 and abs(f["slope_se_MPa"] - se) < 1e-10,
          f"slope {f['slope_MPa']:.6f} +- {f['slope_se_MPa']:.6f} against {beta[0]:.6f} +- {se:.6f}")
    b = result["boundary_layer_fit"]
    check(abs(b["P_inf_MPa"] - 10.0) < 1e-9 and abs(1e3 * b["C_MPa_m"] - 3.0) < 1e-9 and b["chi2"] < 1e-15 and b["dof"] == 1,
          f"C / L fit: P_inf {b['P_inf_MPa']}, C {1e3 * b['C_MPa_m']} MPa mm, chi2 {b['chi2']:.1e}")

    bad = make_cell(root / "other", 3.0, 0, [0.2], 18.0, seed=7, porosity=0.034)
    for name in ("analysed",):
        (root / "other" / name / "size_3.0mm" / "cell_00" / "summary.json").write_text(json.dumps({
            "cell": {"size_m": 0.003, "seed": 8, "porosity": 0.034}, "peak_stress_Pa": 1.8e7}))
    code, err = run(root / "other")
    check(code == 2 and str(bad) in err and "'seed'" in err, f"another seed refused with exit 2 ({code}: {err.strip()})")

    (root / "other" / "analysed" / "size_3.0mm" / "cell_00" / "summary.json").write_text(json.dumps({
        "cell": {"size_m": 0.003, "seed": 7, "porosity": 0.030}, "peak_stress_Pa": 1.8e7}))
    code, err = run(root / "other")
    check(code == 2 and "'porosity.achieved'" in err, f"other pores refused with exit 2 ({code}: {err.strip()})")

    for k in range(3):
        make_cell(root / "one_size", 3.0, k, [0.2 + 0.1 * k], 18.0 - k, seed=k, porosity=0.034)
    code, err = run(root / "one_size")
    check(code == 2 and "two sizes" in err, f"one size refused with exit 2 ({code}: {err.strip()})")

print(f"{len(failures)} failure(s)")
sys.exit(1 if failures else 0)
