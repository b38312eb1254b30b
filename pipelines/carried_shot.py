#!/usr/bin/env python3
"""One shot decided by the sphere rather than by the end time: uhpc-macro at one impact velocity, kept if it
was already made from the same inputs, and carried on from its checkpoint while it is undecided.

usage: carried_shot.py --macro UHPC_MACRO --config CASE.json [--sdel SDEL.json] [--set key=value ...]
                       --velocity V [--end-time T] [--max-end-time T] [--launch PREFIX]
                       [--checkpoint-every-min M] --out DIR

The run goes to DIR with run.end_time_s = T (--end-time, else a --set run.end_time_s=T among the sets,
else the case's own run.end_time_s). A run still undecided there (the sphere neither through, nor stopped,
nor thrown back) is carried on from its checkpoint (uhpc-macro --restart) to twice that end time, and so
on up to --max-end-time (default: the end time, no extension). A run whose result.json exists is kept if
it was made from the inputs this command would give it at one end time of that ladder (its
provenance.config_hash against `uhpc-macro ... --inputs-hash`, either line), carried on if it is still
undecided below --max-end-time, and refused otherwise (exit 2, naming it: another case, SDEL, --set or
end time). Each run writes DIR/checkpoint.h5 every --checkpoint-every-min minutes of wall time (default
10; 0: none), which is not an input of the run (uhpc-macro --checkpoint-every-min). A run killed before
its end time with a checkpoint to go on from (DIR/config.json of these inputs at an end time of the
ladder, and DIR/checkpoint.h5: one the clock wrote, or the last state it was carried on from) goes on from
that checkpoint, so at most the minutes since it are lost. A checkpoint that another build of uhpc-macro
wrote, or a missing one (uhpc-macro --restart-check says "start"), cannot be gone on from: that run, or
that carry-on, starts again from t = 0. A run resumed from a clock's checkpoint rebuilds its lazy shape
rows where the killed one had kept them: it differs from an unstopped run within
solver.shape_reuse_tolerance. A run that failed numerically before (DIR/diagnostic.json and
DIR/config.json of the same inputs) is not run again (exit 1; remove DIR to run it again).
--launch puts a launcher before each run of uhpc-macro, split as a shell would (e.g. "srun -N1 -n1 -c2
--exclusive"); a kept run launches nothing.
Exit codes: 0 the run is in DIR (decided, or undecided at --max-end-time: its result.json says which);
1 it failed numerically (its diagnostic.json beside it); 2 bad input (the arguments, the case, uhpc-macro's
exit 2, a run made from other inputs); 3 a run that neither finished nor failed numerically (killed, or
its launcher failed).

The sweep and thickness study of pipelines/Makefile run each shot through this command; ballistic_limit.py
runs each of its bisection's shots through the same Shot.
"""
import argparse
import json
import math
import pathlib
import shlex
import subprocess
import sys

END_TIME_KEY = "run.end_time_s"


