#!/usr/bin/env python3
"""The archived cells of the shipped ensemble are reloaded, not recomputed: every cell of
data/micro_analysis_ensemble_cells/cells.tar.xz must match the hash that `uhpc-micro ensemble` computes
today for data/micro_analysis_ensemble.json (cell config, microstructure, size, seed, analysis section,
solver revision), and assembling them must give the stored ensemble_4x25.h5.

A change of any hashed input (even a config file's "notes" text) or a new solver revision makes every
archived cell stale: `make -C pipelines micro-ensemble` would then recompute all 100 cells (hours). This
test fails first, naming the cause; the remedy is to recompute the ensemble and refresh the archive
(data/micro_analysis_ensemble_cells/README.md), or to undo the change of the hashed input.

usage: check_archived_cells.py --micro UHPC_MICRO --source SRC --out DIR
"""
import argparse
import pathlib
import shutil
import subprocess
import sys
import tarfile

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
sys.exit(1 if failures else 0)
