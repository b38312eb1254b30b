#!/usr/bin/env python3
"""Hostile inputs for every program: no input may crash, hang or end in an internal error.

usage: fuzz_inputs.py --source SRC --build BUILD [--jobs 2] [--timeout 30]

Generated from the shipped inputs, deterministically (no randomness: the same cases every run):
  configs     every leaf key of each program's shipped config replaced by a value of the wrong type
              (a string, null, a list, an object, a number where text is expected), deleted, or joined
              by an unknown sibling; the file truncated at a spread of offsets; nested 100 000 deep;
  --set       hostile values (deep nesting, huge and non-finite numbers, empty keys, unknown keys);
  sdel.json   the handoff mutated the same way (uhpc-sdel --sdel);
  result.json the shot result mutated the same way (uhpc-compare-shots);
  HDF5        the ensemble file truncated and with bytes overwritten at a spread of offsets
              (uhpc-calibrate --ensemble).
Each case must end with exit 0, or exit 2 and exactly one line on stderr starting with "error: ", or
exit 1 with one line starting with "numerical failure: " -- never a signal, a timeout, or "internal
error". Prints every violation and the count of cases.
"""
import argparse
import concurrent.futures
import copy
import json
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile

WRONG_TYPES = {"text": "not-a-number", "null": None, "list": [1, 2], "object": {"k": 1}, "number": 12345}


def leaves(doc, path=()):
    """Every (path, value) of the scalars and lists of scalars of a JSON document."""
    if isinstance(doc, dict):
        for k, v in doc.items():
            yield from leaves(v, path + (k,))
    elif isinstance(doc, list) and doc and all(isinstance(x, (dict, list)) for x in doc):
        for i, v in enumerate(doc):
            yield from leaves(v, path + (i,))
    else:
        yield path, doc


def set_at(doc, path, value=None, delete=False):
    out = copy.deepcopy(doc)
    node = out
    for p in path[:-1]:
        node = node[p]
    if delete:
        del node[path[-1]]
    else:
        node[path[-1]] = value
    return out


def mutations(doc):
    """(name, text) of the structural mutations of a JSON document."""
    for path, value in leaves(doc):
        if not path:
            continue
        name = ".".join(str(p) for p in path)
        for kind, wrong in WRONG_TYPES.items():
            if type(wrong) is type(value) or (kind == "number" and isinstance(value, (int, float))):
                continue
            yield f"{name}={kind}", json.dumps(set_at(doc, path, wrong))
        if isinstance(path[-1], str):
            yield f"{name} deleted", json.dumps(set_at(doc, path, delete=True))
            yield f"{name} unknown sibling", json.dumps(set_at(doc, path[:-1] + (path[-1] + "_x",), 1))
    text = json.dumps(doc, indent=1)
    for k in range(1, 9):
        cut = len(text) * k // 9
        yield f"truncated at {cut}", text[:cut]
    deep = 100000
    yield "nested 100000 deep", '{"a": ' + "[" * deep + "1" + "]" * deep + "}"
    yield "binary garbage", "\x00\xff\xfe{" * 50
    yield "top-level list", "[1, 2, 3]"


def hostile_sets(key):
    deep = 100000
    return [
        ("deep --set", f"{key}=" + "[" * 30000 + "]" * 30000),  # one argument is limited to 128 KiB
        ("1e400", f"{key}=1e400"),
        ("-1e308", f"{key}=-1e308"),
        ("NaN text", f"{key}=NaN"),
        ("huge integer", f"{key}=18446744073709551616"),
        ("empty key", "=1"),
        ("no equals", "justtext"),
        ("unknown key", "no.such.key=1"),
        ("dotted nothing", "...=1"),
    ]