class Shot:
    """How a study runs its shots: the program, its launcher, the case, the SDEL, the --set overrides
    (without the end time) and the ladder of end times an undecided run is carried along."""

    def __init__(self, prog, macro, launch, config, sdel, sets, end_time, max_end_time, checkpoint_every_min=0.0):
        self.prog, self.macro, self.launch, self.config, self.sdel = prog, macro, launch, config, sdel
        self.sets, self.end_time, self.max_end_time = sets, end_time, max_end_time
        self.checkpoint_every_min = checkpoint_every_min

    def end_times(self):
        """The end times a run may be carried to: the end time, doubled up to the maximum."""
        times = [self.end_time]
        while times[-1] < self.max_end_time:
            times.append(min(2.0 * times[-1], self.max_end_time))
        return times

    def command(self, velocity, end_time):
        """uhpc-macro at one velocity and end time, without the launcher and the output options."""
        cmd = [self.macro, "--config", self.config, "--set", f"projectile.velocity_m_s={velocity}",
               "--set", f"{END_TIME_KEY}={end_time}"]
        if self.sdel:
            cmd += ["--sdel", self.sdel]
        for s in self.sets:
            cmd += ["--set", s]
        return cmd

    def input_hashes(self, velocity, end_time):
        """The hashes of the inputs of the run at one velocity and end time: this scheme's, then (uhpc-macro
        since 2026-12-06) the former one's, notes included."""
        done = subprocess.run(self.command(velocity, end_time) + ["--inputs-hash"], capture_output=True, text=True)
        if done.returncode != 0:
            sys.exit(f"{self.prog}: uhpc-macro --inputs-hash failed at {velocity} m/s: {done.stderr.strip()}")
        return done.stdout.split()

    def check_reusable(self, velocity, out, found):
        """Stops (exit 2) unless the run in `out` (its inputs' hash `found`) was made from the inputs this
        study would give it, at one of its end times."""
        expected = []
        for end_time in self.end_times():
            hashes = self.input_hashes(velocity, end_time)
            expected.append(hashes[0] if hashes else "")
            if found in hashes:
                return
        print(f"{self.prog}: the run in {out} was made from other inputs (hash {found}, this study's "
              f"{', '.join(expected)}: another case, SDEL, --set or end time); use another --out or remove it",
              file=sys.stderr)
        sys.exit(2)

    def resumable(self, velocity, out, end_time):
        """uhpc-macro --restart-check: True when the run in `out` can go on from its checkpoint to end_time,
        False when only a run from t = 0 is left (another build of uhpc-macro wrote the checkpoint, e.g. after
        a rebuild); stops the study (exit 2) for a checkpoint of other inputs or a corrupt one."""
        done = subprocess.run(self.command(velocity, end_time) + ["--out", str(out), "--restart-check"],
                              capture_output=True, text=True)
        if done.returncode != 0:
            print(f"{self.prog}: the checkpoint in {out} cannot be gone on from: {done.stderr.strip()}", file=sys.stderr)
            sys.exit(2)
        if done.stdout.strip() == "restart":
            return True
        why = "was written by another build of uhpc-macro" if (out / "checkpoint.h5").exists() else "is missing"
        print(f"{self.prog}: {out / 'checkpoint.h5'} {why}: the run starts again from t = 0", flush=True)
        return False

    def interrupted(self, velocity, out):
        """The end time of a run in `out` that was stopped before it (no result.json) but can go on from its
        checkpoint: an undecided run being carried on when it was killed (its config.json, written at its
        start, of these inputs at one end time of the ladder, and a checkpoint.h5, which uhpc-macro writes
        at an end time, every --checkpoint-every-min minutes, or at run.checkpoint_interval_steps, of this
        build). None otherwise: a run killed before its first checkpoint leaves none and starts again, and so
        does one whose checkpoint another build wrote."""
        config, checkpoint = out / "config.json", out / "checkpoint.h5"
        if not (config.is_file() and checkpoint.is_file()):
            return None
        found = json.loads(config.read_text()).get("hash")
        end_time = next((t for t in self.end_times() if found in self.input_hashes(velocity, t)), None)
        return end_time if end_time is not None and self.resumable(velocity, out, end_time) else None

    def launch_run(self, velocity, out, end_time, restart):
        """Runs uhpc-macro (a fresh run, or the undecided one in `out` carried on to end_time): None when it
        finished, else the failed run's exit code (1, with its diagnostic); stops the study on any other
        end."""
        cmd = shlex.split(self.launch) + self.command(velocity, end_time) + ["-q", "--out", str(out)]
        if self.checkpoint_every_min > 0:  # not an input of the run: kept out of command(), so out of its hash
            cmd += ["--checkpoint-every-min", f"{self.checkpoint_every_min:g}"]
        if restart:
            cmd.append("--restart")
        print(f"{self.prog}:", " ".join(cmd), flush=True)
        done = subprocess.run(cmd)
        if done.returncode == 2:  # bad input: every other run would fail the same way
            print(f"{self.prog}: uhpc-macro refused the input at {velocity} m/s (exit 2, above)", file=sys.stderr)
            sys.exit(2)
        if done.returncode == 1 and (out / "diagnostic.json").is_file():
            print(f"{self.prog}: the run at {velocity} m/s failed (exit 1); see {out}", file=sys.stderr, flush=True)
            return done.returncode
        if done.returncode != 0:
            print(f"{self.prog}: the run at {velocity} m/s ended with exit {done.returncode} and no diagnostic "
                  f"(killed, or its launcher failed); see {out}", file=sys.stderr)
            sys.exit(3)
        return None

    def decide(self, velocity, out):
        """The run at one velocity in `out`, made, kept or carried on: (its result.json, None), or (None,
        the exit code) for a run that failed numerically (None as the code: it failed before, not rerun)."""
        result, diagnostic = out / "result.json", out / "diagnostic.json"
        if result.is_file():
            self.check_reusable(velocity, out, json.loads(result.read_text()).get("provenance", {}).get("config_hash"))
        elif diagnostic.is_file() and (out / "config.json").is_file():  # failed before: not rerun if the same inputs
            self.check_reusable(velocity, out, json.loads((out / "config.json").read_text()).get("hash"))
            return None, None
        else:
            # A run killed while it was carried on goes on from its checkpoint, not from t = 0.
            resume = self.interrupted(velocity, out)
            failure = self.launch_run(velocity, out, resume or self.end_time, restart=resume is not None)
            if failure is not None:
                return None, failure
        r = json.loads(result.read_text())
        # Undecided: carried on, each time to the next end time of the ladder past the one it reached.
        while r.get("outcome") == "undecided" and r["end_time_s"] < self.max_end_time * (1.0 - 1e-9):
            end_time = next(t for t in self.end_times() if t > r["end_time_s"] * (1.0 + 1e-9))
            failure = self.launch_run(velocity, out, end_time, restart=self.resumable(velocity, out, end_time))
            if failure is not None:
                return None, failure
            r = json.loads(result.read_text())
        return r, None


