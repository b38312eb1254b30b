#!/usr/bin/env python3
"""Corrupted files the programs read back: never a crash, never a silently different answer.

usage: fuzz_files.py --source SRC --build BUILD [--jobs 2] [--mutants 40] [--timeout 60]

The files (docs/architecture.md, section 2.7), each made here by the programs themselves:
  checkpoint  uhpc-macro's checkpoint.h5 of the elastic block, stopped undecided at 15 us (the sphere in
              contact) and restarted with --restart to 17 us;
  cell        a finished ensemble cell (curves.h5, summary.json) reloaded by `uhpc-micro ensemble
              --assemble-only` (the archived cells cell_00 of 3.0 and 4.5 mm, rewritten by this version;
              the mutants hit size_3.0mm/cell_00);
  ensemble    the ensemble.h5 that assembly writes, read by uhpc-calibrate (a few mutants: a fit takes
              seconds).
Mutants, deterministic (a fixed seed): single bytes flipped and 8-byte runs overwritten with ff at
random offsets (half of them in the first 4 KiB, where most metadata sits). Each mutant must end with
exit 2 and one line "error: ..." naming the mutated file, or exit 0 with the very answer of the intact
file (the checkpoint's result.json, history.csv and every value of fields.h5, the cell's assembled ensemble.h5, the fit's
sdel.json). A signal, a timeout, "internal error" or another answer fails the test.

Plus the corruption that crashed libhdf5 1.10.8 (SIGSEGV in H5Lexists): the v1 group B-tree address of
the root group's symbol-table message (and, separately, of the superblock's cached copy) set to ff x 8,
in files of the format before HDF5 1.8, which have no checksums: the shipped ensemble_4x10.h5
(uhpc-calibrate --ensemble), a cell's curves.h5 of that format (tests/regression/micro_former_hash_cell, the
archive's cell_00 as written before the archive carried checksums; uhpc-micro ensemble resuming over it: the cell
is reported and not reloaded, exit 2 under --assemble-only) and a checkpoint copied into that format
(uhpc-macro --restart). Each must be exit 2 naming the file.
"""
import argparse
import concurrent.futures
import json
import pathlib
import random
import shutil
import struct
import subprocess
import sys
import tarfile
import tempfile

import h5py
import numpy as np

MACRO_CASE = ["--set", "run.checkpoint_interval_steps=5", "-q"]
MICRO_PART = ["--set", "cell_sizes_m=[0.003,0.0045]", "--set", "realizations=1", "-j", "1"]


def run(cmd, timeout):
    try:
        return subprocess.run(cmd, capture_output=True, text=True, errors="replace", timeout=timeout)
    except subprocess.TimeoutExpired:
        return None


def error_lines(done):
    # The programs' log lines ("[hh:mm:ss] program warn: ...") may precede the one error line.
    return [line for line in done.stderr.strip().splitlines() if line and not line.startswith("[")]


def verdict(name, done, named, same_answer, cmd):
    """None when the mutant was refused by name (exit 2) or changed nothing; else what went wrong."""
    if done is None:
        return f"{name}: timed out: {' '.join(cmd)[:300]}"
    if done.returncode < 0:
        return f"{name}: CRASH, killed by signal {-done.returncode}: {' '.join(cmd)[:300]}"
    err = error_lines(done)
    if done.returncode == 0:
        return None if same_answer() else f"{name}: SILENTLY ACCEPTED: exit 0 with another answer"
    if done.returncode == 2 and len(err) == 1 and err[0].startswith("error: ") and named in err[0] + done.stderr:
        return None
    return f"{name}: exit {done.returncode}, stderr {err[:3]}: {' '.join(cmd)[:300]}"


def ensemble_values(path):
    """Every dataset of an HDF5 file (an ensemble.h5, a fields.h5), as bytes."""
    with h5py.File(path, "r") as f:
        names = []
        f.visititems(lambda n, o: names.append(n) if isinstance(o, h5py.Dataset) else None)
        return {n: np.asarray(f[n]).tobytes() for n in names}


def fit_answer(path):
    """A fit's answer: the constants and what they apply to (the rest of sdel.json names the input file
    and dates)."""
    j = json.loads(path.read_text())
    return [j[k] for k in ("constants", "l_mac_m", "strain_measure", "cell_sizes_m")]


def mutants(data, count, rng):
    """(label, bytes) of `count` deterministic corruptions of `data`."""
    out = []
    for k in range(count):
        span = min(len(data), 4096) if k % 2 == 0 else len(data)
        at = rng.randrange(span)
        b = bytearray(data)
        if k % 4 < 2:
            b[at] ^= rng.randrange(1, 256)
            out.append((f"byte {at} flipped", bytes(b)))
        else:
            b[at:at + 8] = b"\xff" * min(8, len(b) - at)
            out.append((f"8 bytes at {at} set to ff", bytes(b)))
    return out


