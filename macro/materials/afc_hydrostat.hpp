#pragma once
// The AFC hydrostat (docs/physics.md section 4): pressure P (> 0 in compression) as a function of the
// volumetric strain mu = rho/rho0 - 1, its history maximum mu_max and the tensile cutoff T.
//
//   loading curve P_L(mu), continuous:
//     elastic    0 <= mu <= C7 :  K_e mu,                      K_e = C6 / C7
//     crushing   C7 < mu <= C9 :  C6 + K1 x + K2 x^2 + K3 x^3,  x = mu - C7
//     locking    mu > C9       :  P_L(C9) + C8 (mu - C9)
//   unloading / reloading, mu < mu_max: the straight line through the point where loading stopped,
//     P = P_L(mu_max) + K_u (mu - mu_max),   K_u = K_e + F (C8 - K_e),
//     F = (mu_max - C7) / (C9 - C7) clipped to [0, 1].
//     Anchoring the line at (mu_max, P_L(mu_max)) makes P continuous in mu (the line meets the curve
//     where loading stopped) and in time (mu_max only grows while the point is on the curve, where line
//     and curve agree). For an uncrushed point (mu_max <= C7) the line is K_e mu: elasticity.
//   tension: the same line continued below zero pressure, not below -T, T = Tmax (1 - d+). For an
//     uncrushed point that is docs/physics.md's P = K_e mu >= -Tmax (1 - d+); a crushed one reaches zero
//     pressure at the crushing (plastic volumetric) strain mu_p = mu_max - P_L(mu_max) / K_u and
//     carries tension only beyond it. P is a function of (mu, mu_max, T): a point that went past the
//     cutoff carries pressure again as soon as its volume returns (cracks close).
#include "materials/afc_params.hpp"

namespace uhpc::macro {

class AfcHydrostat {
 public:
  explicit AfcHydrostat(const AfcParams& p);

  double elastic_bulk_modulus() const { return K_e_; }  // C6 / C7
  double locking_pressure() const { return P9_; }       // P_L(C9)

  double loading_pressure(double mu) const;  // P_L(mu), mu >= 0 (K_e mu below 0)
  double loading_slope(double mu) const;     // dP_L / dmu (right derivative at C7 and C9)
  double unloading_modulus(double mu_max) const;  // K_u
  double crushing_strain(double mu_max) const;    // mu_p, where the unloading line has P = 0

  // The pressure before the tensile cutoff: the loading curve at mu >= mu_max, else the unloading line.
  // Its sign tells whether the point is on the tensile side (open) even where the cutoff is 0.
  double uncut_pressure(double mu, double mu_max) const;
  // The pressure at mu for a point whose history maximum is mu_max (>= 0; the caller raises it to mu
  // first when mu > mu_max) with tensile cutoff T >= 0: max(uncut_pressure, -T).
  double pressure(double mu, double mu_max, double cutoff_Pa) const;
  // dP / dmu at (mu, mu_max): the loading slope on the curve (mu >= mu_max), K_u below it. At the
  // tensile cutoff the flat part has slope 0; K_u is returned there too, since the next step reloads
  // along the line (a wave speed of zero would be an unsafe stable step).
  double slope(double mu, double mu_max) const;

  // Energy per unit reference volume dissipated by crushing when mu_max grows from m0 to m1: the work
  // along the loading curve minus the growth of the work recoverable along the unloading line (down to
  // zero pressure), both as the integral of P dmu / (1 + mu + o)^2 = -P dV / V0, the work per reference
  // volume of the pressure on the volume change; o the permanent opening (the hydrostat reads
  // mu = rho/rho0 - 1 - o, AfcOptions::opened_volume). Zero while m1 <= C7.
  double crushing_dissipation(double m0, double m1, double opening = 0.0) const;

 private:
  double recoverable_work(double mu_max, double o) const;   // the unloading line from mu_p to mu_max
  double loading_work(double a, double b, double o) const;  // integral of P_L dmu / (1 + mu + o)^2 over [a, b]

  double C6_, C7_, C8_, C9_, K1_, K2_, K3_;
  double K_e_, P9_;
};

}  // namespace uhpc::macro
