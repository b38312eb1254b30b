#!/usr/bin/env python3
"""The sweep, thickness-study and report targets of pipelines/Makefile end to end on the coarse disc.

usage: check_sweep_pipeline.py --source SRC --build BUILD --out DIR

Runs `make -C SRC/pipelines sweep thickness-study report` with 3 velocities (689 and 1112 m/s match Table
5 shots, 900 m/s matches none) at 31.75 mm and a thickness study of 2 thicknesses x 2 velocities that
reuses the sweep's runs at 31.75 mm, on data/macro_disc_afc_coarse.json with a 0.4 ms end time (5 runs,
a few seconds each). Checks: the table's residual velocities are those of each run's result.json; the
comparison keeps the unmatched run and takes its statistics over the matched ones; the fit is physical
and inside its bootstrap interval; a second `make sweep` runs nothing; the thickness study reuses the
sweep's runs; the report page links only figures that exist, shows each run's provenance and the SDEL
fitted to the stored microcell ensemble (constants with standard errors beside Table 4, fit per size).
"""
import csv
import json
import pathlib
import shutil
import subprocess

from make_target_case import ENV, Checks, make_command, start

check = Checks()


def main():
    src, build, out = start()
    make = make_command(src, build, out, "SHOT_SET=--set run.end_time_s=4e-4", "VELOCITIES=689 900 1112",
                        "THICKNESS=0.03175", "THICKNESSES=0.025 0.03175", "TS_VELOCITIES=689 1112", "BOOTSTRAP=200")
    done = subprocess.run(make + ["-j2", "sweep", "thickness-study"], env=ENV)
    check(done.returncode == 0, "make sweep thickness-study exits 0")
    check.exit_if_failed()
    # A calibration beside the runs (the stored ensemble, a fraction of a second) for the report's section.
    done = subprocess.run([str(pathlib.Path(build) / "calibrate" / "uhpc-calibrate"), "--ensemble",
                           str(src / "data" / "micro_analysis_ensemble_cells" / "ensemble_4x10.h5"),
                           "--out", str(out / "calibrate" / "sdel.json")], env=ENV)
    check(done.returncode == 0, "uhpc-calibrate on the stored ensemble exits 0")
    done = subprocess.run(make + ["report"], env=ENV)
    check(done.returncode == 0, "make report exits 0")

    sweep = out / "sweep" / "t0.03175"
    for name in ("sweep.csv", "sweep.md", "sweep.json", "sweep.png", "comparison.json"):
        check((sweep / name).is_file(), f"sweep/t0.03175/{name} exists")
    check((sweep / "sweep.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", "sweep.png is a PNG")

    # The table against each run's own result.json.
    with open(sweep / "sweep.csv") as f:
        rows = list(csv.DictReader(f))
    check([float(r["impact_velocity_m_s"]) for r in rows] == [689.0, 900.0, 1112.0], "one row per velocity, in order")
    for r in rows:
        res = json.loads((sweep / f"v{float(r['impact_velocity_m_s']):g}" / "result.json").read_text())
        expected = res["residual_velocity_m_s"] if res["perforated"] else 0.0
        got = float(r["residual_velocity_m_s"]) if r["residual_velocity_m_s"] else None
        check(res["outcome"] != "undecided" and got is not None and abs(got - expected) < 1e-9,
              f"v{r['impact_velocity_m_s']}: table residual {got} = result.json's {expected} ({res['outcome']})")
        check(r["outcome"] == res["outcome"], f"v{r['impact_velocity_m_s']}: outcome {r['outcome']}")
        # The plug and the a it implies, from the same result.json (empty when the sphere did not perforate).
        m, m_plug = res["inputs"]["projectile"]["mass_kg"], res["panel"]["plug"]["mass_kg"]
        if res["perforated"]:
            check(abs(float(r["plug_mass_kg"]) - m_plug) < 1e-12 and abs(float(r["a_plug"]) - m / (m + m_plug)) < 1e-12,
                  f"v{r['impact_velocity_m_s']}: plug {r['plug_mass_kg']} kg, a_plug {r['a_plug']} = m / (m + m_plug)")
        else:
            check(r["plug_mass_kg"] == "" and r["a_plug"] == "", f"v{r['impact_velocity_m_s']}: no plug when not perforated")

    # uhpc-compare-shots kept the run without an experiment, statistics over the two matched ones.
    c = json.loads((sweep / "comparison.json").read_text())
    s = c["summary"]["simulation"]
    check(s["shots_total"] == 3 and s["shots"] == 2 and s["shots_without_experiment"] == 1,
          f"comparison: 3 shots, 2 matched ({s['shots_total']}, {s['shots']}, {s['shots_without_experiment']})")
    unmatched = [x for x in c["shots"] if not x["matched"]]
    check(len(unmatched) == 1 and unmatched[0]["simulation"]["impact_velocity_m_s"] == 900
          and unmatched[0]["experiment"]["residual_velocity_m_s"] is None, "the 900 m/s run is listed, unmatched")
    errs = [x["simulation"]["residual_velocity_error_m_s"] for x in c["shots"] if x["matched"]]
    rms = (sum(e * e for e in errs) / len(errs)) ** 0.5
    check(abs(rms - s["rms_residual_velocity_error_m_s"]) < 1e-9, f"RMS {rms:.3f} m/s over the matched runs")

    # The fits: physical constants, inside their bootstrap intervals.
    fits = json.loads((sweep / "sweep.json").read_text())["fits"]
    for name in ("sweep", "experiments"):
        f = fits[name]
        vmin = min(float(r["impact_velocity_m_s"]) for r in rows if float(r["residual_velocity_m_s"] or 0) > 0) \
            if name == "sweep" else 610.0
        check(0.0 < f["a"] <= 1.0 and 0.0 <= f["v_bl_m_s"] < vmin and 0.3 <= f["p"] <= 6.1,
              f"{name} fit physical: a {f['a']:.3f}, v_bl {f['v_bl_m_s']:.1f} < {vmin:g}, p {f['p']:.2f}")
        b = f["bootstrap"]
        check(b["resamples"] == 200 and b["seed"] == 20261205, f"{name}: 200 resamples, seed 20261205")
        for k in ("a", "v_bl_m_s", "p"):
            lo, hi = b["ci"][k]
            check(lo <= f[k] + 1e-9 and f[k] - 1e-9 <= hi, f"{name}: {k} {f[k]:.4g} in [{lo:.4g}, {hi:.4g}]")
    exp = fits["experiments"]
    check(exp["points"] == 7 and exp["rms_m_s"] < 30.0, f"the experiments' fit: 7 points, RMS {exp['rms_m_s']:.1f}")

    # Resumable: a second make sweep keeps every run made from the same inputs (uhpc-macro --reuse: their
    # files untouched) and refuses one made from other inputs (exit 2, naming it) without touching it.
    runs = sorted(sweep.glob("v*/result.json"))
    before = {r: (r.read_bytes(), (r.parent / "history.csv").stat().st_mtime_ns) for r in runs}
    again = subprocess.run(make + ["sweep"], env=ENV, capture_output=True, text=True)
    check(again.returncode == 0 and all((r.read_bytes(), (r.parent / "history.csv").stat().st_mtime_ns) == before[r]
                                        for r in runs), f"a second make sweep keeps its {len(runs)} runs untouched")
    # Through a launcher (as Slurm's srun), a finished shot is recognised before the launcher
    # (pipelines/launch_shot.sh): no launch for the kept runs, one for a run that is missing.
    launcher = out / "launcher.sh"
    launcher.write_text(f"#!/bin/sh\necho \"$*\" >> {out / 'launches.txt'}\nexec \"$@\"\n")
    launcher.chmod(0o755)
    through = subprocess.run(make + ["sweep", f"LAUNCH={launcher}"], env=ENV, capture_output=True, text=True)
    check(through.returncode == 0 and not (out / "launches.txt").exists()
          and all(r.read_bytes() == before[r][0] for r in runs), "through a launcher, the kept runs launch nothing")
    shutil.rmtree(sweep / "v900")
    through = subprocess.run(make + ["sweep", f"LAUNCH={launcher}"], env=ENV, capture_output=True, text=True)
    launched = (out / "launches.txt").read_text().splitlines() if (out / "launches.txt").exists() else []
    check(through.returncode == 0 and len(launched) == 1 and "projectile.velocity_m_s=900" in launched[0]
          and (sweep / "v900" / "result.json").is_file(), f"through a launcher, only the missing run is launched: {launched}")
    runs = sorted(sweep.glob("v*/result.json"))
    before = {r: (r.read_bytes(), (r.parent / "history.csv").stat().st_mtime_ns) for r in runs}
    other = [a if not a.startswith("SHOT_SET=") else "SHOT_SET=--set run.end_time_s=5e-4" for a in make]
    refused = subprocess.run(other + ["sweep"], env=ENV, capture_output=True, text=True)
    check(refused.returncode != 0 and "made from other inputs" in refused.stderr
          and all(r.read_bytes() == before[r][0] for r in runs),
          "make sweep with another SHOT_SET stops, naming a run made from other inputs, and changes nothing")

    # The thickness study: 2 thicknesses, the 31.75 mm runs are the sweep's.
    t = json.loads((out / "thickness" / "thickness.json").read_text())
    ts = t["thicknesses"]
    check([x["thickness_m"] for x in ts] == [0.025, 0.03175], "thickness study: 0.025 and 0.03175 m")
    check((out / "thickness" / "thickness.png").is_file(), "thickness.png exists")
    for x in ts:
        for r in x["runs"]:
            res = json.loads((pathlib.Path(r["run"]) / "result.json").read_text())
            check(abs(res["inputs"]["target"]["thickness_m"] - x["thickness_m"]) < 1e-12
                  and r["residual_velocity_m_s"] == (res["residual_velocity_m_s"] if res["perforated"] else 0.0),
                  f"t {x['thickness_m']} v {r['impact_velocity_m_s']:g}: residual {r['residual_velocity_m_s']} "
                  "from its result.json")
    check(all(str(sweep) in r["run"] for r in ts[1]["runs"]), "the 31.75 mm runs are the sweep's")
    # Two runs and two constants: the fit is exact and says so instead of printing an RMS of 0.
    exact = [x for x in ts if x["lambert_jonas_p2"] and x["lambert_jonas_p2"]["degrees_of_freedom"] == 0]
    table = (out / "thickness" / "thickness.md").read_text()
    check(len(exact) > 0 and "exact: 2 runs, 2 constants" in table and "| 0.0 |" not in table,
          f"{len(exact)} exact fit(s) flagged as exact in thickness.md, no RMS of 0 printed")
    thin = {r["impact_velocity_m_s"]: r["residual_velocity_m_s"] for r in ts[0]["runs"]}
    thick = {r["impact_velocity_m_s"]: r["residual_velocity_m_s"] for r in ts[1]["runs"]}
    check(all(thin[v] >= thick[v] for v in thin), f"a thinner target leaves the sphere faster: {thin} vs {thick}")

    # The report page.
    page = (out / "report" / "report.md").read_text()
    # The coarse disc's shots take more than half of the sphere's energy in contact and stabilization.
    warned = [r for r in (out / "sweep").rglob("result.json") if json.loads(r.read_text()).get("warnings")]
    check(len(warned) > 0 and "## Warnings of the runs" in page and "| numerical_dissipation |" in page,
          f"the report lists the runs' warnings ({len(warned)} runs warned)")
    import re
    links = re.findall(r"!\[[^\]]*\]\(([^)]+)\)", page)
    check(len(links) >= 2, f"the page shows figures ({len(links)})")
    check(all((out / "report" / l).is_file() for l in links), "every figure the page links is in the folder")
    check("Not run: the seven shots (31.75 mm). Command: `make -C pipelines shots`" in page, "shots listed as not run")
    # Each study names its case and spacing; the coarse disc (6 mm) is marked a demonstration.
    check("Case `macro_disc_afc_coarse.json`" in page and "axis spacing 6.00 mm" in page
          and "**A demonstration**" in page, "the studies are labelled with their case and marked a demonstration")
    # Every ballistic-limit estimate in one table with its method; the exact p = 2 fits say so.
    estimates = page.split("## Ballistic limit: every estimate")[-1].split("## Warnings")[0]
    check("| sweep/t0.03175 | Lambert-Jonas, p free |" in estimates and "| sweep/t0.03175 | Lambert-Jonas, p = 1 |"
          in estimates and "| Lambert-Jonas, p = 2 |" in estimates and "exact: 2 runs, 2 constants" in estimates,
          "the report's ballistic-limit table labels each estimate with its study and method")
    # The panel of every run, in the run's own figures (a perforated 1112 m/s shot: a hole, no deflection).
    panels = page.split("## The panel after each run")[-1].split("## Warnings")[0]
    fast = json.loads((sweep / "v1112" / "result.json").read_text())
    hole_mm = 1e3 * fast["panel"]["hole_diameter_m"]
    check(fast["outcome"] == "perforated" and hole_mm > 0.0 and fast["panel"]["rear_face_deflection_m"] is None
          and f"| sweep/t0.03175/v1112 | 1112 | perforated | {fast['residual_velocity_m_s']:.1f} |" in panels
          and f"| {hole_mm:.1f} |" in panels, f"the report shows each run's panel (1112 m/s: hole {hole_mm:.1f} mm)")
    fit = json.loads((out / "calibrate" / "fit_report.json").read_text())["sdel"]
    check(f"| A | {fit['constants']['A']:.4g} | {fit['standard_errors']['A']:.3g} |" in page
          and "| 0.0002 |" in page, "the calibration shows the fitted A with its standard error beside Table 4's")
    check(all(f"| {1e3 * r['size_m']:.2f} | {r['lambda']:.4g} | {r['r_squared']:.4f} |" in page
              for r in fit["per_size"]), "the calibration shows the fit of every cell size")
    for run_dir in list(sweep.glob("v*")) + list((out / "sweep" / "t0.025").glob("v*")):
        res = json.loads((run_dir / "result.json").read_text())
        check(res["provenance"]["config_hash"] in page, f"{run_dir.name}: config hash in the provenance")
    check.exit_if_failed()
    print("all checks passed")


if __name__ == "__main__":
    main()
