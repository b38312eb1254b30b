#!/usr/bin/env python3
"""pipelines/compare_ensembles.py on hand-made ensembles whose differences are known: two sizes of three
cells; the candidate's 3.0 mm cells have every peak 1 % above the reference's and damage curves 0.005 above,
so the means differ by exactly +1 % and 0.005 (within 2 %); its 6.0 mm cells have a peak 3 % above on one
cell of three (mean +1 %, within) and then, in a second candidate, the dissipation 7 % above on every cell
(outside). A cell that one run did not bridge is left out of the means and listed. Refusals with exit 2:
a cell with another seed, a candidate cell the reference does not hold."""
import json
import pathlib
import subprocess
import sys
import tempfile

import h5py
import numpy as np

SCRIPT = pathlib.Path(__file__).resolve().parents[2] / "pipelines" / "compare_ensembles.py"
STRAIN = np.linspace(0.0, 1.5e-3, 31)
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def make_cell(root, size_mm, k, peak_MPa, e50, dissipation, damage_shift=0.0, seed=None, bridged=True, geometries=10):
    d = root / f"size_{size_mm:.1f}mm" / f"cell_{k:02d}"
    d.mkdir(parents=True)
    (d / "summary.json").write_text(json.dumps({
        "cell": {"seed": seed if seed is not None else 1000 * k + int(size_mm)},
        "status": "reached_end" if bridged else "failed", "peak_stress_Pa": peak_MPa * 1e6 if bridged else None,
        "strain_at_half_damage": e50 if bridged else None,
        "dissipated_energy_density_J_m3": dissipation if bridged else None,
        "grid": {"complete": True} if bridged else None, "wall_s": 10.0, "crack_geometries": geometries}))
    with h5py.File(d / "curves.h5", "w") as f:
        f["resampled/strain"] = STRAIN
        f["resampled/damage"] = np.clip(STRAIN / 1.5e-3 * 0.9 + damage_shift, 0.0, 1.0)


def build(root, dissipation_factor=1.0, damage_shift=0.0, geometries=8):
    """Peaks 16, 17, 18 MPa (3.0 mm) and 15, 16, 17 MPa (6.0 mm)."""
    for k in range(3):
        make_cell(root, 3.0, k, 16.0 + k, 7e-4, 1.2e4 * dissipation_factor, damage_shift, geometries=geometries)
        make_cell(root, 6.0, k, 15.0 + k, 6e-4 + 1e-5 * k, 2e4 * dissipation_factor, geometries=geometries)


def set_peak(cell_dir, peak_Pa):
    p = cell_dir / "summary.json"
    s = json.loads(p.read_text())
    s["peak_stress_Pa"] = peak_Pa
    p.write_text(json.dumps(s))


def run(ref, cand, out=None):
    cmd = [sys.executable, str(SCRIPT), str(ref), str(cand)] + (["--out", str(out)] if out else [])
    r = subprocess.run(cmd, capture_output=True, text=True)
    return r.returncode, r.stdout, r.stderr


with tempfile.TemporaryDirectory() as tmp:
    root = pathlib.Path(tmp)
    build(root / "ref", geometries=20)
    build(root / "cand", damage_shift=0.005)
    for k in range(3):  # every 3.0 mm peak 1 % above the reference's
        set_peak(root / "cand" / "size_3.0mm" / f"cell_{k:02d}", (16.0 + k) * 1.01e6)
    set_peak(root / "cand" / "size_6.0mm" / "cell_01", 16.0e6 * 1.03)  # mean (15 + 16.48 + 17) / 3 = 16.16: +1 %
    code, out, err = run(root / "ref", root / "cand", root / "out")
    check(code == 0, f"within 2 %: exit 0 ({code}: {err.strip()})")
    r = json.loads((root / "out" / "ensemble_comparison.json").read_text())
    s3, s6 = r["sizes"]
    check(abs(s3["peak"]["relative"] - 0.01) < 1e-12, f"3.0 mm mean peak +1 % ({s3['peak']['relative']})")
    check(abs(s3["damage_curve_max_difference"] - 0.005) < 1e-12,
          f"3.0 mm mean damage curve 0.005 above ({s3['damage_curve_max_difference']})")
    check(abs(s6["peak"]["relative"] - 0.01) < 1e-12, f"6.0 mm mean peak +1 % ({s6['peak']['relative']})")
    check(abs(s6["per_cell"][1]["peak"] - 0.03) < 1e-12, f"its cell 1 +3 % ({s6['per_cell'][1]['peak']})")
    check(s3["e50"]["relative"] == 0.0 and s6["dissipation"]["relative"] == 0.0, "unchanged measures: 0")
    check(s3["crack_geometries"] == {"reference": 60, "candidate": 24}, f"geometries summed ({s3['crack_geometries']})")
    check((root / "out" / "ensemble_comparison.md").read_text().startswith("| size mm |"), "markdown table written")

    build(root / "cand_dissipation", dissipation_factor=1.07)
    code, out, err = run(root / "ref", root / "cand_dissipation")
    check(code == 1, f"dissipation +7 %: exit 1 ({code})")
    check("NOT within" in out, "the verdict says so")

    build(root / "cand_failed")
    (root / "cand_failed" / "size_6.0mm" / "cell_02").rename(root / "gone")
    make_cell(root / "cand_failed", 6.0, 2, 0.0, 0.0, 0.0, bridged=False)
    code, out, err = run(root / "ref", root / "cand_failed", root / "out_failed")
    r = json.loads((root / "out_failed" / "ensemble_comparison.json").read_text())
    s6 = r["sizes"][1]
    check(code == 0 and s6["paired"] == 2 and s6["not_bridged_in_one"] == [2],
          f"a failed candidate cell is left out and listed ({code}, {s6['paired']}, {s6['not_bridged_in_one']})")
    check(abs(s6["peak"]["reference"] - 15.5e6) < 1e-6, "the means over the pairs both bridged")

    build(root / "cand_seed")
    p = root / "cand_seed" / "size_3.0mm" / "cell_01" / "summary.json"
    s = json.loads(p.read_text())
    s["cell"]["seed"] = 7
    p.write_text(json.dumps(s))
    code, out, err = run(root / "ref", root / "cand_seed")
    check(code == 2 and "cell_01" in err and "'cell.seed'" in err, f"another seed: exit 2 naming the cell ({code}: {err.strip()})")

    build(root / "cand_extra")
    make_cell(root / "cand_extra", 3.0, 5, 16.0, 7e-4, 1.2e4)
    code, out, err = run(root / "ref", root / "cand_extra")
    check(code == 2 and "cell_05" in err, f"a cell the reference lacks: exit 2 naming it ({code}: {err.strip()})")

    code, out, err = run(root / "nowhere", root / "cand")
    check(code == 2 and "nowhere" in err, f"a missing directory: exit 2 naming it ({code})")

print(f"{len(failures)} failure(s)")
sys.exit(1 if failures else 0)
