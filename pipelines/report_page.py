#!/usr/bin/env python3
"""One page gathering the studies found under an output directory, to send to a colleague as one folder.

usage: report_page.py OUT --out OUT/report

Writes OUT/report/report.md and copies every figure it shows into OUT/report/ (links are relative to the
page, so the folder is self-contained). Sections, each shown when its files exist under OUT and listed as
"not run" with its make command otherwise: the microcell ensemble (OUT/micro/*.png), the calibration
(OUT/calibrate/: fit_report.json, figures), the seven shots (OUT/shots/comparison.md, lambert_jonas.md),
the shots at measured thickness, the velocity sweeps (OUT/sweep/t*/sweep.{md,png}), the ballistic limit
(OUT/ballistic_limit/ballistic_limit.md), the thickness study (OUT/thickness/thickness.{md,png}), and the
provenance of every uhpc-macro run under OUT (result.json: program version, commit, config hash, the files
read with their hashes, the overrides).
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


def provenance_rows(root):
    rows = []
    for res in sorted(root.rglob("result.json")):
        if "report" in res.relative_to(root).parts:
            continue
        try:
            r = json.loads(res.read_text())
        except (OSError, ValueError):
            continue
        prov, inputs = r.get("provenance", {}), r.get("inputs", {})
        if not prov or "impact_velocity_m_s" not in r:
            continue
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
            p.include(root / sub / "comparison.md")
            if (root / sub / "lambert_jonas.md").is_file():
                p.include(root / sub / "lambert_jonas.md")
        else:
            p.not_run(name.lower(), command)

    p.add("", "## Velocity sweep")
    sweeps = sorted((root / "sweep").glob("t*/sweep.md")) if (root / "sweep").is_dir() else []
    for md in sweeps:
        p.add("", f"### Thickness {md.parent.name[1:]} m")
        if (md.parent / "sweep.png").is_file():
            p.figure(md.parent / "sweep.png", f"residual against impact velocity, thickness {md.parent.name[1:]} m")
        p.include(md)
    if not sweeps:
        p.not_run("the velocity sweep", "make -C pipelines sweep")

    p.add("", "## Ballistic limit (bisection)")
    if (root / "ballistic_limit" / "ballistic_limit.md").is_file():
        p.include(root / "ballistic_limit" / "ballistic_limit.md")
    else:
        p.not_run("the ballistic-limit bisection", "make -C pipelines ballistic-limit")

    p.add("", "## Thickness study")
    if (root / "thickness" / "thickness.md").is_file():
        if (root / "thickness" / "thickness.png").is_file():
            p.figure(root / "thickness" / "thickness.png", "residual velocity and ballistic limit against thickness")
        p.include(root / "thickness" / "thickness.md")
    else:
        p.not_run("the thickness study", "make -C pipelines thickness-study")

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
