#!/usr/bin/env python3
"""uhpc-macro over N ranks (mpirun -np N) against the same shot in one process (issue 49 item 3).

The shot: the coarse disc's case on a small disc (72 mm across, 12 mm thick, about 1 000 particles), the
sphere at 817 m/s through it in about 200 steps, with about 20 halo rebuilds and particles changing ranks;
once with the shipped lazy RK rows (solver.shape_reuse_tolerance 3e-4), once with every row rebuilt each
step (0).

Checks:
  - the residual velocity, the outcome, the sphere, the steps, the panel's damage and every particle field
    in fields.h5 and sphere.h5 are the one-process run's, bit for bit;
  - the energy and momentum books in result.json and history.csv agree to 1e-10 of the energy put in and
    of the initial momentum (each rank sums its own particles, then the ranks' sums are added);
  - result.json records the rank count;
  - checkpoints: the shot stopped undecided at 20 us and carried on with --restart, over N ranks and then
    another rank count (one process after 2 ranks), equals the same in one process;
  - the options beyond the shipped case, each once: the full field set with the penalty contact, and the
    midpoint strain configuration; the same checks.

usage: check_mpi_shot.py --macro BIN --mpirun "MPIRUN --oversubscribe -np" --ranks N --out DIR
"""
import argparse
import csv
import json
import math
import pathlib
import shutil
import subprocess

import h5py
import numpy as np

from make_target_case import ENV, Checks

SMALL_DISC = ["target.radius_m=0.036", "target.thickness_m=0.012", "target.h_axis_m=0.003", "target.h_rim_m=0.0045",
              "target.core_radius_m=0.012", "support.rim_width_m=0.006", "run.end_time_s=4e-5"]
EXACT = ["outcome", "perforated", "residual_velocity_m_s", "final_velocity_m_s", "final_sphere_position_m",
         "outcome_time_s", "end_time_s", "steps", "step_repeats", "particle_count", "fragment_particles", "panel",
         "beyond_domain", "field_outputs"]
BOOKS = 1e-10


def run(command, **kw):
    return subprocess.run(command, env=ENV, capture_output=True, text=True, **kw)


def datasets(path):
    found = {}
    with h5py.File(path, "r") as f:
        f.visititems(lambda name, obj: found.__setitem__(name, obj[()]) if isinstance(obj, h5py.Dataset) else None)
    return found


def history(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(line for line in f if not line.startswith("#")))
    return rows[0], np.array(rows[1:], dtype=float)


ap = argparse.ArgumentParser()
ap.add_argument("--macro", required=True)
ap.add_argument("--mpirun", required=True)
ap.add_argument("--ranks", type=int, required=True)
ap.add_argument("--case", required=True)
ap.add_argument("--out", required=True)
a = ap.parse_args()
out = pathlib.Path(a.out)
shutil.rmtree(out, ignore_errors=True)
mpirun = a.mpirun.split() + [str(a.ranks)]
check = Checks()


def macro(ranks, sets, out_dir, *flags):
    """uhpc-macro with --set `sets`, over `ranks` ranks (1: no launcher), into out_dir."""
    launcher = [] if ranks == 1 else a.mpirun.split() + [str(ranks)]
    sets = [x for s in sets for x in ("--set", s)]
    return run([*launcher, a.macro, "--config", a.case, *sets, "-q", "--out", str(out_dir), *flags])


def succeeded(name, what, done):
    check(done.returncode == 0, f"{name}: {what} exits 0" + ("" if done.returncode == 0 else f": {done.stderr.strip()[-500:]}"))
    return done.returncode == 0


def compare(name, extra):
    """The shot with --set `extra` in one process and over the ranks, in out/name/{one,many}."""
    here = out / name
    one = macro(1, SMALL_DISC + extra, here / "one")
    many = macro(a.ranks, SMALL_DISC + extra, here / "many")
    if succeeded(name, "one process", one) & succeeded(name, f"{a.ranks} ranks", many):
        return same_shot(name, here / "one", here / "many", a.ranks)


