#!/usr/bin/env python3
"""Every run target of pipelines/Makefile takes SHOT_CASE, SDEL, OUT and BUILD as the user typed them.

usage: test_pipeline_paths.py SOURCE_DIR

From a scratch directory holding its own case file, `make -n -C SOURCE_DIR/pipelines <target>` (a dry run:
nothing is built or run) with SHOT_CASE=mycase.json (in the scratch directory), SDEL=data/sdel_paper.json
(not there: read from the repository root), OUT=rel_out and BUILD=rel_build. Every uhpc-macro,
ballistic_limit.py and carried_shot.py command a target would run must name the case and SDEL by absolute paths that exist,
run <scratch>/rel_build's program and write under <scratch>/rel_out; the targets that run their own case
through a sub-make (paper-model, model-variants) the same but for the case. A shell sets PWD to the
directory it is in; the test sets it the same way. An empty OUT does not reach `rm -rf` in `clean`.
"""
import os
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile

TARGETS = ["shots", "shots-measured", "spacing-study", "refinement-study", "rim-study", "ballistic-limit",
           "sweep", "thickness-study"]
OWN_CASE = ["paper-model", "model-variants"]  # the paper-model case, through a sub-make


def main():
    src = pathlib.Path(sys.argv[1]).resolve()
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        scratch = pathlib.Path(tmp)
        shutil.copy(src / "data" / "macro_disc_afc_coarse.json", scratch / "mycase.json")
        # As from a shell in the scratch directory, whatever started the test (ctest under `make test`
        # hands down the outer make's MAKEFLAGS and MAKELEVEL).
        env = {k: v for k, v in os.environ.items() if k not in ("MAKEFLAGS", "MFLAGS", "MAKELEVEL", "UHPC_STARTED_IN")}
        env["PWD"] = str(scratch)
        for target in TARGETS + OWN_CASE:
            cmd = ["make", "-n", "-C", str(src / "pipelines"), "--no-print-directory", "-o", "macro-tools",
                   target, "SHOT_CASE=mycase.json", "SDEL=data/sdel_paper.json", "OUT=rel_out", "BUILD=rel_build",
                   "VELOCITIES=700", "TS_VELOCITIES=700", "THICKNESSES=0.03", "VARIANTS=cutoff", "VARIANT_SDELS=paper"]
            done = subprocess.run(cmd, cwd=scratch, env=env, capture_output=True, text=True)
            commands = done.stdout.replace("\\\n", " ").splitlines()  # continued lines joined
            scripts = ("ballistic_limit.py", "carried_shot.py")
            runs = [l for l in commands if "uhpc-macro --config" in l or any(s in l for s in scripts)]
            problems = []
            if done.returncode != 0:
                problems.append(f"exit {done.returncode}: {done.stderr.strip()[-300:]}")
            if not runs:
                problems.append("no run in the dry run")
            for line in runs:
                config = re.search(r"--config (\S+)", line)
                sdel = re.search(r"--sdel (\S+)", line)
                out = re.search(r"--out (\S+)", line)
                case = src / "data" / "macro_disc_paper_model.json" if target in OWN_CASE else scratch / "mycase.json"
                if not config or config.group(1) != str(case):
                    problems.append(f"case not {case}: {line[:300]}")
                if "uhpc-macro --config" in line and str(scratch / "rel_build" / "macro" / "uhpc-macro") not in line:
                    problems.append(f"program not <scratch>/rel_build's: {line[:300]}")
                if any(s in line for s in scripts) and f"--macro {scratch / 'rel_build' / 'macro' / 'uhpc-macro'}" not in line:
                    problems.append(f"program not <scratch>/rel_build's: {line[:300]}")
                if not sdel or sdel.group(1) != str(src / "data" / "sdel_paper.json"):
                    problems.append(f"SDEL not the root's: {line[:300]}")
                if not out or not out.group(1).startswith(str(scratch / "rel_out") + "/"):
                    problems.append(f"output not under <scratch>/rel_out: {line[:300]}")
            print(("ok   " if not problems else "FAIL ") + f"{target}: {len(runs)} run(s)")
            for p in problems[:3]:
                print("     " + p)
            failures += problems
        clean = subprocess.run(["make", "-n", "-C", str(src / "pipelines"), "--no-print-directory", "clean", "OUT="],
                               cwd=scratch, env=env, capture_output=True, text=True)
        emptied = clean.stdout.replace("\\\n", " ")
        ok = "must not be empty" in emptied and str(scratch) not in emptied
        print(("ok   " if ok else "FAIL ") + "clean with OUT= guards rm -rf and does not name the directory make started in")
        if not ok:
            failures.append(emptied[:300])
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
