#!/usr/bin/env python3
"""Compare two analysed microcells (uhpc-micro run / ensemble cell directories) value by value.

usage: compare_cells.py A B [--rtol R]

Every key of summary.json (apart from wall_s, dates, provenance and its checksum) and every dataset of curves.h5 must
agree: exactly by default (a refactor of the solver must not change a bit), or within the relative
tolerance R (a changed solver: the issue asks for 1e-6). A key or a dataset in only one of the two cells
is a difference, whichever cell holds it. Prints each difference and the verdict; exit 0
when the cells agree, 1 otherwise.
"""
import argparse
import json
import sys

import h5py
import numpy as np

SKIP = {"wall_s", "date", "date_utc", "provenance", "checksum_fnv1a64"}  # the checksum covers wall_s


def close(x, y, rtol):
    if rtol == 0.0:
        return np.array_equal(x, y, equal_nan=True)
    return np.allclose(x, y, rtol=rtol, atol=0.0, equal_nan=True)


def compare_json(x, y, rtol, path=""):
    bad = []
    if isinstance(x, dict) and isinstance(y, dict):
        for k in sorted(set(x) | set(y)):
            if k in SKIP:
                continue
            if k not in x or k not in y:
                bad.append(f"{path}/{k}: only in {'B' if k not in x else 'A'}")
            else:
                bad += compare_json(x[k], y[k], rtol, f"{path}/{k}")
    elif isinstance(x, list) and isinstance(y, list):
        if len(x) != len(y):
            return [f"{path}: {len(x)} against {len(y)} entries"]
        for i, (u, v) in enumerate(zip(x, y)):
            bad += compare_json(u, v, rtol, f"{path}[{i}]")
    elif isinstance(x, (int, float)) and isinstance(y, (int, float)) and not isinstance(x, bool):
        if not close(np.float64(x), np.float64(y), rtol):
            bad.append(f"{path}: {x!r} against {y!r}")
    elif x != y:
        bad.append(f"{path}: {x!r} against {y!r}")
    return bad


def dataset_names(f):
    names = []
    f.visititems(lambda n, o: names.append(n) if isinstance(o, h5py.Dataset) else None)
    return names


def compare_h5(a, b, rtol):
    """The differences between the datasets of two curves.h5, and how many datasets the two hold together: a
    dataset in only one of them is a difference, whichever it is in."""
    bad = []
    with h5py.File(a, "r") as fa, h5py.File(b, "r") as fb:
        in_a, in_b = dataset_names(fa), dataset_names(fb)
        for n in sorted(set(in_a) | set(in_b)):
            if n not in in_b:
                bad.append(f"curves.h5 {n}: only in A")
                continue
            if n not in in_a:
                bad.append(f"curves.h5 {n}: only in B")
                continue
            x, y = fa[n][()], fb[n][()]
            if np.shape(x) != np.shape(y):
                bad.append(f"curves.h5 {n}: shape {np.shape(x)} against {np.shape(y)}")
            elif np.asarray(x).dtype.kind == "f":
                if not close(x, y, rtol):
                    bad.append(f"curves.h5 {n}: largest difference {np.nanmax(np.abs(x - y)):.3e}")
            elif not np.array_equal(x, y):
                bad.append(f"curves.h5 {n}: differs")
    return bad, len(set(in_a) | set(in_b))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("a")
    ap.add_argument("b")
    ap.add_argument("--rtol", type=float, default=0.0)
    args = ap.parse_args()
    with open(f"{args.a}/summary.json") as fa, open(f"{args.b}/summary.json") as fb:
        bad = compare_json(json.load(fa), json.load(fb), args.rtol)
    h5_bad, datasets = compare_h5(f"{args.a}/curves.h5", f"{args.b}/curves.h5", args.rtol)
    bad += h5_bad
    for line in bad:
        print(line)
    what = "identical" if args.rtol == 0.0 else f"within rtol {args.rtol:g}"
    print(f"{args.a} vs {args.b}: summary.json and {datasets} datasets: "
          + (what if not bad else f"{len(bad)} difference(s)"))
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