def same_shot(name, one_dir, many_dir, ranks):
    """The outputs of many_dir (a run over `ranks` ranks) against one_dir's (one process)."""
    r1 = json.loads((one_dir / "result.json").read_text())
    rn = json.loads((many_dir / "result.json").read_text())
    check(r1["outcome"] == "perforated", f"{name}: the shot perforates ({r1['outcome']})")
    differ = [key for key in EXACT if r1[key] != rn[key]]
    check(not differ, f"{name}: result.json {', '.join(EXACT[:3])} ... the same ({differ}); residual velocity "
          f"{rn['residual_velocity_m_s']!r} ({r1['residual_velocity_m_s']!r} in one process)")
    check(rn.get("ranks") == ranks and r1.get("ranks") == 1, f"{name}: result.json records the ranks ({rn.get('ranks')})")
    put_in = r1["energy"]["initial_kinetic_J"] + abs(r1["energy"]["external_work_J"])
    worst = max(abs(rn["energy"][k] - r1["energy"][k]) / put_in for k in r1["energy"] if "error" not in k)
    check(worst <= BOOKS, f"{name}: energy books within {BOOKS:g} of the energy put in ({worst:.2e})")
    p0 = math.hypot(*r1["momentum"]["initial_N_s"])
    worst = max(abs(x - y) / p0 for k in ("final_N_s", "external_impulse_N_s")
                for x, y in zip(rn["momentum"][k], r1["momentum"][k]))
    check(worst <= BOOKS, f"{name}: momentum books within {BOOKS:g} of the initial momentum ({worst:.2e})")
    check(abs(rn["momentum"]["worst_balance_error"] - r1["momentum"]["worst_balance_error"]) <= BOOKS,
          f"{name}: the momentum balance is unchanged")
    for file in ("fields.h5", "sphere.h5"):
        d1, dn = datasets(one_dir / file), datasets(many_dir / file)
        differ = [k for k in d1 if k not in dn or not np.array_equal(d1[k], dn[k])]
        check(len(d1) > 0 and d1.keys() == dn.keys() and not differ,
              f"{name}: {file}: {len(d1)} datasets, the same bits ({len(differ)} differ: {differ[:3]})")
    h1, v1 = history(one_dir / "history.csv")
    hn, vn = history(many_dir / "history.csv")
    check(h1 == hn and v1.shape == vn.shape, f"{name}: history.csv: the same columns and {len(v1)} rows")
    if h1 == hn and v1.shape == vn.shape:
        books = [i for i, c in enumerate(h1) if c.endswith("_J") or c.startswith("momentum")]
        exact = [i for i in range(len(h1)) if i not in books]
        check(np.array_equal(v1[:, exact], vn[:, exact]),
              f"{name}: history.csv: the time, step, sphere and contact columns the same text ({len(exact)} columns)")
        # The books are printed to 10 digits: a last digit may round the other way.
        scale = np.array([p0 if h1[i].startswith("momentum") else put_in for i in books])
        allowed = BOOKS * scale + 1e-9 * np.maximum(np.abs(v1[:, books]), np.abs(vn[:, books]))
        over = int(np.sum(np.abs(vn[:, books] - v1[:, books]) > allowed))
        check(over == 0, f"{name}: history.csv: {len(books)} book columns within {BOOKS:g} and the printed digits "
              f"({over} over)")
    return r1


lazy = compare("lazy_rows", [])
if lazy:
    check(lazy["shape_rows_kept_fraction"] > 0.2, f"lazy rows kept rows ({lazy['shape_rows_kept_fraction']:.2f})")
compare("rows_rebuilt", ["solver.shape_reuse_tolerance=0"])

# Checkpoints: the shot stopped undecided at 20 us (its checkpoint written at the end, and the rows dropped
# every 50 steps) and carried on to 40 us with --restart, the second half at another rank count.
legs = SMALL_DISC + ["run.checkpoint_interval_steps=50"]
later = 1 if a.ranks == 2 else a.ranks - 1
name = f"checkpoint ({a.ranks} then {later} rank{'s' if later > 1 else ''})"
ok = True
for ranks, where in ((1, out / "restart" / "one"), (a.ranks, out / "restart" / "many")):
    ok &= succeeded(name, f"{ranks} rank(s) to 20 us", macro(ranks, legs + ["run.end_time_s=2e-5"], where))
    ok &= (where / "checkpoint.h5").is_file()
    again = 1 if ranks == 1 else later
    ok &= succeeded(name, f"{again} rank(s) on to 40 us", macro(again, legs + ["run.end_time_s=4e-5"], where, "--restart"))
check(ok, f"{name}: both halves run, the first leaves its checkpoint")
if ok:
    same_shot(name, out / "restart" / "one", out / "restart" / "many", later)

# The options beyond the shipped case, each run once: the full field set (the fragment flags gathered from
# the ranks) with the penalty contact (its sums over every rank's pairs in the order of their ids), and the
# midpoint strain configuration (the stresses updated between two row builds a step).
compare("penalty_full_fields", ["run.fields=\"full\"", "projectile.contact.model=\"penalty\""])
compare("midpoint", ["solver.strain_configuration=\"midpoint\""])
check.exit()