def end_time_and_sets(prog, sets, end_time, config):
    """The ladder's first end time and the sets without it: --end-time, else the last --set
    run.end_time_s, else the case's run.end_time_s; both given and different is refused (exit 2), since
    the set would otherwise override the ladder's end times."""
    given = [s.split("=", 1)[1] for s in sets if s.split("=", 1)[0].strip() == END_TIME_KEY]
    rest = [s for s in sets if s.split("=", 1)[0].strip() != END_TIME_KEY]
    try:
        from_sets = float(given[-1]) if given else None
    except ValueError:
        sys.exit(f"{prog}: --set {END_TIME_KEY}={given[-1]}: not a number")
    if end_time is not None and from_sets is not None and from_sets != end_time:
        print(f"{prog}: the end time is given twice, --end-time {end_time:g} and --set {END_TIME_KEY}={given[-1]}: "
              f"give it once", file=sys.stderr)
        sys.exit(2)
    if end_time is None:
        end_time = from_sets
    if end_time is None:
        try:
            end_time = float(json.loads(pathlib.Path(config).read_text())["run"]["end_time_s"])
        except (OSError, ValueError, KeyError, TypeError) as e:
            print(f"{prog}: {config}: no run.end_time_s to start from ({type(e).__name__}: {e}); give --end-time",
                  file=sys.stderr)
            sys.exit(2)
    return end_time, rest


def add_shot_arguments(ap):
    """The arguments that say how a study runs its shots (a Shot's, but the end times)."""
    ap.add_argument("--macro", required=True)
    ap.add_argument("--launch", default="", help="launcher prefix of each run, e.g. \"srun -N1 -n1 -c2 --exclusive\"")
    ap.add_argument("--config", required=True)
    ap.add_argument("--sdel")
    ap.add_argument("--set", action="append", default=[])
    ap.add_argument("--checkpoint-every-min", type=float, default=10.0,
                    help="each run writes its checkpoint every M minutes of wall time, so that a killed run goes on "
                         "from it (default 10; 0: none)")


def main():
    prog = "carried_shot.py"
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_shot_arguments(ap)
    ap.add_argument("--velocity", required=True, help="m/s, passed to uhpc-macro as written")
    ap.add_argument("--end-time", type=float)
    ap.add_argument("--max-end-time", type=float, help="an undecided run is carried on up to it (default: the end time)")
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    end_time, sets = end_time_and_sets(prog, args.set, args.end_time, args.config)
    max_end_time = end_time if args.max_end_time is None else args.max_end_time
    try:
        velocity_ok = float(args.velocity) > 0
    except ValueError:
        velocity_ok = False
    if not (0 < end_time <= max_end_time) or not velocity_ok or not 0 <= args.checkpoint_every_min < math.inf:
        print(f"{prog}: need 0 < end time ({end_time:g}) <= --max-end-time ({max_end_time:g}), --velocity > 0 "
              f"({args.velocity}) and --checkpoint-every-min >= 0 ({args.checkpoint_every_min:g})",
              file=sys.stderr)
        sys.exit(2)
    shot = Shot(prog, args.macro, args.launch, args.config, args.sdel, sets, end_time, max_end_time,
                args.checkpoint_every_min)
    r, failure = shot.decide(args.velocity, pathlib.Path(args.out))
    if r is None:
        if failure is None:
            print(f"{prog}: the run in {args.out} failed before with the same inputs (its diagnostic.json); "
                  f"remove it to run it again", file=sys.stderr)
        sys.exit(1)
    sys.exit(0)


if __name__ == "__main__":
    main()
