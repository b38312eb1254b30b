#!/usr/bin/env python3
"""One page gathering the studies found under an output directory, to send to a colleague as one folder.

usage: report_page.py OUT --out OUT/report

Writes OUT/report/report.md and copies every figure it shows into OUT/report/ (links are relative to the
page, so the folder is self-contained). Sections, each shown when its files exist under OUT and listed as
"not run" with its make command otherwise: the microcell ensemble (OUT/micro/*.png), the calibration
(OUT/calibrate/: fit_report.json, figures), the seven shots (OUT/shots/comparison.md, lambert_jonas.md),
the shots at measured thickness, the velocity sweeps (OUT/sweep/t*/sweep.{md,png}), the ballistic limit
(OUT/ballistic_limit/ballistic_limit.md), the thickness study (OUT/thickness/thickness.{md,png}), every
ballistic-limit estimate side by side with its method, the uncertainty (OUT/uq_sdel/*/summary.md,
OUT/uq/*/uq_band.md, OUT/sensitivity/sensitivity.md), the runs' warnings, and the provenance of every uhpc-macro run under OUT (result.json: program version, commit, config hash, the files
read with their hashes, the overrides). Each study says the case, SDEL, spacing and particle count of its
runs, and one coarser than the paper's 3.0 mm core is marked as a demonstration.
"""
import argparse
import json
import pathlib
import shutil


def rel(path, root):
    return str(pathlib.Path(path).relative_to(root))


class Page:
    def __init__(self, root, out):
        self.root, self.out = root, out
        self.lines = []
        self.figures = []

    def add(self, *lines):
        self.lines.extend(lines)

    def figure(self, src, caption):
        """Copy src into the report folder (a unique name from its path under OUT) and link it."""
        name = rel(src, self.root).replace("/", "__")
        shutil.copyfile(src, self.out / name)
        self.figures.append(name)
        self.add("", f"![{caption}]({name})", "", f"*{caption}* (`{rel(src, self.root)}`)", "")

    def include(self, src):
        text = pathlib.Path(src).read_text().rstrip()
        self.add("", f"From `{rel(src, self.root)}`:", "", text, "")

    def not_run(self, what, command):
        self.add("", f"Not run: {what}. Command: `{command}`", "")


def paper_table4():
    """The paper's SDEL constants (data/table4_sdel_constants.csv), by name; {} when the file is absent."""
    path = pathlib.Path(__file__).resolve().parent.parent / "data" / "table4_sdel_constants.csv"
    if not path.is_file():
        return {}
    rows = [line.split(",") for line in path.read_text().splitlines() if line and not line.startswith("#")]
    return {r[0]: float(r[2]) for r in rows[1:]}


