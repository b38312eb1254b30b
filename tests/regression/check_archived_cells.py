#!/usr/bin/env python3
"""The archived cells of the shipped ensemble are reloaded, not recomputed: every cell of
data/micro_analysis_ensemble_cells/cells.tar.xz must match the hash that `uhpc-micro ensemble` computes
today for data/micro_analysis_ensemble.json (cell config, microstructure, size, seed, analysis section,
solver revision), and assembling them must give the stored ensemble_4x25.h5.

A change of any hashed input (a value of those configs, not their "notes" text) or a new solver revision
makes every archived cell stale: `make -C pipelines micro-ensemble` would then recompute all 100 cells
(hours). This test fails first, naming the cause; the remedy is to recompute the ensemble and refresh the
archive (data/micro_analysis_ensemble_cells/README.md), or to undo the change of the hashed input.

It also checks that the archive carries today's hash scheme (a cell stamped with the former one, which
hashed the notes too, is reloaded and re-stamped, so the archive would differ from what the reload
writes), and that such a cell (tests/regression/micro_former_hash_cell: the archive's 3.0 mm cell_00 as
stamped before 2026-12-06) is reloaded and re-stamped, not recomputed.

usage: check_archived_cells.py --micro UHPC_MICRO --source SRC --out DIR
"""
import argparse
import pathlib
import shutil
import subprocess
import sys
import tarfile

import json

import h5py
import numpy as np

ap = argparse.ArgumentParser()
ap.add_argument("--micro", required=True)
ap.add_argument("--source", required=True)
ap.add_argument("--out", required=True)
args = ap.parse_args()
src, out = pathlib.Path(args.source), pathlib.Path(args.out)
archive = src / "data" / "micro_analysis_ensemble_cells"
shutil.rmtree(out, ignore_errors=True)
out.mkdir(parents=True)
with tarfile.open(archive / "cells.tar.xz") as t:
    t.extractall(out)

# --assemble-only analyses nothing: it exits 2 naming the cells whose hash does not match.
run = subprocess.run([args.micro, "ensemble", "--config", str(src / "data" / "micro_analysis_ensemble.json"),
                      "--assemble-only", "-j", "1", "--out", str(out)], capture_output=True, text=True)
print(run.stdout[-2000:], run.stderr[-2000:], sep="\n")
if run.returncode != 0:
    print("FAIL: the archived cells are not reloaded (stale hash): a hashed input of "
          "data/micro_analysis_ensemble.json, data/micro_cell.json or data/microstructure.json, or the solver "
          "revision, changed since they were computed; see this script's docstring")
    sys.exit(1)

failures = 0
with h5py.File(out / "ensemble.h5") as a, h5py.File(archive / "ensemble_4x25.h5") as b:
    for name in ("sizes", "cells", "strain", "nominal_strength", "stress/mean", "stress/std", "damage/mean",
                 "damage/std"):
        x, y = np.asarray(a[name]), np.asarray(b[name])
        ok = x.shape == y.shape and np.allclose(x, y, rtol=1e-12, atol=0.0)
        print(("ok   " if ok else "FAIL ") + f"{name}: assembled from the archive = ensemble_4x25.h5")
        failures += not ok


def cell_hash(directory):
    return json.loads((directory / "summary.json").read_text())["cell_hash"]


with tarfile.open(archive / "cells.tar.xz") as t:
    summaries = [m.name for m in t.getmembers() if m.name.endswith("/summary.json")]
    stale = [name for name in summaries
             if json.load(t.extractfile(name))["cell_hash"] != cell_hash(out / pathlib.Path(name).parent)]
ok = len(summaries) == 100 and not stale
print(("ok   " if ok else "FAIL ") + f"{len(summaries)} archived cells carry today's hash"
      + (f" ({len(stale)} carry the former scheme's, e.g. {stale[0]}: re-stamp the archive)" if stale else ""))
failures += not ok

# A cell stamped with the former scheme: reloaded (the 3.0 mm cell takes minutes to compute, the reload a
# second; its recorded wall time stays the fixture's) and re-stamped with today's hash.
former_dir = src / "tests" / "regression" / "micro_former_hash_cell" / "size_3.0mm" / "cell_00"
again = out.parent / (out.name + "_former_hash")
shutil.rmtree(again, ignore_errors=True)
shutil.copytree(former_dir, again / "size_3.0mm" / "cell_00")
try:
    run = subprocess.run([args.micro, "ensemble", "--config", str(src / "data" / "micro_analysis_ensemble.json"),
                          "--only-size", "3", "--only-cell", "0", "-j", "1", "--out", str(again)],
                         capture_output=True, text=True, timeout=60)
    code = run.returncode
except subprocess.TimeoutExpired:
    code = "timeout (computed, not reloaded)"
fixture = json.loads((former_dir / "summary.json").read_text())
reloaded = json.loads((again / "size_3.0mm" / "cell_00" / "summary.json").read_text())
ok = (code == 0 and fixture["cell_hash"] != reloaded["cell_hash"] == cell_hash(out / "size_3.0mm" / "cell_00")
      and reloaded["wall_s"] == fixture["wall_s"])
print(("ok   " if ok else "FAIL ") + f"a cell of the former hash scheme is reloaded and re-stamped (exit {code}, "
      f"hash {fixture['cell_hash']} -> {reloaded['cell_hash']})")
failures += not ok
sys.exit(1 if failures else 0)
