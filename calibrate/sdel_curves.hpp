#pragma once
// What an SDEL handoff means at a given length scale (a microcell size or a macro particle spacing):
// the damage curve d+(e), the uniaxial stress-strain curve sigma = (1 - d+) E e it implies, and the
// figures that characterize it. Pure functions, no I/O: uhpc-sdel writes them, tests check them.
#include <vector>

#include "uhpc/sdel.hpp"

namespace uhpc {

struct SdelLengthSummary {
  double length_m = 0;
  double lambda = 0;                      // length / l_mac
  double initiation_strain = 0;           // e_i (eq. 26)
  double damage_at_zero_strain = 0;       // d+(0) > 0: the law's floor
  double strain_at_damage_10 = 0;         // d+ = 0.1, 0.5, 0.9
  double strain_at_damage_50 = 0;
  double strain_at_damage_90 = 0;
  double peak_stress_Pa = 0;              // max of (1 - d+) E e
  double strain_at_peak = 0;
  double dissipated_energy_J_m3 = 0;      // integral of sigma de to complete damage, per unit volume
  double crack_band_energy_J_m2 = 0;      // dissipated_energy * length (a fracture energy equivalent)
};

struct SdelCurve {
  std::vector<double> strain;  // uniform grid from 0 to strain_max
  std::vector<double> damage;
  std::vector<double> stress_Pa;
  SdelLengthSummary summary;
};

// Requires length_m, l_mac_m, strain_max, youngs_modulus_Pa > 0 and points >= 2.
SdelCurve sdel_curve(const SdelConstants<double>& c, double l_mac_m, double length_m, double strain_max,
                     int points, double youngs_modulus_Pa);

// Energy per unit volume dissipated by a bar loaded in uniaxial tension to complete damage,
// E * integral_0^inf (1 - d+(e)) e de (secant unloading: nothing is stored once d+ = 1). Numerical
// (composite Simpson up to d+ = 1 - 1e-15).
double sdel_dissipated_energy(const SdelConstants<double>& c, double lambda, double youngs_modulus_Pa);

// The same integral in closed form (a Fermi-Dirac integral): with k = lambda chi and e_h the strain at
// d+ = 1/2, x = k e_h, it is E/k^2 (x^2/2 + pi^2/6 + Li2(-exp(-x))) for x > 0. For verification.
double sdel_dissipated_energy_closed_form(const SdelConstants<double>& c, double lambda, double youngs_modulus_Pa);

}  // namespace uhpc
