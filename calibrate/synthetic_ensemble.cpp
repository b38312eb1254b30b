#include "synthetic_ensemble.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

namespace uhpc {

Ensemble synthesize_ensemble(const SdelConstants<double>& c, const SyntheticEnsembleSettings& s) {
  if (s.sizes_m.empty() || s.points < 2 || !(s.strain_max > 0) || !(s.youngs_modulus_Pa > 0) || s.cells < 1 ||
      !(s.noise_std >= 0)) {
    throw std::invalid_argument("synthesize_ensemble: invalid settings");
  }
  Ensemble e;
  e.sizes_m = s.sizes_m;
  const auto m = static_cast<std::size_t>(s.points);
  for (std::size_t j = 0; j < m; ++j) e.strain.push_back(s.strain_max * static_cast<double>(j) / static_cast<double>(m - 1));

  std::mt19937_64 rng(s.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double spread = s.noise_std * std::sqrt(static_cast<double>(s.cells));
  for (double size : s.sizes_m) {
    const double lambda = sdel_lambda(size, s.l_mac_m);
    std::vector<double> dm(m), ds(m, spread), sm(m), ss(m);
    for (std::size_t j = 0; j < m; ++j) {
      const double eps = e.strain[j];
      dm[j] = sdel_damage(lambda, eps, c) + (s.noise_std > 0 ? s.noise_std * normal(rng) : 0.0);
      sm[j] = (1.0 - dm[j]) * s.youngs_modulus_Pa * eps;
      ss[j] = spread * s.youngs_modulus_Pa * eps;
    }
    e.nominal_strength_Pa.push_back(*std::max_element(sm.begin(), sm.end()));
    e.damage_mean.push_back(dm);
    e.damage_std.push_back(ds);
    e.stress_mean_Pa.push_back(sm);
    e.stress_std_Pa.push_back(ss);
    e.cells.push_back(s.cells);
  }
  return e;
}

}  // namespace uhpc
