#!/usr/bin/env python3
"""pipelines/sweep_report.py's plug columns on hand-made result.json files: a perforating run gives its plug
and a = m / (m + m_plug); an embedded, an undecided run and one of an earlier build (no panel, or a null
one) give none; a result_file that cannot be found from here is refused with exit 2, naming it."""
import json
import pathlib
import subprocess
import sys
import tempfile

from pipeline_checks import check, finish  # puts pipelines/ on the path first
import sweep_report  # noqa: E402

M = 0.009071


def result(folder, name, perforated, panel=True, null_panel=False):
    r = {"perforated": perforated, "inputs": {"projectile": {"mass_kg": M}}}
    if null_panel:
        r["panel"] = None
    elif panel:
        r["panel"] = {"plug": {"mass_kg": 0.0487, "particles": 742, "velocity_m_s": 9.2}}
    path = pathlib.Path(folder) / name / "result.json"
    path.parent.mkdir(parents=True)
    path.write_text(json.dumps(r))
    return path


with tempfile.TemporaryDirectory() as d:
    m_plug, a = sweep_report.plug_share(result(d, "v496", True), "comparison.json")
    check(m_plug == 0.0487 and abs(a - M / (M + 0.0487)) < 1e-15, f"perforated: plug {m_plug} kg, a {a:.4f} (0.1570)")
    for name, kwargs in [("embedded", {"perforated": False}), ("undecided", {"perforated": False}),
                         ("earlier build", {"perforated": True, "panel": False}),
                         ("null panel", {"perforated": True, "null_panel": True})]:
        got = sweep_report.plug_share(result(d, name.replace(" ", "_"), **kwargs), "comparison.json")
        check(got == (None, None), f"{name}: no plug ({got})")
    # A result_file recorded relative to another folder: exit 2 naming the comparison, the key and the path.
    comparison = pathlib.Path(d) / "comparison.json"
    comparison.write_text(json.dumps({"shots": [{"label": "v1", "result_file": "elsewhere/v1/result.json",
                                                 "simulation": {"impact_velocity_m_s": 600.0, "outcome": "perforated",
                                                                "residual_velocity_m_s": 50.0,
                                                                "final_velocity_m_s": 50.0, "end_time_s": 1e-3,
                                                                "wall_time_s": 1.0},
                                                 "experiment": {"residual_velocity_m_s": None}}]}))
    script = pathlib.Path(sweep_report.__file__)
    done = subprocess.run([sys.executable, str(script), "sweep", str(comparison), "--out", str(pathlib.Path(d) / "out")],
                          capture_output=True, text=True, cwd=d)
    check(done.returncode == 2 and "key 'result_file': elsewhere/v1/result.json not found" in done.stderr,
          f"a result_file not found: exit {done.returncode}, {done.stderr.strip()[:120]}")
finish()
