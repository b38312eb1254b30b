#!/usr/bin/env python3
"""pipelines/ballistic_limit.py against a stand-in for uhpc-macro whose sphere perforates at and above a
known limit (237 m/s): the bracket must contain it to the stated width, each velocity must be run and
listed once; a run that fails inside the bracket is recorded and bisected around (not rerun on resume),
one at an end of the bracket stops it; too many failures report the bracket reached (exit 1); a resume
reuses a run only if it was made from the same inputs (exit 2 otherwise); a run killed without a
diagnostic stops the bisection (exit 3); nothing perforating up to --max-velocity stops it (exit 1); a run
undecided at its end time is carried on from its checkpoint up to --max-end-time, and recognised on resume."""
import json
import pathlib
import subprocess
import sys
import tempfile

SCRIPT = pathlib.Path(__file__).resolve().parents[2] / "pipelines" / "ballistic_limit.py"

# The stand-in reads --out and projectile.velocity_m_s like uhpc-macro, counts its runs, and writes
# config.json (the inputs' hash) and a result.json: perforated at and above LIMIT, embedded below; at a
# velocity of FAIL_AT, config.json and diagnostic.json and exit 1. At a velocity of UNDECIDED the sphere is
# decided only at DECIDE_TIME: a run ending earlier is undecided and keeps a checkpoint.h5, which --restart
# (exit 2 without one) carries on. --inputs-hash prints the hash of its arguments but --out, -q,
# --restart, --restart-check and --checkpoint-every-min, as uhpc-macro prints the hash of its inputs (the
# end time among them). --restart-check prints "restart" for a checkpoint.h5, "start" for none or one
# reading "other build", and exits 2 for one reading "corrupt"; --checkpoint-every-min is logged in
# clock.txt beside the runs.
STAND_IN = """#!{python}
import hashlib, json, pathlib, sys
a = sys.argv[1:]
inputs = [s for i, s in enumerate(a) if s not in ("-q", "--out", "--inputs-hash", "--restart", "--restart-check",
                                                  "--checkpoint-every-min")
          and (i == 0 or a[i - 1] not in ("--out", "--checkpoint-every-min"))]
h = hashlib.sha1(" ".join(inputs).encode()).hexdigest()[:16]
if "--inputs-hash" in a:
    print(h)
    sys.exit(0)
out = pathlib.Path(a[a.index("--out") + 1])
if "--restart-check" in a:  # a checkpoint reading "other build" is another build's, "corrupt" is refused
    c = out / "checkpoint.h5"
    if c.exists() and c.read_text() == "corrupt":
        sys.exit(2)
    print("restart" if c.exists() and c.read_text() != "other build" else "start")
    sys.exit(0)
v = [int(float(s.split("=")[1])) for s in a if s.startswith("projectile.velocity_m_s=")][0]
end = [float(s.split("=")[1]) for s in a if s.startswith("run.end_time_s=")][0]
restart = "--restart" in a
if restart and not (out / "checkpoint.h5").exists():
    sys.exit(2)
calls = out.parent / ("restarts.txt" if restart else "calls.txt")
calls.write_text((calls.read_text() if calls.exists() else "") + f"{{v}}\\n")
if "--checkpoint-every-min" in a:  # the clock's checkpoints asked for, logged beside the runs
    clock = out.parent / "clock.txt"
    clock.write_text((clock.read_text() if clock.exists() else "") + a[a.index("--checkpoint-every-min") + 1] + "\\n")
out.mkdir(parents=True, exist_ok=True)
(out / "config.json").write_text(json.dumps({{"hash": h}}))
if v in {fail_at}:
    (out / "diagnostic.json").write_text("{{}}")
    sys.exit(1)
if v in {kill_at}:
    sys.exit(137)
p = v >= {limit}
if v in {undecided} and end < {decide_time}:
    (out / "checkpoint.h5").write_text("")
    (out / "result.json").write_text(json.dumps({{"outcome": "undecided", "perforated": False,
        "residual_velocity_m_s": None, "final_velocity_m_s": 5.0, "end_time_s": end, "provenance": {{"config_hash": h}}}}))
    sys.exit(0)
(out / "result.json").write_text(json.dumps({{"outcome": "perforated" if p else "embedded", "perforated": p,
    "residual_velocity_m_s": 0.2 * v if p else None, "final_velocity_m_s": 0.2 * v if p else 0.0,
    "end_time_s": {decide_time} if v in {undecided} else 1e-3, "provenance": {{"config_hash": h}}}}))
"""


