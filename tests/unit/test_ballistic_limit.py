#!/usr/bin/env python3
"""pipelines/ballistic_limit.py against a stand-in for uhpc-macro whose sphere perforates at and above a
known limit (237 m/s): the bracket must contain it to the stated width, each velocity must be run and
listed once, and a run that fails must stop the bisection with the run named."""
import json
import os
import pathlib
import subprocess
import sys
import tempfile

SCRIPT = pathlib.Path(__file__).resolve().parents[2] / "pipelines" / "ballistic_limit.py"

# The stand-in reads --out and projectile.velocity_m_s like uhpc-macro, counts its calls, and writes a
# result.json: perforated at and above LIMIT, embedded below; exit 1 at FAIL_AT.
STAND_IN = """#!{python}
import json, pathlib, sys
a = sys.argv
out = pathlib.Path(a[a.index("--out") + 1])
v = [int(float(s.split("=")[1])) for s in a if s.startswith("projectile.velocity_m_s=")][0]
calls = out.parent / "calls.txt"
calls.write_text((calls.read_text() if calls.exists() else "") + f"{{v}}\\n")
if v == {fail_at}:
    sys.exit(1)
out.mkdir(parents=True, exist_ok=True)
p = v >= {limit}
(out / "result.json").write_text(json.dumps({{"outcome": "perforated" if p else "embedded", "perforated": p,
    "residual_velocity_m_s": 0.2 * v if p else None, "final_velocity_m_s": 0.2 * v if p else 0.0,
    "end_time_s": 1e-3}}))
"""


def bisect(tmp, low, high, fail_at=-1):
    macro = pathlib.Path(tmp) / "macro.py"
    macro.write_text(STAND_IN.format(python=sys.executable, limit=237, fail_at=fail_at))
    macro.chmod(0o755)
    out = pathlib.Path(tmp) / "bl"
    done = subprocess.run([sys.executable, str(SCRIPT), "--macro", str(macro), "--config", "case.json",
                           "--low", str(low), "--high", str(high), "--width", "10", "--out", str(out)],
                          capture_output=True, text=True)
    calls = (out / "calls.txt").read_text().split() if (out / "calls.txt").exists() else []
    return done, out, [int(c) for c in calls]


def check(condition, message):
    if not condition:
        sys.exit("FAILED: " + message)


def main():
    with tempfile.TemporaryDirectory() as tmp:  # the limit inside the bracket
        done, out, calls = bisect(tmp, 200, 300)
        check(done.returncode == 0, done.stderr)
        s = json.loads((out / "ballistic_limit.json").read_text())
        check(s["highest_not_perforating_m_s"] < 237 <= s["lowest_perforating_m_s"], f"bracket {s}")
        check(s["bracket_width_m_s"] <= 10, f"width {s['bracket_width_m_s']}")
        check(len(calls) == len(set(calls)), f"a velocity was run twice: {calls}")
        check(len(s["runs"]) == len(calls), "every run listed once")
    with tempfile.TemporaryDirectory() as tmp:  # the bracket above the limit: widened downward
        done, out, calls = bisect(tmp, 260, 300)
        check(done.returncode == 0, done.stderr)
        s = json.loads((out / "ballistic_limit.json").read_text())
        check(s["highest_not_perforating_m_s"] < 237 <= s["lowest_perforating_m_s"], f"bracket {s}")
        check(len(calls) == len(set(calls)) and len(s["runs"]) == len(calls), f"runs {calls}")
        # resuming reads every result and runs nothing
        done, out, again = bisect(tmp, 260, 300)
        check(done.returncode == 0 and again == calls, f"resume reran: {again} after {calls}")
    with tempfile.TemporaryDirectory() as tmp:  # a failed run stops the bisection, named
        done, out, calls = bisect(tmp, 200, 300, fail_at=250)
        check(done.returncode != 0 and "250 m/s failed" in done.stderr, done.stderr)
    print("ballistic_limit.py: bracket, widening, resume and failure as documented")


if __name__ == "__main__":
    main()
