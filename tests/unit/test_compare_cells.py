#!/usr/bin/env python3
"""pipelines/compare_cells.py on two hand-made cell directories (summary.json + curves.h5): identical cells
agree; a changed value, a key or a dataset present in only one cell (either one) is a difference and exit 1;
--rtol admits a small relative change and no larger one."""
import json
import pathlib
import subprocess
import sys
import tempfile

import h5py
import numpy as np

SCRIPT = pathlib.Path(__file__).resolve().parents[2] / "pipelines" / "compare_cells.py"
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def make_cell(d, summary, datasets):
    d.mkdir(parents=True)
    (d / "summary.json").write_text(json.dumps(summary))
    with h5py.File(d / "curves.h5", "w") as f:
        for name, values in datasets.items():
            f[name] = np.asarray(values)


def compare(a, b, *extra):
    r = subprocess.run([sys.executable, str(SCRIPT), str(a), str(b), *extra], capture_output=True, text=True)
    return r.returncode, r.stdout


SUMMARY = {"peak_stress_Pa": 1.25e7, "status": "separated", "wall_s": 3.0}
DATA = {"states/strain": [0.0, 1e-4, 2e-4], "states/sigma_bar": [0.0, 4.0e6, 1.0e6], "states/count": [0, 1, 2]}

with tempfile.TemporaryDirectory() as tmp:
    root = pathlib.Path(tmp)
    make_cell(root / "a", SUMMARY, DATA)
    make_cell(root / "same", dict(SUMMARY, wall_s=9.0), DATA)  # wall_s is not compared
    code, out = compare(root / "a", root / "same")
    check(code == 0 and "3 datasets: identical" in out, f"identical cells agree (exit {code}): {out.strip()}")

    make_cell(root / "extra_b", SUMMARY, dict(DATA, **{"states/extra": [1.0]}))
    code, out = compare(root / "a", root / "extra_b")
    check(code == 1 and "curves.h5 states/extra: only in B" in out, f"a dataset only in B is a difference (exit {code})")
    code, out = compare(root / "extra_b", root / "a")
    check(code == 1 and "curves.h5 states/extra: only in A" in out, f"a dataset only in A is a difference (exit {code})")

    make_cell(root / "key_b", dict(SUMMARY, new_key=1), DATA)
    code, out = compare(root / "a", root / "key_b")
    check(code == 1 and "/new_key: only in B" in out, f"a summary key only in B is a difference (exit {code})")

    nudged = dict(DATA, **{"states/sigma_bar": [0.0, 4.0e6 * (1 + 5e-7), 1.0e6]})
    make_cell(root / "nudged", SUMMARY, nudged)
    code, out = compare(root / "a", root / "nudged")
    check(code == 1 and "curves.h5 states/sigma_bar: largest difference 2.000e+00" in out,
          f"a relative change of 5e-7 is a difference by default (exit {code})")
    code, _ = compare(root / "a", root / "nudged", "--rtol", "1e-6")
    check(code == 0, f"... and within --rtol 1e-6 (exit {code})")
    code, _ = compare(root / "a", root / "nudged", "--rtol", "1e-7")
    check(code == 1, f"... but not within --rtol 1e-7 (exit {code})")

    make_cell(root / "status", dict(SUMMARY, status="failed"), DATA)
    code, out = compare(root / "a", root / "status")
    check(code == 1 and "/status: 'separated' against 'failed'" in out, f"a changed text is a difference (exit {code})")

print(f"{len(failures)} failed")
sys.exit(1 if failures else 0)