def calibration_lines(rep, paper):
    """uhpc-calibrate's fit_report.json as Markdown: the constants with their standard errors beside the
    paper's Table 4, the fit per cell size, the size effect of the nominal strength, the notes, provenance."""
    sdel, lines = rep.get("sdel", {}), []
    constants, se = sdel.get("constants", {}), sdel.get("standard_errors", {})
    rse, ident = sdel.get("relative_standard_errors", {}), sdel.get("identifiable", {})
    if constants:
        lines += ["", "| constant | fitted | standard error | relative | identifiable | paper (Table 4) |",
                  "|---|---|---|---|---|---|"]
        for k, v in constants.items():
            lines.append(f"| {k} | {v:.4g} | {se[k]:.3g} | {rse[k]:.3f} | {'yes' if ident.get(k) else 'no'} | "
                         f"{paper[k]:.4g} |" if k in se and k in rse and k in paper else f"| {k} | {v:.4g} | | | | |")
        lines += ["", f"Cost {sdel.get('cost', float('nan')):.4g} over {sdel.get('samples', '?')} samples; "
                  f"{sdel.get('starts_agreeing', '?')} of {sdel.get('starts_run', '?')} starts agree on the optimum."]
    per_size = sdel.get("per_size", [])
    if per_size:
        lines += ["", "| cell size mm | lambda | R^2 | RMS of d | max abs residual | samples |", "|---|---|---|---|---|---|"]
        lines += [f"| {1e3 * r['size_m']:.2f} | {r['lambda']:.4g} | {r['r_squared']:.4f} | {r['rms']:.4f} | "
                  f"{r['max_abs_residual']:.4f} | {r['samples']} |" for r in per_size]
    size = rep.get("size_effect", {})
    if size.get("sizes_m"):
        lines += ["", f"Size effect of the nominal strength ({size.get('law', '')}): B = {size['B']:.4g}, "
                  f"D0 = {1e3 * size['D0_m']:.4g} mm, R^2 {size['r_squared']:.3f}.", "",
                  "| cell size mm | nominal strength MPa | fitted MPa |", "|---|---|---|"]
        lines += [f"| {1e3 * d:.2f} | {1e-6 * n:.3f} | {1e-6 * f:.3f} |"
                  for d, n, f in zip(size["sizes_m"], size["nominal_strength_Pa"], size["fitted_Pa"])]
    notes = list(sdel.get("notes", [])) + ([size["note"]] if size.get("note") else [])
    if notes:
        lines += [""] + [f"- {n}" for n in notes]
    ens, prov = rep.get("ensemble", {}), rep.get("provenance", {})
    ens_prov = ens.get("provenance", {})
    lines += ["", f"Ensemble `{ens.get('file', '?')}` (made by {ens_prov.get('program', '?')}, commit "
              f"{ens_prov.get('git_commit', '?')}, {ens_prov.get('date_utc', '?')}); fitted by "
              f"{prov.get('program', '?')} {prov.get('version', '')}, commit {prov.get('git_commit', '?')}, "
              f"config hash {prov.get('config_hash', '?')}, {prov.get('date_utc', '?')}."]
    return lines


PAPER_AXIS_SPACING_M = 0.003  # the paper's particle spacing at the panel's centre (section 5.4)


def study_label(run_dirs):
    """One line saying what a study's runs were made of (the case file, the SDEL, the spacing at the axis and
    the particle count), read from their config.json and result.json; a study coarser than the paper's 3.0 mm
    core is marked as a demonstration of the workflow. "" when no run is there."""
    cases, sdels, spacings, counts = set(), set(), set(), set()
    for d in run_dirs:
        try:
            config = json.loads((d / "config.json").read_text())
            result = json.loads((d / "result.json").read_text())
        except (OSError, ValueError):
            continue
        target = config.get("case", {}).get("target", {})
        cases.add(pathlib.Path(config.get("case_file", "?")).name)
        sdels.update(pathlib.Path(f["path"]).name for f in config.get("files", []) if f.get("role") == "sdel")
        spacing = target.get("h_axis_m", target.get("spacing_m"))
        if spacing is not None:
            spacings.add(float(spacing))
        counts.add(result.get("particle_count"))
    if not cases:
        return ""
    join = lambda xs: ", ".join(f"`{x}`" for x in sorted(xs))
    sdel_text = join(sdels) if len(sdels) <= 3 else f"{len(sdels)} handoffs (`{min(sdels)}` ... `{max(sdels)}`)"
    line = (f"Case {join(cases)}" + (f", SDEL {sdel_text}" if sdels else "")
            + (f"; axis spacing {', '.join(f'{1e3 * h:.2f}' for h in sorted(spacings))} mm" if spacings else "")
            + f"; {', '.join(str(c) for c in sorted(c for c in counts if c is not None))} particles.")
    if spacings and max(spacings) > PAPER_AXIS_SPACING_M * 1.001:
        line += (f" **A demonstration**: coarser than the paper's {1e3 * PAPER_AXIS_SPACING_M:.1f} mm core, so its "
                 "figures show the workflow, not converged answers.")
    return line


def fit_row(study, method, f, fixed_p):
    """A row of the ballistic-limit table from a Lambert-Jonas fit, with what a reader must know of it."""
    ci = f.get("bootstrap", {}).get("ci", {}).get("v_bl_m_s")
    dof = f["points"] - (2 if fixed_p else 3)
    notes = []
    if not f.get("v_bl_bracketed", True):
        notes.append("extrapolated (every run perforated)")
    if dof == 0:
        notes.append(f"exact: {f['points']} runs, {f['points']} constants")
    elif dof < 0:
        notes.append(f"underdetermined: {f['points']} runs, {f['points'] - dof} constants")
    if f.get("p_at_search_edge"):
        notes.append("p at its search edge")
    interval = f"[{ci[0]:.0f}, {ci[1]:.0f}] (bootstrap 95 %)" if ci else ""
    return f"| {study} | {method} | {f['v_bl_m_s']:.0f} | {interval} | {f['points']} | {'; '.join(notes)} |"


