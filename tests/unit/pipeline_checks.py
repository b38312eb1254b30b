"""What the unit tests of pipelines/*.py share: the scripts on the import path, and checks that are all
run and reported (ok / FAIL, one line each) before the test exits 1 if any failed."""
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "pipelines"))

failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def finish():
    """Exits 1 if any check failed, naming how many, else 0."""
    print(f"{len(failures)} failed")
    sys.exit(1 if failures else 0)