def check(case):
    name, cmd, cwd, timeout = case
    try:
        done = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, errors="replace", timeout=timeout)
    except subprocess.TimeoutExpired:
        return f"{name}: timed out after {timeout} s: {' '.join(cmd)[:300]}"
    err = done.stderr.strip().splitlines()
    # The programs' log lines ("[hh:mm:ss] program info: ...") may precede the one error line.
    err = [line for line in err if not line.startswith("[")]
    if done.returncode < 0:
        return f"{name}: killed by signal {-done.returncode}: {' '.join(cmd)[:300]}"
    if done.returncode == 0:
        return None
    if done.returncode == 2 and len(err) == 1 and err[0].startswith("error: "):
        return None
    if done.returncode == 1 and len(err) == 1 and err[0].startswith("numerical failure: "):
        return None
    return f"{name}: exit {done.returncode}, stderr {err[:3]}: {' '.join(cmd)[:300]}"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--source", required=True, type=pathlib.Path)
    ap.add_argument("--build", required=True, type=pathlib.Path)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--timeout", type=float, default=30.0)
    args = ap.parse_args()
    src, build = args.source.resolve(), args.build.resolve()
    data = src / "data"
    sdel_prog = str(build / "calibrate" / "uhpc-sdel")
    micro = str(build / "micro" / "uhpc-micro")
    calibrate = str(build / "calibrate" / "uhpc-calibrate")
    macro = str(build / "macro" / "uhpc-macro")
    compare = str(build / "macro" / "uhpc-compare-shots")

    tmp = pathlib.Path(tempfile.mkdtemp(prefix="uhpc_fuzz_"))
    cases = []
    counter = [0]

    def write(text, suffix=".json", binary=False):
        counter[0] += 1
        p = tmp / f"in_{counter[0]:05d}{suffix}"
        if binary:
            p.write_bytes(text)
        else:
            p.write_text(text)
        return str(p)

    def out():
        return str(tmp / f"out_{counter[0]:05d}")

    # Program configs: each file mutated, run as the program would be.
    # uhpc-macro: the elastic block cut to a few steps, so a valid mutation finishes in a second.
    short = ["--set", "run.end_time_s=2e-7"]
    # The mutated copies of micro_cell.json sit in the scratch directory beside a copy of the
    # microstructure file they name.
    for doc_path, runner in [
        (data / "sdel_curves.json", lambda f: [sdel_prog, "--config", f, "--out", out()]),
        (data / "macro_elastic_block.json", lambda f: [macro, "--config", f, "--out", out(), "-q"]),
        (data / "calibrate.json", lambda f: [calibrate, "--ensemble",
                                             str(data / "micro_analysis_ensemble_cells" / "ensemble_4x10.h5"),
                                             "--config", f, "--out", out() + "/sdel.json"]),
        (data / "micro_cell.json", lambda f: [micro, "generate", "--config", f, "--set",
                                              "discretization.mesh=false", "--out", out()]),
    ]:
        doc = json.loads(doc_path.read_text())
        for name, text in mutations(doc):
            f = write(text)
            cmd = runner(f)
            if doc_path.name == "macro_elastic_block.json":
                cmd += short
            cases.append((f"{doc_path.name}: {name}", cmd, str(tmp), args.timeout))
    # Hostile --set values on each program.
    for key, base in [
        ("lengths_m", [sdel_prog, "--config", str(data / "sdel_curves.json")]),
        ("projectile.velocity_m_s", [macro, "--config", str(data / "macro_elastic_block.json"), "-q"] + short),
        ("target.spacing_m", [macro, "--config", str(data / "macro_elastic_block.json"), "-q"] + short),
        ("cell_size_m", [micro, "generate", "--config", str(data / "micro_cell.json")]),
        ("starts", [calibrate, "--ensemble", str(data / "micro_analysis_ensemble_cells" / "ensemble_4x10.h5")]),
    ]:
        for name, assignment in hostile_sets(key):
            counter[0] += 1
            o = out() if base[0] != calibrate else out() + "/sdel.json"
            cases.append((f"{pathlib.Path(base[0]).name} --set {name}", base + ["--set", assignment, "--out", o],
                          str(tmp), args.timeout))
    # Targets far beyond the size budget (a 1 nm spacing asked for 4e22 particles) and a stable step of 0.
    for assignment in ["target.spacing_m=1e-9", "target.spacing_m=1e-300", "run.max_particles=1",
                       "material.density_kg_m3=1e-300"]:
        counter[0] += 1
        cases.append((f"uhpc-macro --set {assignment}", [macro, "--config", str(data / "macro_elastic_block.json"),
                                                          "-q", "--set", assignment, "--out", out()],
                      str(tmp), args.timeout))
    # The SDEL handoff (uhpc-sdel --sdel).
    handoff = json.loads((data / "sdel_paper.json").read_text())
    for name, text in mutations(handoff):
        f = write(text)
        cases.append((f"sdel handoff: {name}", [sdel_prog, "--config", str(data / "sdel_curves.json"), "--sdel", f,
                                                "--out", out()], str(tmp), args.timeout))
    # A shot's result.json (uhpc-compare-shots), from a stand-in written here.
    result = {"impact_velocity_m_s": 610.0, "outcome": "perforated", "perforated": True, "rebounded": False,
              "residual_velocity_m_s": 200.0, "final_velocity_m_s": 200.0, "particle_count": 10, "steps": 5,
              "wall_time_s": 1.0, "energy": {"balance_error": 1e-4, "worst_balance_error": 2e-4}}
    for name, text in mutations(result):
        d = tmp / f"run_{counter[0]:05d}"
        counter[0] += 1
        d.mkdir()
        (d / "result.json").write_text(text)
        cases.append((f"result.json: {name}", [compare, "--results", str(d), "--out", out()], str(tmp), args.timeout))
    # The ensemble file (HDF5): truncated, and bytes overwritten.
    ensemble = (data / "micro_analysis_ensemble_cells" / "ensemble_4x10.h5").read_bytes()
    for k in range(1, 13):
        cut = len(ensemble) * k // 13
        f = write(ensemble[:cut], ".h5", binary=True)
        cases.append((f"ensemble truncated at {cut}", [calibrate, "--ensemble", f, "--out", out() + "/sdel.json"],
                      str(tmp), args.timeout))
    for k in range(40):
        at = (len(ensemble) * k) // 40
        corrupt = bytearray(ensemble)
        corrupt[at:at + 16] = b"\xff" * 16
        f = write(bytes(corrupt), ".h5", binary=True)
        cases.append((f"ensemble overwritten at {at}", [calibrate, "--ensemble", f, "--out", out() + "/sdel.json"],
                      str(tmp), args.timeout))

    # The cell configs name microstructure.json beside themselves.
    shutil.copy(data / "microstructure.json", tmp / "microstructure.json")
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        failures = [f for f in pool.map(check, cases) if f]
    shutil.rmtree(tmp, ignore_errors=True)
    for f in failures:
        print(f)
    print(f"{len(cases)} hostile cases, {len(failures)} failed")
    return 1 if failures or not cases else 0


if __name__ == "__main__":
    sys.exit(main())