def ballistic_limit_rows(root):
    """Every ballistic-limit estimate under OUT, each labelled with its method: the bisection's bracket and the
    Lambert-Jonas fits (p free, p = 1, p = 2) of the shots, the sweeps and the thickness study."""
    rows = []
    bl = root / "ballistic_limit" / "ballistic_limit.json"
    if bl.is_file():
        b = json.loads(bl.read_text())
        notes = []
        if b.get("undecided_runs_m_s"):
            notes.append(f"undecided at {b.get('end_time_s')} s counted as not perforating: {b['undecided_runs_m_s']} m/s")
        rows.append(f"| ballistic_limit | bisection: highest not perforating to lowest perforating | "
                    f"{b['estimate_m_s']:.0f} | [{b['highest_not_perforating_m_s']:g}, {b['lowest_perforating_m_s']:g}] "
                    f"(bracket) | {len(b.get('runs', []))} | {'; '.join(notes)} |")
    studies = [(d, root / d / "lambert_jonas.json") for d in ("shots", "shots_measured")]
    studies += [(rel(p.parent, root), p) for p in sorted(root.glob("sweep/t*/sweep.json"))]
    for study, path in studies:
        if not path.is_file():
            continue
        data = json.loads(path.read_text())
        fits = data.get("fits", data)
        for name, f in fits.items():
            if name.startswith("experiments") or not isinstance(f, dict) or "v_bl_m_s" not in f:
                continue
            fixed = "p = 1" in name
            rows.append(fit_row(study, "Lambert-Jonas, p = 1" if fixed else "Lambert-Jonas, p free", f, fixed))
    th = root / "thickness" / "thickness.json"
    if th.is_file():
        for s in json.loads(th.read_text()).get("thicknesses", []):
            f = s.get("lambert_jonas_p2")
            if f:
                rows.append(fit_row(f"thickness {1e3 * s['thickness_m']:.2f} mm", "Lambert-Jonas, p = 2", f, True))
    return rows


def macro_results(root):
    """Every uhpc-macro result.json under root (the report's own folder left out): (path, document)."""
    for res in sorted(root.rglob("result.json")):
        if "report" in res.relative_to(root).parts:
            continue
        try:
            r = json.loads(res.read_text())
        except (OSError, ValueError):
            continue
        if r.get("provenance") and "impact_velocity_m_s" in r:
            yield res, r


def mm(value):
    return "" if value is None else f"{1e3 * value:.1f}"


def panel_rows(root):
    """One table row per run: what a test engineer measures on the panel (result.json `panel`)."""
    rows = []
    for res, r in macro_results(root):
        panel = r.get("panel")
        if not panel:
            continue
        plug = panel.get("plug", {})
        plug_text = f"{1e3 * plug['mass_kg']:.1f} g at {plug['velocity_m_s']:.1f} m/s" if plug.get("particles") else ""
        residual = r.get("residual_velocity_m_s")
        rows.append(f"| {rel(res.parent, root)} | {r['impact_velocity_m_s']:.0f} | {r.get('outcome')} | "
                    f"{'' if residual is None else f'{residual:.1f}'} | "
                    f"{mm(panel.get('front_crater_diameter_m'))} / {mm(panel.get('front_crater_depth_m'))} | "
                    f"{mm(panel.get('rear_scab_diameter_m'))} / {mm(panel.get('rear_scab_depth_m'))} | "
                    f"{mm(panel.get('hole_diameter_m'))} | {plug_text} | {mm(panel.get('rear_face_deflection_m'))} |")
    return rows


