#!/usr/bin/env python3
"""pipelines/depth_of_penetration.py: Forrestal's formulas against values worked by hand for the 9.071 g,
12.7 mm sphere in the paper's UHPC (f'c 193.6 MPa, rho 2555.7 kg/m^3), and the crater and tunnel forms
meeting at the crater's depth 4a (the force is continuous there, so must the depth be)."""
import math

from pipeline_checks import check, finish  # puts pipelines/ on the path first
import depth_of_penetration as dop  # noqa: E402



m, a, rho, fc = 0.009071, 0.00635, 2555.7, 193.6e6
# S = 82.6 exp(-0.544 ln 193.6) = 82.6 * 0.05701 = 4.709; S f'c = 911.6 MPa.
s = dop.frew_s(fc)
check(abs(s - 4.709) < 1e-3, f"Frew's S at 193.6 MPa: {s:.4f} (4.709)")
# 400 m/s: m V0^2 = 1451 J < 4 pi a^3 S f'c = 2934 J, so the sphere stops in the crater region:
# P = 400 sqrt(4 m / (pi a S f'c)) = 400 * 4.465e-5 = 17.86 mm.
p400 = dop.forrestal_crater_tunnel(400.0, m, a, rho, fc)
check(abs(p400 - 17.86e-3) < 0.02e-3, f"400 m/s, crater region: {1e3 * p400:.3f} mm (17.86)")
# The tunnel alone at 400 m/s: m / (2 pi a^2 rho N) = 0.02804 m, N rho V^2 / (S f'c) = 0.2242: 5.67 mm.
t400 = dop.forrestal_tunnel(400.0, m, a, rho, fc)
check(abs(t400 - 5.67e-3) < 0.02e-3, f"400 m/s, tunnel alone: {1e3 * t400:.3f} mm (5.67)")
# At the speed whose m V0^2 is the crater's work both branches give 4a.
v_edge = math.sqrt(4.0 * math.pi * a**3 * s * fc / m)
below = dop.forrestal_crater_tunnel(v_edge * (1 - 1e-9), m, a, rho, fc)
above = dop.forrestal_crater_tunnel(v_edge * (1 + 1e-9), m, a, rho, fc)
check(abs(below - 4 * a) < 1e-8 and abs(above - 4 * a) < 1e-8,
      f"continuous at the crater depth ({v_edge:.1f} m/s): {1e3 * below:.6f} / {1e3 * above:.6f} mm (4a = 25.4)")
check(dop.forrestal_crater_tunnel(600.0, m, a, rho, fc) > 4 * a, "600 m/s reaches the tunnel")
finish()
