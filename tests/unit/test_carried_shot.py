#!/usr/bin/env python3
"""pipelines/carried_shot.py (one shot of a sweep) against the stand-in for uhpc-macro of
test_ballistic_limit.py: a run undecided until 3 ms is carried on from its checkpoint 1 -> 2 -> 4 ms and
decided; run again, it launches nothing; a run carried on only to 2 ms stays undecided (exit 0, its
result says so) and is carried on further when the maximum is raised; the end time is taken from a --set
run.end_time_s (not overridden by the ladder) or from the case; given twice and different, refused (exit
2); a run made from other inputs refused (exit 2), untouched; a numerical failure exits 1 and is not
rerun; a killed run exits 3; a run killed while carried on goes on from its checkpoint on resume, one
without a checkpoint starts over; every run asks uhpc-macro for its clock's checkpoints (10 min unless
--checkpoint-every-min says otherwise, none at 0, a negative or infinite one refused), kept out of the
inputs' hash, and a fresh run killed after one goes on from it; a checkpoint another build wrote is not
gone on from (uhpc-macro --restart-check): the run or its carry-on starts over; a decided run launches
through --launch, a kept one does not."""
import json
import pathlib
import subprocess
import sys
import tempfile

from test_ballistic_limit import STAND_IN, check

SCRIPT = pathlib.Path(__file__).resolve().parents[2] / "pipelines" / "carried_shot.py"


def stand_in(tmp, undecided=(), fail_at=(), kill_at=()):
    macro = pathlib.Path(tmp) / "macro.py"
    macro.write_text(STAND_IN.format(python=sys.executable, limit=237, fail_at=list(fail_at), kill_at=list(kill_at),
                                     undecided=list(undecided), decide_time=3e-3))
    macro.chmod(0o755)
    case = pathlib.Path(tmp) / "case.json"
    case.write_text(json.dumps({"run": {"end_time_s": 1e-3}}))
    return macro, case


def shot(tmp, velocity, *extra, max_end_time=None, case=None):
    macro, own_case = stand_in(tmp, undecided=[238, 232], fail_at=[250], kill_at=[260])
    out = pathlib.Path(tmp) / "sweep" / f"v{velocity}"
    out.parent.mkdir(exist_ok=True)  # the stand-in logs its runs beside them
    args = [sys.executable, str(SCRIPT), "--macro", str(macro), "--config", str(case or own_case),
            "--velocity", str(velocity), *extra, "--out", str(out)]
    if max_end_time:
        args += ["--max-end-time", max_end_time]
    done = subprocess.run(args, capture_output=True, text=True)
    return done, out


def log(tmp, name):
    f = pathlib.Path(tmp) / "sweep" / name
    return [int(c) for c in f.read_text().split()] if f.exists() else []


def result(out):
    return json.loads((out / "result.json").read_text())