def provenance_rows(root):
    rows = []
    for res, r in macro_results(root):
        prov, inputs = r.get("provenance", {}), r.get("inputs", {})
        files = "; ".join(f"{f.get('role')}: {f.get('path')} ({f.get('fnv1a64')})" for f in inputs.get("files", []))
        rows.append({"run": rel(res.parent, root), "program": prov.get("program"), "version": prov.get("version"),
                     "commit": prov.get("git_commit"), "config_hash": prov.get("config_hash"),
                     "date": prov.get("date_utc"), "files": files,
                     "overrides": " ".join(inputs.get("overrides", [])), "outcome": r.get("outcome"),
                     "residual": r.get("residual_velocity_m_s"), "warnings": r.get("warnings", [])})
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("root")
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    root = pathlib.Path(args.root).resolve()
    out = pathlib.Path(args.out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    for old in out.glob("*.png"):  # figures of an earlier page
        old.unlink()
    p = Page(root, out)
    p.add("# UHPC penetration studies", "", f"Gathered from `{root}` by `make -C pipelines report` "
          "(pipelines/report_page.py). Figures are beside this page; tables are copied from the study's own files.")

    p.add("", "## Microcell ensemble")
    micro = sorted((root / "micro").glob("*.png")) if (root / "micro").is_dir() else []
    for f in micro:
        p.figure(f, f.stem.replace("_", " "))
    if not micro:
        p.not_run("the microcell ensembles (Figs. 8-9)", "make -C pipelines micro-ensemble")

    p.add("", "## Calibration of the SDEL")
    cal = root / "calibrate"
    if (cal / "sdel.json").is_file():
        if (cal / "fit_report.json").is_file():
            p.add(*calibration_lines(json.loads((cal / "fit_report.json").read_text()), paper_table4()))
        else:
            p.add("", f"`{rel(cal / 'sdel.json', root)}` exists without its fit_report.json: no fit details to show.")
        for f in sorted(cal.glob("*.png")):
            p.figure(f, f.stem.replace("_", " "))
    else:
        p.not_run("the SDEL fitted to the microcell ensemble (Figs. 10-11)", "make -C pipelines calibration")

    for name, sub, command in (("The seven shots (31.75 mm)", "shots", "make -C pipelines shots"),
                               ("The seven shots at measured thickness", "shots_measured",
                                "make -C pipelines shots-measured")):
        p.add("", f"## {name}")
        if (root / sub / "comparison.md").is_file():
            p.add("", study_label(sorted((root / sub).glob("v*"))))
            p.include(root / sub / "comparison.md")
            if (root / sub / "lambert_jonas.md").is_file():
                p.include(root / sub / "lambert_jonas.md")
        else:
            p.not_run(name.lower(), command)

    p.add("", "## Velocity sweep")
    sweeps = sorted((root / "sweep").glob("t*/sweep.md")) if (root / "sweep").is_dir() else []
    for md in sweeps:
        p.add("", f"### Thickness {md.parent.name[1:]} m", "", study_label(sorted(md.parent.glob("v*"))))
        if (md.parent / "sweep.png").is_file():
            p.figure(md.parent / "sweep.png", f"residual against impact velocity, thickness {md.parent.name[1:]} m")
        p.include(md)
    if not sweeps:
        p.not_run("the velocity sweep", "make -C pipelines sweep")

    p.add("", "## Ballistic limit (bisection)")
    if (root / "ballistic_limit" / "ballistic_limit.md").is_file():
        p.add("", study_label(sorted((root / "ballistic_limit").glob("v*"))))
        p.include(root / "ballistic_limit" / "ballistic_limit.md")
    else:
        p.not_run("the ballistic-limit bisection", "make -C pipelines ballistic-limit")

    p.add("", "## Thickness study")
    if (root / "thickness" / "thickness.md").is_file():
        p.add("", study_label(sorted(root.glob("sweep/t*/v*"))))
        if (root / "thickness" / "thickness.png").is_file():
            p.figure(root / "thickness" / "thickness.png", "residual velocity and ballistic limit against thickness")
        p.include(root / "thickness" / "thickness.md")
    else:
        p.not_run("the thickness study", "make -C pipelines thickness-study")

    p.add("", "## Ballistic limit: every estimate", "",
          "One answer per study and method: the bisection's bracket (a property of the runs' end time when runs "
          "near the limit end undecided), and Lambert-Jonas fits, vr = a (v^p - v_bl^p)^(1/p), with p free or held "
          "at 1 or 2; a fit with as many constants as runs passes through them exactly and says nothing of its "
          "error, and an extrapolated v_bl is the fitted curve's foot below the slowest perforating run.")
    estimates = ballistic_limit_rows(root)
    if estimates:
        p.add("", "| study | method | v_bl m/s | interval | runs | notes |", "|---|---|---|---|---|---|", *estimates)
    else:
        p.add("", "No ballistic-limit estimate under the folder.")

    p.add("", "## Uncertainty", "",
          "From the microcells' scatter and the calibration to the residual velocity (docs/uncertainty.md): the SDEL "
          "constants' spread over their samples, the band of the residual velocity over the shots run with each "
          "sample, and the Sobol indices of a surrogate checked on runs it did not see.")
    # (what, its pages, the glob of its runs under a page's folder, the command that makes it)
    uq_parts = [("SDEL samples", sorted(root.glob("uq_sdel/*/summary.md")), None, "make -C pipelines uq-sdel"),
                ("the band of the residual velocity", sorted(root.glob("uq/*/uq_band.md")), "s*/v*",
                 "make -C pipelines uq"),
                ("Sobol indices", sorted(root.glob("sensitivity/sensitivity.md")), "points/k*/v*",
                 "make -C pipelines sensitivity")]
    for what, found, runs, command in uq_parts:
        for md in found:
            p.add("", f"### {what[0].upper() + what[1:]} (`{rel(md.parent, root)}`)")
            if runs:
                p.add("", study_label(sorted(md.parent.glob(runs))))
            p.include(md)
        if not found:
            p.not_run(what, command)

    p.add("", "## The panel after each run", "",
          "What a test engineer measures (result.json `panel`, macro/README.md): the front crater's and the rear "
          "scab's diameter (face-layer particles that moved more than half their spacing) and depth (how deep the "
          "material now out of the face came from), the narrowest clear opening along the shot line, the plug that "
          "leaves with the sphere, and the rear face's deflection at the shot line (+: the sphere's way; none for a "
          "perforated panel). At the run's end time, so a crater may still be growing.")
    panels = panel_rows(root)
    if panels:
        p.add("", "| run | v0 m/s | outcome | residual m/s | crater diameter / depth mm | scab diameter / depth mm | "
              "hole mm | plug | rear deflection mm |", "|---|---|---|---|---|---|---|---|---|", *panels)
    else:
        p.add("", "No uhpc-macro run under the folder.")

    p.add("", "## Warnings of the runs", "",
          "What each run said about its own numbers (result.json `warnings`, macro/README.md): a target too few "
          "particles thick, contact and stabilization taking most of the sphere's energy, the energy check off.")
    warned = [(r["run"], w) for r in provenance_rows(root) for w in r["warnings"]]
    if warned:
        p.add("", "| run | warning | what it says |", "|---|---|---|")
        for run, w in warned:
            p.add(f"| {run} | {w.get('code')} | {w.get('message')} |")
    else:
        p.add("", "No run under the folder warned.")

    p.add("", "## Provenance of the runs", "",
          "Every uhpc-macro run under the folder (its result.json): the program, version and commit that made it, "
          "the config hash (over the case after the overrides and every file read), the files read with their "
          "FNV-1a hashes, and the overrides.")
    rows = provenance_rows(root)
    if rows:
        common = {k: rows[0][k] for k in ("program", "version", "commit", "files")
                  if all(r[k] == rows[0][k] for r in rows)}
        if common:
            p.add("", "Common to all runs: " + "; ".join(f"{k} `{v}`" for k, v in common.items()), "")
        cols = [k for k in ("run", "program", "version", "commit", "config_hash", "date", "files", "overrides",
                            "outcome") if k not in common]
        p.add("| " + " | ".join(cols) + " |", "|" + "---|" * len(cols))
        for r in rows:
            p.add("| " + " | ".join(str(r[k]) if r[k] is not None else "" for k in cols) + " |")
    else:
        p.add("", "No uhpc-macro run under the folder.")
    (out / "report.md").write_text("\n".join(p.lines) + "\n")
    print(f"report_page.py: {out / 'report.md'} with {len(p.figures)} figure(s), {len(rows)} run(s) in the provenance")


if __name__ == "__main__":
    main()
