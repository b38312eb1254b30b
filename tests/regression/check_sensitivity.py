#!/usr/bin/env python3
"""A tiny end-to-end case of `make -C pipelines sensitivity` (issue 51 item 3): the coarse disc, 16 design
points at 1112 m/s (about 30 s).

Checks: the design and its 16 runs are there, each run with its point's constants file and handoff (the
values the run records are the point's); sensitivity.{json,md} are written with Q2, the trusted flag and
the indices of every input within [0, 1], first-order <= total; a second `make sensitivity` runs no shot.

usage: check_sensitivity.py --source SRC --build BUILD --out DIR
"""
import json
import subprocess

from make_target_case import ENV, Checks, make_command, start

src, build, out = start()
check = Checks()
make = make_command(src, build, out, "SENS_SAMPLES=16", "SENS_VELOCITIES=1112")
done = subprocess.run(make + ["-j2", "sensitivity"], env=ENV)
check(done.returncode == 0, "make sensitivity exits 0")
root = out / "sensitivity"
results = sorted(root.glob("points/k*/v1112/result.json"))
check(len(results) == 16, f"16 runs: {len(results)}")
check.exit_if_failed()
plan = json.loads((root / "design.json").read_text())
names = [i["name"] for i in plan["inputs"]]
for k, path in enumerate(results):
    r = json.loads(path.read_text())
    x = dict(zip(names, plan["points"][k]))
    files = {f["role"]: f["path"] for f in r["inputs"]["files"]}
    check(files.get("material", "").endswith(f"points/k{k:03d}/afc.json") and r["inputs"]["sdel"]["chi"] == x["chi"],
          f"point {k}: its constants file and handoff")
s = json.loads((root / "sensitivity.json").read_text())
v = s["velocities"][0]
check(s["format"] == "uhpc-sensitivity/1" and v["velocity_m_s"] == 1112, "format and velocity")
check("q2" in v and isinstance(v["trusted"], bool) and v["points_validated"] == 3, "Q2 on the 3 points left out, flagged")
check(all(0.0 <= v["first_order"][n] <= v["total"][n] + 1e-9 <= 1.0 + 1e-9 for n in names),
      "every input's indices within [0, 1], first-order <= total")
check((root / "sensitivity.md").is_file(), "sensitivity.md written")
stamps = {p: p.stat().st_mtime_ns for p in results}
done = subprocess.run(make + ["sensitivity"], env=ENV, capture_output=True, text=True)
check(done.returncode == 0 and all(p.stat().st_mtime_ns == t for p, t in stamps.items()),
      "a second make sensitivity keeps every run")
check.exit()
