#pragma once
// What the single-point tests of the AFC material share: the shipped constants, a driver at the paper's
// centre spacing, and the inverse of the hydrostat's loading curve.
#include "materials/afc.hpp"
#include "materials/afc_config.hpp"
#include "materials/point_driver.hpp"

namespace uhpc::macro::afc_test {

inline constexpr double kSpacing = 0.003;  // h_I = 3 mm, the paper's centre spacing
inline constexpr double MPa = 1e6;
using Driver = PointDriver<AfcMaterial>;

// Table 6 with the paper's SDEL and the shipped options.
inline AfcParams shipped() { return load_afc_params(UHPC_DATA_DIR "/afc_uhpc.json", UHPC_DATA_DIR "/sdel_paper.json"); }

// The volumetric strain of the loading curve at pressure P (bisection on the rising curve).
inline double mu_at_pressure(const AfcHydrostat& h, double P) {
  double lo = 0.0, hi = 0.5;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (h.loading_pressure(mid) < P ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace uhpc::macro::afc_test
