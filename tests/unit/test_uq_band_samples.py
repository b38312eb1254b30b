#!/usr/bin/env python3
"""pipelines/uq_band.py's band against the number of samples (no program runs; a second).

Samples made so that the band's ends are known: with the first 4 and 8 of 10 samples (the rows are
doublings; the last two samples are in no row). OpenTURNS'
empirical quantile interpolates at the position q n - 1/2 and clips at the ends, so the 5 % and 95 %
quantiles of n <= 10 values are their minimum and maximum, and the rows
hold the running minimum and maximum and the moves between rows are their changes. A sample whose later
values stay inside the first ones is stable from 4 samples; one whose last values widen the band by more
than --stable-to is not stable, and `samples_needed` says so (None). --samples N reads the first N samples
of a folder that holds more, and refuses (exit 2) a folder that holds fewer."""
import json
import os
import pathlib
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "pipelines"))
import uq_band  # noqa: E402

failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def table(values):
    return [{"runs": [{"residual_velocity_m_s": v, "outcome": "perforated"}]} for v in values]


inside = [100.0, 110.0, 95.0, 105.0] + [100.0 + k for k in range(6)]  # 10 values within [95, 110]
vr, bands, conv = uq_band.band([610.0], table(inside), 5.0)
rows = conv["by_samples"]
check([r["samples"] for r in rows] == [4, 8], f"rows at 4 and 8 of the 10 samples (doublings): {[r['samples'] for r in rows]}")
check(all(abs(r["q05"][0] - 95.0) < 1e-12 and abs(r["q95"][0] - 110.0) < 1e-12 for r in rows),
      "every row's band is the first four's, 95-110")
check(rows[0]["largest_move_from_previous_m_s"] is None and all(r["largest_move_from_previous_m_s"] == 0.0 for r in rows[1:]),
      "no move after the first row")
check(conv["samples_needed"] == 4, f"stable from 4 samples ({conv['samples_needed']})")

widening = inside[:7] + [120.0] + inside[8:]  # the 8th value widens the band by 10 m/s
vr, bands, conv = uq_band.band([610.0], table(widening), 5.0)
rows = conv["by_samples"]
check(abs(rows[-1]["largest_move_from_previous_m_s"] - 10.0) < 1e-12, f"the last row moves by 10 m/s ({rows[-1]['largest_move_from_previous_m_s']})")
check(conv["samples_needed"] is None, f"not stable to 5 m/s ({conv['samples_needed']})")
vr, bands, conv = uq_band.band([610.0], table(widening), 12.0)
check(conv["samples_needed"] == 4, f"stable to 12 m/s from 4 samples ({conv['samples_needed']})")

late = [100.0, 110.0, 95.0, 105.0, 80.0, 80.0, 110.0] + [100.0] * 9  # 16: ends 80 and 110 held twice each,
vr, bands, conv = uq_band.band([610.0], table(late), 5.0)  # so the interpolated quantiles of 16 are them
check([r["largest_move_from_previous_m_s"] for r in conv["by_samples"]] == [None, 15.0, 0.0]
      and conv["samples_needed"] == 8, f"a widening between 4 and 8 samples: stable from 8 ({conv['samples_needed']})")

script = pathlib.Path(__file__).resolve().parents[2] / "pipelines" / "uq_band.py"
with tempfile.TemporaryDirectory() as tmp:
    root = pathlib.Path(tmp)
    (root / "sdels").mkdir()
    for k, v in enumerate([100.0, 110.0, 95.0]):
        (root / "sdels" / f"sdel_{k:03d}.json").write_text("{}")
        run = root / "runs" / f"s{k:03d}" / "v610"
        run.mkdir(parents=True)
        (run / "result.json").write_text(json.dumps({"outcome": "perforated", "residual_velocity_m_s": v}))
    (root / "runs" / "s002" / "v689").mkdir()  # a velocity only the third sample has: not read with --samples 2

    def uq_band_cli(*extra):
        r = subprocess.run([sys.executable, str(script), str(root / "runs"), "--sdels", str(root / "sdels"),
                            "--out", str(root / "out"), *extra], capture_output=True, text=True)
        return r.returncode, r.stderr

    code, err = uq_band_cli("--samples", "2")
    doc = json.loads((root / "out" / "uq_band.json").read_text()) if code == 0 else {}
    check(code == 0 and [r["sample"] for r in doc["samples"]] == [0, 1] and doc["velocities_m_s"] == [610.0],
          f"--samples 2 reads s000 and s001 at 610 m/s only (exit {code}: {err.strip()})")
    code, err = uq_band_cli("--samples", "4")
    check(code == 2 and "s003" in err, f"--samples 4 of 3 refused with exit 2 ({code}: {err.strip()})")
    code, err = uq_band_cli("--samples", "3", "--velocities", "610")
    doc = json.loads((root / "out" / "uq_band.json").read_text()) if code == 0 else {}
    check(code == 0 and doc["velocities_m_s"] == [610.0] and len(doc["samples"]) == 3,
          f"--velocities 610 leaves out the third sample's 689 m/s (exit {code}: {err.strip()})")
    code, err = uq_band_cli("--samples", "3", "--velocities", "689")
    check(code == 2 and "s000" in err, f"--velocities 689, which two samples lack, refused with exit 2 ({code}: {err.strip()})")

print(f"{len(failures)} failure(s)")
sys.exit(1 if failures else 0)
