#pragma once
// The bridge from an ensemble file to the fitter's input: lambda = l_mic / l_mac per size, and the
// standard error of each mean damage value, std / sqrt(cells) (what the "spread" weighting divides by).
#include <cmath>

#include "uhpc/ensemble_file.hpp"
#include "sdel_fit.hpp"

namespace uhpc {

inline SdelFitData fit_data_from_ensemble(const Ensemble& e, double l_mac_m) {
  SdelFitData d;
  d.strain = e.strain;
  d.damage = e.damage_mean;
  for (std::size_t k = 0; k < e.size_count(); ++k) {
    d.lambdas.push_back(sdel_lambda(e.sizes_m[k], l_mac_m));
    std::vector<double> sigma;
    for (double s : e.damage_std[k]) sigma.push_back(s / std::sqrt(static_cast<double>(e.cells[k])));
    d.sigma.push_back(sigma);
  }
  return d;
}

}  // namespace uhpc
