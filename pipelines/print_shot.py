#!/usr/bin/env python3
"""One line about a uhpc-macro run: impact and residual velocity, outcome, particles, wall time.

usage: print_shot.py RUN_DIR
"""
import json
import pathlib
import sys


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__.strip())
    run = pathlib.Path(sys.argv[1])
    r = json.loads((run / "result.json").read_text())
    vr = r["residual_velocity_m_s"]
    residual = f"residual velocity {vr:.1f} m/s" if vr is not None else f"sphere at {r['final_velocity_m_s']:.1f} m/s"
    print(f"{run}: {r['impact_velocity_m_s']:.0f} m/s -> {residual} ({r['outcome']}), "
          f"{r['particle_count']} particles, {r['wall_time_s']:.1f} s")


if __name__ == "__main__":
    main()
