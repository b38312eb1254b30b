#pragma once
// A synthetic ensemble from a known SDEL, in the format of ensemble_file.hpp, so that the calibration,
// its tests and the quick start run before (and independently of) the microcell program.
//   damage mean  d(e) = sdel_damage(lambda_k, e) + noise_std * N(0, 1)   (additive, not clipped:
//                 clipping at 0 and 1 would bias the mean the fit is meant to recover)
//   damage std   noise_std * sqrt(cells): the spread of a population of `cells` cells whose mean
//                 scatters by noise_std (so std / sqrt(cells), the weight of "spread", is noise_std)
//   stress mean  (1 - d) E0 e with the noisy d; stress std = damage std * E0 e
//   nominal strength: the peak of the stress mean.
#include <cstdint>
#include <vector>

#include "uhpc/ensemble_file.hpp"
#include "uhpc/sdel.hpp"

namespace uhpc {

struct SyntheticEnsembleSettings {
  std::vector<double> sizes_m;   // ascending, > 0
  double l_mac_m = 0.4064;
  double strain_max = 1e-3;      // grid 0 .. strain_max, uniform
  int points = 201;
  double youngs_modulus_Pa = 4.33006e10;
  std::int64_t cells = 25;
  double noise_std = 0.0;        // damage units
  std::uint64_t seed = 1;        // std::mt19937_64 + std::normal_distribution (libstdc++ sequence)
};

Ensemble synthesize_ensemble(const SdelConstants<double>& constants, const SyntheticEnsembleSettings& settings);

}  // namespace uhpc
