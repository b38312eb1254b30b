#!/usr/bin/env python3
"""A tiny end-to-end case of pipelines/uq_sdel.py (issue 51 item 1): 4 realizations of each size of the
archived cells, 3 bootstrap and 3 covariance samples (about 20 s).

Checks: the handoffs sdel_000..002.json are there and read by uhpc-sdel (the handoff's own validation);
their provenance (fit.uq_sample: source, sample, seed, the realizations drawn or the covariance); each
bootstrap sample's ensemble is the mean of its drawn cells' curves counted with their multiplicities (read
here from the cells' curves.h5, a check of uhpc-micro's assembly, not a second implementation); the
summary's fields; a second run keeps every sample; a run with another seed into the same directory is
refused (exit 2); a selection out of range is bad input naming the file and key.

usage: check_uq_sdel.py --micro UHPC_MICRO --calibrate UHPC_CALIBRATE --sdel-program UHPC_SDEL --source SRC --out DIR
"""
import argparse
import json
import pathlib
import shutil
import subprocess
import sys
import tarfile

import h5py
import numpy as np

ap = argparse.ArgumentParser()
ap.add_argument("--micro", required=True)
ap.add_argument("--calibrate", required=True)
ap.add_argument("--sdel-program", required=True)
ap.add_argument("--source", required=True)
ap.add_argument("--out", required=True)
args = ap.parse_args()
src, out = pathlib.Path(args.source), pathlib.Path(args.out)
R = 4
shutil.rmtree(out, ignore_errors=True)
cells = out / "micro"
cells.mkdir(parents=True)
with tarfile.open(src / "data" / "micro_analysis_ensemble_cells" / "cells.tar.xz") as t:
    t.extractall(cells, members=[m for m in t.getmembers()
                                 if any(f"/cell_{r:02d}/" in m.name + "/" for r in range(R))])
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def uq(source, seed=5, samples=3):
    cmd = [sys.executable, str(src / "pipelines" / "uq_sdel.py"), "--source", source, "--samples", str(samples),
           "--seed", str(seed), "--micro", args.micro, "--calibrate", args.calibrate,
           "--micro-config", str(src / "data" / "micro_analysis_ensemble.json"), "--micro-set", f"--set realizations={R}",
           "--cells", str(cells), "--calibrate-config", str(src / "data" / "calibrate.json"), "--out", str(out / source)]
    return subprocess.run(cmd, capture_output=True, text=True)


def reads(handoff):
    r = subprocess.run([args.sdel_program, "--config", str(src / "data" / "sdel_curves.json"), "--sdel", str(handoff),
                        "--out", str(out / "sdel_eval")], capture_output=True, text=True)
    return r.returncode == 0


for source in ("bootstrap", "covariance"):
    r = uq(source)
    print(r.stdout[-1500:], r.stderr[-1500:], sep="\n")
    check(r.returncode == 0, f"{source}: uq_sdel.py exits 0")
    d = out / source
    files = sorted(d.glob("sdel_*.json"))
    check([f.name for f in files] == ["sdel_000.json", "sdel_001.json", "sdel_002.json"], f"{source}: three handoffs")
    base = json.loads((d / "base" / "sdel.json").read_text())
    for k, f in enumerate(files):
        h = json.loads(f.read_text())
        u = h["fit"].get("uq_sample", {})
        check(u.get("source") == source and u.get("sample") == k and u.get("seed") == 5 + k and u.get("plan_hash"),
              f"{f.name}: provenance source, sample, seed, plan hash")
        check(reads(f), f"{f.name}: read by uhpc-sdel")
        if source == "bootstrap":
            draws = u.get("draws", [])
            check(len(draws) == 4 and all(len(x) == R and all(0 <= i < R for i in x) for x in draws),
                  f"{f.name}: {R} realizations drawn per size")
            ens = d / u["fit_directory"] / "ensemble"
            summ = json.loads((ens / "summary.json").read_text())
            check([s["realizations"] for s in summ["cell_selection"]["sizes"]] == draws,
                  f"{f.name}: the assembly's summary lists the draws")
            with h5py.File(ens / "ensemble.h5") as e:
                ok = list(e["cells"][()]) == [R] * 4
                for i, size in enumerate(e["sizes"][()]):
                    curves = []
                    for r in draws[i]:
                        with h5py.File(cells / f"size_{size * 1e3:.1f}mm" / f"cell_{r:02d}" / "curves.h5") as c:
                            curves.append(c["resampled/damage"][()])
                    ok = ok and np.allclose(e["damage/mean"][i], np.mean(curves, axis=0), rtol=0, atol=1e-13)
            check(ok, f"{f.name}: the ensemble is the mean of the drawn cells, with multiplicities")
            check(h["constants"] != base["constants"] or len({tuple(x) for x in draws}) == 1,
                  f"{f.name}: refitted constants differ from the base fit's")
        else:
            check(all(v > 0 for v in h["constants"].values()) and h["provenance"]["seed"] == 5 + k and
                  u.get("covariance", {}).get("matrix") == base["fit"]["sdel"]["covariance"]["matrix"],
                  f"{f.name}: constants > 0, seed in provenance, the base fit's covariance")
    s = json.loads((d / "summary.json").read_text())
    check(s["source"] == source and s["samples_written"] == 3 and set(s["constants"]) == {"a", "A", "nu", "chi"} and
          all({"mean", "std", "q05", "q95", "base_standard_error"} <= set(v) for v in s["constants"].values()) and
          len(s["correlation"]["pearson"]) == 4 and (d / "summary.md").exists(),
          f"{source}: summary.json and summary.md")
    check(all(v["q05"] <= v["mean"] <= v["q95"] for v in s["constants"].values()), f"{source}: 5 % <= mean <= 95 %")
    before = [f.read_bytes() for f in files]
    r = uq(source)
    check(r.returncode == 0 and [f.read_bytes() for f in files] == before, f"{source}: a second run keeps every sample")
    r = uq(source, seed=6)
    check(r.returncode == 2 and "made from other inputs" in r.stderr, f"{source}: another seed is refused: "
          f"{r.stderr.strip()[-200:]}")

# Bad input: a realization out of range, named with its file and key.
sel = out / "bad_selection.json"
sel.write_text(json.dumps({"format": "uhpc-cell-selection/1", "sizes": [
    {"cell_size_m": s, "realizations": [0, R]} for s in (0.003, 0.0045, 0.005, 0.0065)]}))
r = subprocess.run([args.micro, "ensemble", "--config", str(src / "data" / "micro_analysis_ensemble.json"), "--set",
                    f"realizations={R}", "--assemble-only", "--select", str(sel), "--assemble-to", str(out / "bad"),
                    "--out", str(cells)], capture_output=True, text=True)
check(r.returncode == 2 and f"{sel}: key 'sizes[0].realizations[1]'" in r.stderr,
      f"a realization out of range: exit 2 naming the file and key: {r.stderr.strip()}")
print(f"{len(failures)} failures")
sys.exit(1 if failures else 0)