def bisect(tmp, low, high, fail_at=(), end_time="1e-3", kill_at=(), limit=237, undecided=(), decide_time=3e-3,
           max_end_time=None):
    macro = pathlib.Path(tmp) / "macro.py"
    macro.write_text(STAND_IN.format(python=sys.executable, limit=limit, fail_at=list(fail_at), kill_at=list(kill_at),
                                     undecided=list(undecided), decide_time=decide_time))
    macro.chmod(0o755)
    out = pathlib.Path(tmp) / "bl"
    extend = ["--max-end-time", max_end_time] if max_end_time else []
    done = subprocess.run([sys.executable, str(SCRIPT), "--macro", str(macro), "--config", "case.json",
                           "--low", str(low), "--high", str(high), "--width", "10", "--end-time", end_time, *extend,
                           "--out", str(out)], capture_output=True, text=True)
    calls = (out / "calls.txt").read_text().split() if (out / "calls.txt").exists() else []
    return done, out, [int(c) for c in calls]


def restarts(out):
    return [int(c) for c in (out / "restarts.txt").read_text().split()] if (out / "restarts.txt").exists() else []


def check(condition, message):
    if not condition:
        sys.exit("FAILED: " + message)


def main():
    with tempfile.TemporaryDirectory() as tmp:  # the limit inside the bracket
        done, out, calls = bisect(tmp, 200, 300)
        check(done.returncode == 0, done.stderr)
        s = json.loads((out / "ballistic_limit.json").read_text())
        check(s["highest_not_perforating_m_s"] < 237 <= s["lowest_perforating_m_s"], f"bracket {s}")
        check(s["bracket_width_m_s"] <= 10 and s["width_reached"], f"width {s['bracket_width_m_s']}")
        check(len(calls) == len(set(calls)), f"a velocity was run twice: {calls}")
        check(len(s["runs"]) == len(calls), "every run listed once")
        clock = (out / "clock.txt").read_text().split()
        check(clock == ["10"] * len(calls), f"each run's clock checkpoints (every 10 min): {clock}")
        # a resume with another end time finds runs made from other inputs: stops, runs nothing
        done, out, again = bisect(tmp, 200, 300, end_time="2e-3")
        check(done.returncode == 2 and "other inputs" in done.stderr and again == calls, done.stderr)
    with tempfile.TemporaryDirectory() as tmp:  # the bracket above the limit: widened downward
        done, out, calls = bisect(tmp, 260, 300)
        check(done.returncode == 0, done.stderr)
        s = json.loads((out / "ballistic_limit.json").read_text())
        check(s["highest_not_perforating_m_s"] < 237 <= s["lowest_perforating_m_s"], f"bracket {s}")
        check(len(calls) == len(set(calls)) and len(s["runs"]) == len(calls), f"runs {calls}")
        # resuming reads every result and runs nothing
        done, out, again = bisect(tmp, 260, 300)
        check(done.returncode == 0 and again == calls, f"resume reran: {again} after {calls}")
    with tempfile.TemporaryDirectory() as tmp:  # a failed run inside the bracket: recorded, bisected around
        done, out, calls = bisect(tmp, 200, 300, fail_at=[250])
        check(done.returncode == 0, done.stderr)
        s = json.loads((out / "ballistic_limit.json").read_text())
        check(s["failed_runs_m_s"] == [250] and s["highest_not_perforating_m_s"] < 237 <= s["lowest_perforating_m_s"]
              and s["width_reached"], f"bracket {s}")
        failed = [r for r in s["runs"] if r["outcome"] == "failed"]
        check(len(failed) == 1 and failed[0]["diagnostic"], f"failed runs {failed}")
        check("250" in (out / "ballistic_limit.md").read_text().split("Failed runs")[1], "the report names the failed run")
        done, out, again = bisect(tmp, 200, 300, fail_at=[250])  # a resume does not rerun the failed run
        check(done.returncode == 0 and again == calls, f"resume reran: {again} after {calls}")
    with tempfile.TemporaryDirectory() as tmp:  # three failures: the bracket reached, exit 1
        done, out, calls = bisect(tmp, 200, 300, fail_at=[250, 275, 225])
        s = json.loads((out / "ballistic_limit.json").read_text())
        check(done.returncode == 1 and not s["width_reached"] and s["bracket_width_m_s"] == 100, f"{done.returncode} {s}")
    with tempfile.TemporaryDirectory() as tmp:  # a failed end of the bracket stops the bisection, named
        done, out, calls = bisect(tmp, 200, 300, fail_at=[200])
        check(done.returncode == 1 and "200 m/s failed at an end" in done.stderr, done.stderr)
    with tempfile.TemporaryDirectory() as tmp:  # a diagnostic without config.json (an older run): rerun
        (pathlib.Path(tmp) / "bl" / "v250").mkdir(parents=True)
        (pathlib.Path(tmp) / "bl" / "v250" / "diagnostic.json").write_text("{}")
        done, out, calls = bisect(tmp, 200, 300)
        check(done.returncode == 0 and 250 in calls, f"{done.returncode} {calls} {done.stderr}")
    with tempfile.TemporaryDirectory() as tmp:  # a run killed without a diagnostic: stop, exit 3
        done, out, calls = bisect(tmp, 200, 300, kill_at=[250])
        check(done.returncode == 3 and "no diagnostic" in done.stderr, f"{done.returncode} {done.stderr}")
    with tempfile.TemporaryDirectory() as tmp:  # nothing perforates up to --max-velocity (3000): exit 1
        done, out, calls = bisect(tmp, 200, 300, limit=10**6)
        check(done.returncode == 1 and "nothing perforates up to" in done.stderr and max(calls) <= 3000,
              f"{done.returncode} {max(calls)} {done.stderr}")
    with tempfile.TemporaryDirectory() as tmp:  # runs undecided until 3 ms, carried on to 4 ms: decided
        done, out, calls = bisect(tmp, 200, 300, undecided=[232, 238], max_end_time="4e-3")
        check(done.returncode == 0, done.stderr)
        s = json.loads((out / "ballistic_limit.json").read_text())
        check(calls == [200, 300, 250, 225, 238, 232] and restarts(out) == [238, 238, 232, 232],
              f"runs {calls}, carried on {restarts(out)} (each 1 -> 2 -> 4 ms)")
        band = {r["velocity_m_s"]: r for r in s["runs"] if r["velocity_m_s"] in (232, 238)}
        check(band[238]["outcome"] == "perforated" and band[232]["outcome"] == "embedded"
              and all(r["carried_on"] and r["end_time_s"] == 3e-3 for r in band.values())
              and s["undecided_runs_m_s"] == [] and (s["highest_not_perforating_m_s"], s["lowest_perforating_m_s"])
              == (232, 238), f"decided by carrying on: {s}")
        check("Carried on past 1000 us because undecided there: [238, 232]" in (out / "ballistic_limit.md").read_text(),
              "the report says which runs were carried on")
        done, out, again = bisect(tmp, 200, 300, undecided=[232, 238], max_end_time="4e-3")  # resume: nothing run
        check(done.returncode == 0 and again == calls and restarts(out) == [238, 238, 232, 232],
              f"resume reran: {again}, {restarts(out)}")
    with tempfile.TemporaryDirectory() as tmp:  # carried on only to 2 ms: still undecided, counted as not perforating
        done, out, calls = bisect(tmp, 200, 300, undecided=[238], max_end_time="2e-3")
        s = json.loads((out / "ballistic_limit.json").read_text())
        check(done.returncode == 0 and restarts(out) == [238] and s["undecided_runs_m_s"] == [238]
              and s["highest_not_perforating_m_s"] >= 238
              and "Undecided at 2000 us (counted as not perforating): [238]" in (out / "ballistic_limit.md").read_text(),
              f"{done.returncode} {restarts(out)} {s}")
    with tempfile.TemporaryDirectory() as tmp:  # without --max-end-time no run is carried on
        done, out, calls = bisect(tmp, 200, 300, undecided=[238])
        check(done.returncode == 0 and restarts(out) == [], f"{restarts(out)}")
    print("ballistic_limit.py: bracket, widening, resume, reuse check, failures and carrying on as documented")


if __name__ == "__main__":
    main()
