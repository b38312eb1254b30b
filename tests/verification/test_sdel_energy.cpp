// The energy an SDEL dissipates in uniaxial tension: numerical integration against the closed form
// (a Fermi-Dirac integral), and the crack-band trend docs/physics.md section 3 relies on: the energy per
// unit volume falls as the length scale grows.
#include <gtest/gtest.h>

#include <cmath>

#include "sdel_curves.hpp"
#include "uhpc/sdel_handoff.hpp"

namespace {

const uhpc::SdelConstants<double> kPaper{1.0, 0.0002, 120.5, 4.1e6};
constexpr double kLmac = 0.4064, kE = 4.33006e10;

TEST(SdelEnergy, NumericalIntegralMatchesClosedForm) {
  for (double length : {0.001, 0.003, 0.0045, 0.005, 0.0065, 0.02}) {
    const double lambda = length / kLmac;
    const double numeric = uhpc::sdel_dissipated_energy(kPaper, lambda, kE);
    const double exact = uhpc::sdel_dissipated_energy_closed_form(kPaper, lambda, kE);
    EXPECT_NEAR(numeric / exact, 1.0, 1e-9) << "length " << length;
  }
}

TEST(SdelEnergy, SharpLawTendsToTheStepLimit) {
  // For a very steep law (k e_h >> 1) the bar is elastic up to e_h and then loses all stiffness:
  // g -> E e_h^2 / 2 (Sommerfeld: + pi^2 E / (6 k^2)).
  uhpc::SdelConstants<double> steep = kPaper;
  steep.chi = 4.1e9;
  const double lambda = 0.003 / kLmac;
  const double e_h = uhpc::sdel_strain_at_damage(lambda, 0.5, steep);
  EXPECT_NEAR(uhpc::sdel_dissipated_energy(steep, lambda, kE) / (0.5 * kE * e_h * e_h), 1.0, 1e-4);
}

TEST(SdelEnergy, PaperLawDissipatesLessPerVolumeAtLargerSpacing) {
  double previous = INFINITY;
  for (double length : {0.003, 0.0045, 0.005, 0.0065}) {
    const auto curve = uhpc::sdel_curve(kPaper, kLmac, length, 1e-3, 101, kE);
    EXPECT_LT(curve.summary.dissipated_energy_J_m3, previous);
    previous = curve.summary.dissipated_energy_J_m3;
  }
}

TEST(SdelEnergy, PeakStressIsTheMaximumOfTheCurve) {
  const auto curve = uhpc::sdel_curve(kPaper, kLmac, 0.003, 1e-3, 100001, kE);
  double grid_max = 0.0;
  for (double s : curve.stress_Pa) grid_max = std::max(grid_max, s);
  EXPECT_GE(curve.summary.peak_stress_Pa, grid_max * (1 - 1e-12));
  EXPECT_NEAR(curve.summary.peak_stress_Pa / grid_max, 1.0, 1e-8);
  EXPECT_LT(curve.summary.strain_at_peak, curve.summary.strain_at_damage_50);
}

}  // namespace
