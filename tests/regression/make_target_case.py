"""What the end-to-end checks of pipelines/Makefile targets share (check_sweep_pipeline.py,
check_uq_band.py, check_sensitivity.py): their arguments (--source, --build, --out), a fresh output
directory, the make command over ctest's build (macro-tools and uq-tools are built already, so make
builds nothing), the runs on 1 thread, and the list of checks with its exit code."""
import argparse
import os
import pathlib
import shutil
import sys

ENV = dict(os.environ, OMP_NUM_THREADS="1")


def start():
    """(source, build, out) from the command line; out emptied."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--source", required=True)
    ap.add_argument("--build", required=True)
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    out = pathlib.Path(args.out)
    shutil.rmtree(out, ignore_errors=True)
    return pathlib.Path(args.source), args.build, out


def make_command(src, build, out, *variables):
    """make -C SRC/pipelines on the coarse disc with `variables` ("NAME=value") after the common ones."""
    return ["make", "-C", str(src / "pipelines"), "--no-print-directory", "-o", "macro-tools", "-o", "uq-tools",
            f"BUILD={build}", f"OUT={out}", f"SHOT_CASE={src}/data/macro_disc_afc_coarse.json", "JOBS=2",
            *variables]


class Checks:
    def __init__(self):
        self.failures = []

    def __call__(self, ok, what):
        print(("ok   " if ok else "FAIL ") + what)
        if not ok:
            self.failures.append(what)

    def exit_if_failed(self):
        if self.failures:
            print(f"{len(self.failures)} check(s) failed")
            sys.exit(1)

    def exit(self):
        self.exit_if_failed()
        sys.exit(0)
