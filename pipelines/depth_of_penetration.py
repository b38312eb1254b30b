#!/usr/bin/env python3
"""Depth of penetration of the sphere into a thick target, against Forrestal's formulas for concrete.

    depth_of_penetration.py RUN_DIR... --fc-MPa 193.6 --out DIR

For each run (uhpc-macro's result.json and history.csv) the deepest reach of the sphere's nose along
the flight axis (the sphere's centre z plus its radius; the entry face is z = 0), and beside it two
closed forms for a rigid projectile in concrete, both with the target's density and unconfined
compressive strength f'c and the sphere's mass m and radius a:

  Forrestal et al. (1994, Int. J. Impact Eng. 15:395-405) with Frew et al.'s S (1998, Int. J. Impact
  Eng. 21:489-497): a crater region of depth 4a, in which the force grows linearly with depth, then a
  tunnel with the cavity-expansion force F = pi a^2 (S f'c + N rho V^2):
      P = 4a + m / (2 pi a^2 rho N) ln(1 + N rho V1^2 / (S f'c)),
      V1^2 = (m V0^2 - 4 pi a^3 S f'c) / (m + 4 pi a^3 rho N),
  and P = V0 sqrt(4 m / (pi a S f'c)) when the sphere stops inside the crater region (m V0^2 below
  4 pi a^3 S f'c);
  the tunnel alone (the cavity-expansion force from the first contact, no crater):
      P = m / (2 pi a^2 rho N) ln(1 + N rho V0^2 / (S f'c)).
  S = 82.6 (f'c / 1 MPa)^-0.544 and N = 0.5 (a hemispherical nose: N* = (8 psi - 1) / (24 psi^2), psi =
  0.5). S was fitted to concretes of 13-62 MPa and the crater length 4a to ogive rods about ten diameters
  long; a UHPC of 194 MPa and a sphere lie outside both, so the two forms are a check of magnitude and
  of the trend with speed, not a reference value.

Writes DIR/dop.{md,json}.
"""
import argparse
import csv
import json
import math
import sys
from pathlib import Path

HEMISPHERE_NOSE_FACTOR = 0.5


def frew_s(fc_pa):
    return 82.6 * (fc_pa / 1e6) ** -0.544


def forrestal_crater_tunnel(v0, m, a, rho, fc_pa):
    s_fc = frew_s(fc_pa) * fc_pa
    n = HEMISPHERE_NOSE_FACTOR
    crater_work = 4.0 * math.pi * a**3 * s_fc  # m V0^2 that the crater region alone absorbs
    if m * v0 * v0 <= crater_work:
        return v0 * math.sqrt(4.0 * m / (math.pi * a * s_fc))
    v1_sq = (m * v0 * v0 - crater_work) / (m + 4.0 * math.pi * a**3 * rho * n)
    return 4.0 * a + m / (2.0 * math.pi * a * a * rho * n) * math.log1p(n * rho * v1_sq / s_fc)


def forrestal_tunnel(v0, m, a, rho, fc_pa):
    s_fc = frew_s(fc_pa) * fc_pa
    n = HEMISPHERE_NOSE_FACTOR
    return m / (2.0 * math.pi * a * a * rho * n) * math.log1p(n * rho * v0 * v0 / s_fc)


def material_density(config):
    """The target's density from the material file the run read (config.json's files, role material)."""
    for entry in config.get("files", []):
        if entry.get("role") == "material":
            # As the program opened it: relative to where it ran, which for the shipped files is the
            # repository root (this script's parent's parent) when not the directory this runs in.
            for path in (Path(entry["path"]), Path(__file__).resolve().parent.parent / entry["path"]):
                if path.is_file():
                    return json.loads(path.read_text()).get("density_kg_m3")
    return None


def deepest_nose(run):
    """The deepest reach of the nose (m) and when (s), from history.csv."""
    config = json.loads((run / "config.json").read_text())
    radius = config["case"]["projectile"]["radius_m"]
    depth, when = -math.inf, 0.0
    with open(run / "history.csv", newline="") as f:
        for row in csv.DictReader(f):
            z = float(row["sphere_z_m"]) + radius
            if z > depth:
                depth, when = z, float(row["time_s"])
    return depth, when, config


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+", type=Path)
    ap.add_argument("--fc-MPa", type=float, required=True, help="unconfined compressive strength f'c")
    ap.add_argument("--out", type=Path, required=True)
    args = ap.parse_args(argv)
    rows = []
    for run in args.runs:
        for name in ("result.json", "history.csv", "config.json"):
            if not (run / name).is_file():
                print(f"depth_of_penetration.py: {run / name}: missing (not a finished run)", file=sys.stderr)
                return 2
        result = json.loads((run / "result.json").read_text())
        depth, when, config = deepest_nose(run)
        case = config["case"]
        m, a = case["projectile"]["mass_kg"], case["projectile"]["radius_m"]
        rho = material_density(config)
        if rho is None:
            print(f"depth_of_penetration.py: {run / 'config.json'}: no material file with density_kg_m3", file=sys.stderr)
            return 2
        v0 = result["impact_velocity_m_s"]
        fc = args.fc_MPa * 1e6
        rows.append({"run": str(run), "impact_velocity_m_s": v0, "outcome": result["outcome"],
                     "thickness_m": case["target"]["thickness_m"], "depth_m": depth, "depth_time_s": when,
                     "forrestal_crater_tunnel_m": forrestal_crater_tunnel(v0, m, a, rho, fc),
                     "forrestal_tunnel_m": forrestal_tunnel(v0, m, a, rho, fc)})
    rows.sort(key=lambda r: r["impact_velocity_m_s"])
    args.out.mkdir(parents=True, exist_ok=True)
    summary = {"fc_MPa": args.fc_MPa, "S": frew_s(args.fc_MPa * 1e6), "nose_factor": HEMISPHERE_NOSE_FACTOR,
               "runs": rows}
    (args.out / "dop.json").write_text(json.dumps(summary, indent=2) + "\n")
    lines = [f"Depth of penetration of the nose (f'c = {args.fc_MPa:g} MPa, S = {summary['S']:.2f}, N = 0.5)", "",
             "| impact m/s | outcome | target mm | deepest nose mm (at us) | Forrestal crater + tunnel mm | "
             "tunnel alone mm |", "|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['impact_velocity_m_s']:.0f} | {r['outcome']} | {1e3 * r['thickness_m']:.1f} | "
                     f"{1e3 * r['depth_m']:.1f} ({1e6 * r['depth_time_s']:.0f}) | "
                     f"{1e3 * r['forrestal_crater_tunnel_m']:.1f} | {1e3 * r['forrestal_tunnel_m']:.1f} |")
    (args.out / "dop.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())
