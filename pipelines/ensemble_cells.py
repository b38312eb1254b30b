#!/usr/bin/env python3
"""The cells of a microcell analysis ensemble as make target stems, largest cells first.

usage: ensemble_cells.py CONFIG.json [--set key=value ...]

Prints one word per cell, <size in mm>_<realization> (e.g. 6.5_24 ... 3_0), for the micro-cell-% targets of
pipelines/Makefile. Reads cell_sizes_m and realizations from CONFIG, where a `--set cell_sizes_m=[...]` or
`--set realizations=N` (as given to uhpc-micro ensemble) wins; other overrides do not change the cells.
uhpc-micro ensemble validates the config itself: a size or realization it does not have is bad input there.
"""
import json
import sys


def sizes_and_realizations(config, set_args):
    """cell_sizes_m and realizations of the ensemble config `config` (a dict), where a `--set
    cell_sizes_m=[...]` or `--set realizations=N` among `set_args` (as given to uhpc-micro ensemble) wins."""
    sizes, realizations = config.get("cell_sizes_m", []), config.get("realizations", 0)
    for k, arg in enumerate(set_args):
        value = (arg[len("--set="):] if arg.startswith("--set=")
                 else set_args[k + 1] if arg == "--set" and k + 1 < len(set_args) else None)
        if value is None or "=" not in value:
            continue
        key, text = value.split("=", 1)
        if key == "cell_sizes_m":
            sizes = json.loads(text)
        elif key == "realizations":
            realizations = int(json.loads(text))
    return sizes, realizations


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__.strip().splitlines()[2])
    try:
        with open(sys.argv[1]) as f:
            config = json.load(f)
    except (OSError, ValueError) as e:
        sys.exit(f"ensemble_cells.py: {sys.argv[1]}: {e}")
    sizes, realizations = sizes_and_realizations(config, sys.argv[2:])
    cells = [f"{s * 1e3:.12g}_{r}" for s in sizes for r in range(int(realizations))]
    print(" ".join(reversed(cells)))


if __name__ == "__main__":
    main()