def main():
    with tempfile.TemporaryDirectory() as tmp:  # undecided until 3 ms: carried on 1 -> 2 -> 4 ms, decided
        done, out = shot(tmp, 238, max_end_time="4e-3")
        r = result(out)
        check(done.returncode == 0 and r["outcome"] == "perforated" and log(tmp, "calls.txt") == [238]
              and log(tmp, "restarts.txt") == [238, 238], f"{done.returncode} {r} {done.stderr}")
        check(log(tmp, "clock.txt") == [10, 10, 10], f"each run's clock checkpoints: {log(tmp, 'clock.txt')}")
        done, out = shot(tmp, 238, max_end_time="4e-3")  # run again: kept, nothing launched
        check(done.returncode == 0 and log(tmp, "calls.txt") == [238] and log(tmp, "restarts.txt") == [238, 238]
              and "carried_shot.py:" not in done.stdout, f"rerun launched: {done.stdout}")
        done, out = shot(tmp, 238, max_end_time="8e-3")  # a ladder that holds 4 ms: kept as well
        check(done.returncode == 0 and log(tmp, "restarts.txt") == [238, 238], f"{done.stderr}")
        done, out = shot(tmp, 238, "--end-time", "5e-4")  # other inputs (another end time): refused, untouched
        check(done.returncode == 2 and "other inputs" in done.stderr and result(out)["outcome"] == "perforated",
              f"{done.returncode} {done.stderr}")
    with tempfile.TemporaryDirectory() as tmp:  # only to 2 ms: undecided, then carried on when allowed
        done, out = shot(tmp, 232, max_end_time="2e-3")
        check(done.returncode == 0 and result(out)["outcome"] == "undecided" and result(out)["end_time_s"] == 2e-3
              and log(tmp, "restarts.txt") == [232], f"{done.returncode} {done.stderr}")
        done, out = shot(tmp, 232, max_end_time="4e-3")
        check(done.returncode == 0 and result(out)["outcome"] == "embedded" and log(tmp, "restarts.txt") == [232, 232]
              and log(tmp, "calls.txt") == [232], f"{done.returncode} {done.stderr}")
        done, out = shot(tmp, 232)  # no maximum: the end time's run only, which the 4 ms run is not
        check(done.returncode == 2 and "other inputs" in done.stderr, f"{done.returncode} {done.stderr}")
    with tempfile.TemporaryDirectory() as tmp:  # the end time from a --set: the ladder starts there
        done, out = shot(tmp, 232, "--set", "run.end_time_s=2e-3", max_end_time="4e-3")
        check(done.returncode == 0 and result(out)["outcome"] == "embedded" and log(tmp, "restarts.txt") == [232],
              f"2 -> 4 ms: {done.returncode} {log(tmp, 'restarts.txt')} {done.stderr}")
        done, out = shot(tmp, 232, "--set", "run.end_time_s=2e-3", "--end-time", "1e-3")
        check(done.returncode == 2 and "given twice" in done.stderr, f"{done.returncode} {done.stderr}")
        done, out = shot(tmp, 232, "--end-time", "1e-3", "--max-end-time", "5e-4")
        check(done.returncode == 2 and "--max-end-time" in done.stderr, f"{done.returncode} {done.stderr}")
        done, out = shot(tmp, 300, case=pathlib.Path(tmp) / "missing.json")
        check(done.returncode == 2 and "missing.json" in done.stderr and "run.end_time_s" in done.stderr,
              f"{done.returncode} {done.stderr}")
    with tempfile.TemporaryDirectory() as tmp:  # failures
        done, out = shot(tmp, 250)
        check(done.returncode == 1 and "failed" in done.stderr, f"{done.returncode} {done.stderr}")
        done, out = shot(tmp, 250)  # not rerun
        check(done.returncode == 1 and log(tmp, "calls.txt") == [250] and "failed before" in done.stderr,
              f"{done.returncode} {log(tmp, 'calls.txt')} {done.stderr}")
        done, out = shot(tmp, 260)
        check(done.returncode == 3 and "no diagnostic" in done.stderr, f"{done.returncode} {done.stderr}")
    with tempfile.TemporaryDirectory() as tmp:  # killed while carried on: on again from its checkpoint
        done, out = shot(tmp, 238, max_end_time="2e-3")  # undecided at 2 ms, its checkpoint kept
        check(done.returncode == 0 and result(out)["outcome"] == "undecided", f"{done.returncode} {done.stderr}")
        # The carry-on to 4 ms killed: uhpc-macro wrote its config.json and removed result.json at its start.
        sys.path.insert(0, str(SCRIPT.parent))
        from carried_shot import Shot
        to_4ms = Shot("test", str(pathlib.Path(tmp) / "macro.py"), "", str(pathlib.Path(tmp) / "case.json"), None, [],
                      1e-3, 4e-3)
        (out / "result.json").unlink()
        (out / "config.json").write_text(json.dumps({"hash": to_4ms.input_hashes(238, 4e-3)[0]}))
        done, out = shot(tmp, 238, max_end_time="4e-3")
        check(done.returncode == 0 and result(out)["outcome"] == "perforated" and log(tmp, "calls.txt") == [238]
              and log(tmp, "restarts.txt") == [238, 238], f"{done.returncode} {log(tmp, 'calls.txt')} "
              f"{log(tmp, 'restarts.txt')} {done.stderr}")
        # A checkpoint another build wrote (after a rebuild) cannot be gone on from: the run starts over from
        # t = 0 and is carried along the ladder again (1 -> 2 -> 4 ms).
        (out / "result.json").unlink()
        (out / "checkpoint.h5").write_text("other build")
        done, out = shot(tmp, 238, max_end_time="4e-3")
        check(done.returncode == 0 and result(out)["outcome"] == "perforated" and log(tmp, "calls.txt") == [238, 238]
              and log(tmp, "restarts.txt") == [238] * 4 and "another build" in done.stdout,
              f"{done.returncode} {log(tmp, 'calls.txt')} {log(tmp, 'restarts.txt')} {done.stdout} {done.stderr}")
        # A corrupt checkpoint (uhpc-macro --restart-check exits 2) stops the shot, launching nothing.
        (out / "result.json").unlink()
        (out / "checkpoint.h5").write_text("corrupt")
        done, out = shot(tmp, 238, max_end_time="4e-3")
        check(done.returncode == 2 and "cannot be gone on from" in done.stderr and log(tmp, "calls.txt") == [238, 238]
              and log(tmp, "restarts.txt") == [238] * 4, f"{done.returncode} {done.stderr}")
        # Without its checkpoint (killed before its first one) it starts over.
        (out / "checkpoint.h5").unlink()
        done, out = shot(tmp, 238, max_end_time="4e-3")
        check(done.returncode == 0 and log(tmp, "calls.txt") == [238, 238, 238], f"{log(tmp, 'calls.txt')} {done.stderr}")
    with tempfile.TemporaryDirectory() as tmp:  # a fresh run killed after its clock's checkpoint: on from it
        macro, case = stand_in(tmp)
        sys.path.insert(0, str(SCRIPT.parent))
        from carried_shot import Shot
        first = Shot("test", str(macro), "", str(case), None, [], 1e-3, 1e-3)
        out = pathlib.Path(tmp) / "sweep" / "v300"
        out.mkdir(parents=True)
        (out / "config.json").write_text(json.dumps({"hash": first.input_hashes(300, 1e-3)[0]}))
        (out / "checkpoint.h5").write_text("")
        done, out = shot(tmp, 300, "--checkpoint-every-min", "2.5")
        check(done.returncode == 0 and result(out)["outcome"] == "perforated" and log(tmp, "calls.txt") == []
              and log(tmp, "restarts.txt") == [300], f"{done.returncode} {log(tmp, 'calls.txt')} {done.stderr}")
        check((pathlib.Path(tmp) / "sweep" / "clock.txt").read_text().split() == ["2.5"], "--checkpoint-every-min 2.5")
        done, out = shot(tmp, 301, "--checkpoint-every-min", "0")  # 0: no clock asked of uhpc-macro
        check(done.returncode == 0 and log(tmp, "calls.txt") == [301]
              and (pathlib.Path(tmp) / "sweep" / "clock.txt").read_text().split() == ["2.5"], f"{done.stderr}")
        for bad in ("-1", "inf"):
            done, out = shot(tmp, 302, "--checkpoint-every-min", bad)
            check(done.returncode == 2 and "--checkpoint-every-min" in done.stderr, f"{bad}: {done.returncode} {done.stderr}")
        # An undecided run's checkpoint written by another build: its carry-on starts over at the next end time.
        (pathlib.Path(tmp) / "sweep" / "calls.txt").unlink()
        done, out = shot(tmp, 232, max_end_time="2e-3")  # undecided at 1 ms, carried on to 2 ms: undecided
        check(done.returncode == 0 and result(out)["outcome"] == "undecided" and log(tmp, "calls.txt") == [232],
              f"{done.returncode} {done.stderr}")
        (out / "checkpoint.h5").write_text("other build")
        done, out = shot(tmp, 232, max_end_time="4e-3")
        check(done.returncode == 0 and result(out)["outcome"] == "embedded" and log(tmp, "calls.txt") == [232, 232]
              and "another build" in done.stdout, f"{done.returncode} {log(tmp, 'calls.txt')} {done.stdout} {done.stderr}")
        # The same with its checkpoint missing: said so, and started over.
        done, out = shot(tmp, 232, max_end_time="2e-3")  # a 2 ms ladder: the 4 ms run is another's
        check(done.returncode == 2, f"{done.returncode} {done.stderr}")
        (pathlib.Path(tmp) / "sweep" / "v232").rename(pathlib.Path(tmp) / "sweep" / "v232_done")
        done, out = shot(tmp, 232, max_end_time="2e-3")  # undecided at 2 ms, its checkpoint kept
        (out / "checkpoint.h5").unlink()
        done, out = shot(tmp, 232, max_end_time="4e-3")
        check(done.returncode == 0 and result(out)["outcome"] == "embedded" and "is missing" in done.stdout,
              f"{done.returncode} {done.stdout} {done.stderr}")
    with tempfile.TemporaryDirectory() as tmp:  # through a launcher: a missing run launched, a kept one not
        launcher = pathlib.Path(tmp) / "launcher.sh"
        launcher.write_text(f"#!/bin/sh\necho \"$*\" >> {tmp}/launches.txt\nexec \"$@\"\n")
        launcher.chmod(0o755)
        for _ in range(2):
            done, out = shot(tmp, 300, "--launch", str(launcher))
        launches = (pathlib.Path(tmp) / "launches.txt").read_text().splitlines()
        check(done.returncode == 0 and len(launches) == 1 and "projectile.velocity_m_s=300" in launches[0],
              f"{launches}")
    print("carried_shot.py: carrying on, reuse, the end time's sources, failures and the launcher as documented")


if __name__ == "__main__":
    main()