def btree_addresses(data):
    """Offsets of the root group's v1 B-tree address in a superblock-v0 file: in the root object header's
    symbol-table message, and in the superblock's cached copy (the scratch pad of the root entry). The
    message holds the same two addresses (B-tree, local heap) as the cache: it is found by them, wherever
    the object header put it (a continuation block, after attributes)."""
    assert data[:8] == b"\x89HDF\r\n\x1a\n" and data[8] == 0, "not a superblock-v0 file"
    cached = 56 + 24  # the root entry follows the signature, versions, sizes, K values, flags, 4 addresses
    assert struct.unpack_from("<I", data, 56 + 16)[0] == 1, "the root entry caches no symbol table"
    message = data.find(data[cached:cached + 16], cached + 16)
    assert message > 0, "no symbol-table message with the cached addresses"
    return message, cached


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--source", required=True, type=pathlib.Path)
    ap.add_argument("--build", required=True, type=pathlib.Path)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--mutants", type=int, default=40)
    ap.add_argument("--timeout", type=float, default=60.0)
    args = ap.parse_args()
    src, build = args.source.resolve(), args.build.resolve()
    data = src / "data"
    macro = str(build / "macro" / "uhpc-macro")
    micro = str(build / "micro" / "uhpc-micro")
    calibrate = str(build / "calibrate" / "uhpc-calibrate")
    tmp = pathlib.Path(tempfile.mkdtemp(prefix="uhpc_fuzz_files_"))
    rng = random.Random(48)
    cases = []  # (name, cmd, named, same_answer)
    setup_failures = []

    def setup(cmd, what):
        done = run(cmd, 600)
        if done is None or done.returncode != 0:
            setup_failures.append(f"setup: {what} failed: {done.stderr[-1500:] if done else 'timeout'}")
            return False
        return True

    # --- the checkpoint: a run stopped undecided, its restart from the intact file as the answer ---
    case = [macro, "--config", str(data / "macro_elastic_block.json")] + MACRO_CASE
    base = tmp / "macro_base"
    if setup(case + ["--set", "run.end_time_s=1.5e-5", "--out", str(base)], "uhpc-macro to 15 us"):
        reference = tmp / "macro_reference"
        shutil.copytree(base, reference)
        restart = case + ["--set", "run.end_time_s=1.7e-5", "--restart"]
        setup(restart + ["--out", str(reference)], "the restart from the intact checkpoint")

        def macro_answer(d):
            r = json.loads((d / "result.json").read_text())
            for clock in ("wall_time_s", "particle_steps_per_s", "peak_memory_MB", "provenance"):
                r.pop(clock, None)
            return r, (d / "history.csv").read_text(), ensemble_values(d / "fields.h5")

        checkpoint = (base / "checkpoint.h5").read_bytes()
        legacy = tmp / "checkpoint_legacy.h5"
        # The same checkpoint in the format before HDF5 1.8 (no checksums), for the B-tree corruption.
        with h5py.File(base / "checkpoint.h5", "r") as a, h5py.File(legacy, "w", libver="earliest") as b:
            for key in a:
                a.copy(a[key], b, name=key)
            for key, value in a.attrs.items():
                b.attrs[key] = value
        old = legacy.read_bytes()
        tree, cached = btree_addresses(old)
        labelled = mutants(checkpoint, args.mutants, rng)
        for label, at in (("B-tree address in the root symbol-table message", tree),
                          ("cached B-tree address in the superblock", cached)):
            b = bytearray(old)
            b[at:at + 8] = b"\xff" * 8
            labelled.append((f"pre-1.8 format, {label}", bytes(b)))
        for k, (label, mutated) in enumerate(labelled):
            d = tmp / f"macro_{k:03d}"
            shutil.copytree(base, d)
            (d / "checkpoint.h5").write_bytes(mutated)
            cmd = restart + ["--out", str(d)]
            same = (lambda d=d: macro_answer(d) == macro_answer(reference))
            cases.append((f"checkpoint: {label}", cmd, str(d / "checkpoint.h5"), same))

    # --- the cell: the archived cell rewritten by this version (its strain grid changed: 300 points) ---
    cell_dir = pathlib.PurePosixPath("size_3.0mm/cell_00")
    config = str(data / "micro_analysis_ensemble.json")
    ensemble_cmd = [micro, "ensemble", "--config", config] + MICRO_PART
    archived = tmp / "micro_archived"
    with tarfile.open(data / "micro_analysis_ensemble_cells" / "cells.tar.xz") as t:
        t.extractall(archived, members=[m for m in t.getmembers()
                                        if m.name.split("/cell_")[0] in ("size_3.0mm", "size_4.5mm")
                                        and "/cell_00/" in m.name])
    cells = tmp / "micro_base"
    shutil.copytree(archived, cells)
    regrid = ["--set", "strain_grid.points=300"]
    if setup(ensemble_cmd + regrid + ["--out", str(cells)], "uhpc-micro ensemble over the archived cell"):
        with h5py.File(cells / cell_dir / "curves.h5", "r") as f:
            if "checksums" not in f.attrs:
                setup_failures.append("setup: the reloaded cell was not rewritten with checksums")

        reference_ensemble = ensemble_values(cells / "ensemble.h5")
        for file_name in ("curves.h5", "summary.json"):
            original = (cells / cell_dir / file_name).read_bytes()
            count = args.mutants if file_name == "curves.h5" else args.mutants // 4
            for k, (label, mutated) in enumerate(mutants(original, count, rng)):
                d = tmp / f"micro_{file_name}_{k:03d}"
                shutil.copytree(cells, d)
                (d / "ensemble.h5").unlink()
                (d / cell_dir / file_name).write_bytes(mutated)
                cmd = ensemble_cmd + regrid + ["--assemble-only", "--out", str(d)]
                same = (lambda d=d: ensemble_values(d / "ensemble.h5") == reference_ensemble)
                # A corrupt cell is not reloaded: --assemble-only then names the cell's directory.
                cases.append((f"cell {file_name}: {label}", cmd, "size_3.0mm/cell_00", same))
        # The ensemble it wrote, read by uhpc-calibrate: a few mutants against the intact fit.
        fit = tmp / "fit_reference" / "sdel.json"
        if setup([calibrate, "--ensemble", str(cells / "ensemble.h5"), "--out", str(fit)], "uhpc-calibrate"):
            ensemble = (cells / "ensemble.h5").read_bytes()
            for k, (label, mutated) in enumerate(mutants(ensemble, max(4, args.mutants // 8), rng)):
                f = tmp / f"ensemble_{k:03d}.h5"
                f.write_bytes(mutated)
                out = tmp / f"fit_{k:03d}" / "sdel.json"
                same = (lambda out=out: fit_answer(out) == fit_answer(fit))
                cases.append((f"ensemble.h5: {label}", [calibrate, "--ensemble", str(f), "--out", str(out)], str(f),
                              same))

    # --- the B-tree corruption in the shipped files of the format before 1.8 (the cached copy in the
    #     superblock may go unused: exit 0 is then right, with the intact file's answer) ---
    legacy_fit = tmp / "fit_legacy" / "sdel.json"
    shipped = data / "micro_analysis_ensemble_cells" / "ensemble_4x10.h5"
    setup([calibrate, "--ensemble", str(shipped), "--out", str(legacy_fit)], "uhpc-calibrate on ensemble_4x10.h5")
    # The archive is written with checksums; the format before 1.8 is the fixture's cell_00 (stamped before
    # 2026-12-06, reloaded under its former hash) in place of the archive's.
    legacy = tmp / "micro_legacy"
    shutil.copytree(archived, legacy)
    shutil.rmtree(legacy / cell_dir)
    shutil.copytree(src / "tests" / "regression" / "micro_former_hash_cell" / cell_dir, legacy / cell_dir)
    legacy_assembled = tmp / "micro_legacy_reference"
    shutil.copytree(legacy, legacy_assembled)
    setup(ensemble_cmd + ["--assemble-only", "--out", str(legacy_assembled)], "assembling the archived cell")
    for what, original in (("ensemble_4x10.h5", shipped.read_bytes()),
                           ("archived curves.h5", (legacy / cell_dir / "curves.h5").read_bytes())):
        for label, at in zip(("root symbol-table message", "superblock's cached copy"), btree_addresses(original)):
            b = bytearray(original)
            b[at:at + 8] = b"\xff" * 8
            name = f"{what}: B-tree address in the {label} set to ff x 8"
            k = len(cases)
            if what == "ensemble_4x10.h5":
                f = tmp / f"btree_{k:03d}.h5"
                f.write_bytes(bytes(b))
                out = tmp / f"btree_{k:03d}" / "sdel.json"
                same = (lambda out=out: fit_answer(out) == fit_answer(legacy_fit))
                cases.append((name, [calibrate, "--ensemble", str(f), "--out", str(out)], str(f), same))
            else:
                d = tmp / f"btree_{k:03d}"
                shutil.copytree(legacy, d)
                (d / cell_dir / "curves.h5").write_bytes(bytes(b))
                same = (lambda d=d: ensemble_values(d / "ensemble.h5") ==
                        ensemble_values(legacy_assembled / "ensemble.h5"))
                cases.append((name, ensemble_cmd + ["--assemble-only", "--out", str(d)], "size_3.0mm/cell_00", same))

    def check(c):
        name, cmd, named, same = c
        done = run(cmd, args.timeout)
        return verdict(name, done, named, same, cmd), done.returncode if done else None

    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        results = list(pool.map(check, cases))
    failures = setup_failures + [r for r, _ in results if r]
    refused = sum(1 for r, code in results if not r and code == 2)
    unchanged = sum(1 for r, code in results if not r and code == 0)
    print(f"{refused} refused naming the file (exit 2), {unchanged} read with the intact file's answer (exit 0)")
    shutil.rmtree(tmp, ignore_errors=True)
    for f in failures:
        print(f)
    crashes = sum("CRASH" in f for f in failures)
    silent = sum("SILENTLY ACCEPTED" in f for f in failures)
    print(f"{len(cases)} corrupted files: {crashes} crashes, {silent} silently accepted, {len(failures)} failures")
    return 1 if failures or not cases else 0


if __name__ == "__main__":
    sys.exit(main())
