#!/usr/bin/env python3
"""A tiny end-to-end case of `make -C pipelines uq` (issue 51 item 2): the coarse disc, 4 SDEL samples of
the fit's covariance, 2 impact velocities (about 30 s).

Checks: the 8 runs and uq_band.{json,md} are there; each sample's runs used its own handoff (the SDEL file's
hash recorded, the runs' config hashes differ between samples and agree with the handoff they name); the
band is ordered (5 % <= median <= 95 %) and holds every sample's residual velocity between the extremes;
the convergence block is there; a second `make uq` runs no shot (every run kept).

usage: check_uq_band.py --source SRC --build BUILD --out DIR
"""
import hashlib
import json
import pathlib
import subprocess

from make_target_case import ENV, Checks, make_command, start

src, build, out = start()
check = Checks()
make = make_command(src, build, out, "UQ_SOURCE=covariance", "UQ_SAMPLES=4", "UQ_VELOCITIES=817 1112")
done = subprocess.run(make + ["-j2", "uq"], env=ENV)
check(done.returncode == 0, "make uq exits 0")
runs = out / "uq" / "covariance"
results = sorted(runs.glob("s*/v*/result.json"))
check(len(results) == 8, f"8 runs (4 samples x 2 velocities): {len(results)}")
band_file = runs / "uq_band.json"
check(band_file.is_file() and (runs / "uq_band.md").is_file(), "uq_band.json and uq_band.md written")
check.exit_if_failed()

band = json.loads(band_file.read_text())
check(band["format"] == "uhpc-uq-band/1" and band["source"] == "covariance", "format and source")
check([s["sample"] for s in band["samples"]] == [0, 1, 2, 3], "the four samples, in order")
for s in band["samples"]:
    sdel = pathlib.Path(s["sdel"])
    check(sdel.name == f"sdel_{s['sample']:03d}.json"
          and hashlib.sha256(sdel.read_bytes()).hexdigest()[:16] == s["sdel_sha256"],
          f"sample {s['sample']}: its handoff and that file's hash")
    for r in s["runs"]:
        result = json.loads((runs / f"s{s['sample']:03d}" / f"v{r['velocity_m_s']:g}" / "result.json").read_text())
        used, constants = result["inputs"]["sdel"], json.loads(sdel.read_text())["constants"]
        check(pathlib.Path(used["path"]).name == sdel.name and all(used[k] == constants[k] for k in constants),
              f"sample {s['sample']} at {r['velocity_m_s']:g} m/s ran with {sdel.name}'s constants")
hashes = [[r["config_hash"] for r in s["runs"]] for s in band["samples"]]
check(len({h[0] for h in hashes}) == 4, "the samples' runs differ in their inputs (their SDEL)")
vr = [[r["residual_velocity_m_s"] for r in s["runs"]] for s in band["samples"]]
for j, b in enumerate(band["band"]):
    col = [row[j] for row in vr]
    check(b["q05"] <= b["median"] <= b["q95"], f"{b['velocity_m_s']:g} m/s: 5 % <= median <= 95 %")
    check(min(col) <= b["q05"] and b["q95"] <= max(col), f"{b['velocity_m_s']:g} m/s: the band within the samples")
check(set(band["convergence"]) >= {"samples", "first_half", "largest_band_end_move_m_s", "stable", "by_samples",
                                   "samples_needed"}, "the convergence block")
check([r["samples"] for r in band["convergence"]["by_samples"]] == [4], "the band against the samples: one row at 4")
check(band["lambert_jonas_p1"]["a"]["q05"] <= band["lambert_jonas_p1"]["a"]["q95"], "the fits' band ordered")

# Resumable: a second make uq keeps every run (uhpc-macro --reuse) and runs no shot.
stamps = {p: p.stat().st_mtime_ns for p in results}
done = subprocess.run(make + ["uq"], env=ENV, capture_output=True, text=True)
check(done.returncode == 0, "a second make uq exits 0")
check(all(p.stat().st_mtime_ns == t for p, t in stamps.items()), "it kept every run")
check.exit()
