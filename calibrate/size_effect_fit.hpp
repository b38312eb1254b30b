#pragma once
// Bazant's size effect law fitted to the nominal strengths of the cell sizes:
//   sigma_N(D) = B f_t / sqrt(1 + D / D0)
// with D the cell size, f_t a reference tensile strength (the microcell matrix's, Table 2) and B, D0 > 0
// fitted. Start: the law is linear in D after (f_t / sigma_N)^2 = 1/B^2 + D / (B^2 D0); then a Ceres
// least-squares fit of sigma_N itself (ln B, ln D0) with its covariance. Pure numerics, no I/O.
#include <array>
#include <string>
#include <vector>

namespace uhpc {

struct SizeEffectFit {
  bool size_effect = false;   // false: strength does not fall with size, D0 undefined (law not fitted)
  std::string note;           // why, when size_effect is false
  double B = 0;               // dimensionless
  double D0_m = 0;            // transitional size
  double f_t_Pa = 0;
  std::array<double, 2> standard_error{};  // of B and D0 (NaN with fewer than 3 sizes)
  double correlation = 0;                  // between B and D0 (NaN when not available)
  double rms_Pa = 0;
  double r_squared = 0;
  std::vector<double> fitted_Pa;           // the law at each size
};

// The law at size D.
double size_effect_strength(double B, double f_t_Pa, double D0_m, double D_m);

// sizes > 0 ascending and strengths > 0, equal lengths >= 2. Throws std::invalid_argument otherwise.
SizeEffectFit fit_size_effect(const std::vector<double>& sizes_m, const std::vector<double>& strengths_Pa,
                              double f_t_Pa);

}  // namespace uhpc
