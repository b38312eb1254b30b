// Energy bridging (micro/analysis/energy_bridging.hpp) against known answers: the 1D bar with one
// linear-softening cohesive crack (tests/support/cohesive_bar.hpp), without and with snap-back, and
// hand-made paths for the strain-control rules.
#include <cmath>

#include <gtest/gtest.h>

#include "cohesive_bar.hpp"
#include "energy_bridging.hpp"
#include "ensemble_curves.hpp"

namespace uhpc::micro {
namespace {

using test::CohesiveBar;

BridgingOptions first_passage() { return {}; }
BridgingOptions max_below() {
  BridgingOptions o;
  o.strain_control = StrainControl::MaxBelow;
  return o;
}

TEST(MicroEnergyBridgingBar, TableTwoBarsSnapBackAboveTwiceTheCharacteristicLength) {
  CohesiveBar bar;
  const double l_ch = bar.E * bar.G_f / (bar.f_t * bar.f_t);
  EXPECT_NEAR(l_ch, 3.0087e-3, 1e-6);
  bar.L = 0.003;
  EXPECT_FALSE(bar.snaps_back());
  bar.L = 0.0065;  // the largest cell: longer than 2 l_ch
  EXPECT_TRUE(bar.snaps_back());
}

TEST(MicroEnergyBridgingBar, PerStateDamageIsTheClosedFormBothWays) {
  const CohesiveBar bar;  // 3 mm, no snap-back
  const CellResponse r = bar.response(10, 200);
  const BridgedPath p = bridge_energy(r);
  ASSERT_EQ(p.d_energy.size(), r.states.size());
  EXPECT_DOUBLE_EQ(p.cell_area_m2, bar.L * bar.L);
  for (std::size_t i = 0; i < r.states.size(); ++i) {
    const CellState& s = r.states[i];
    const double expected = s.open_segments == 0 ? 0.0 : 1.0 - s.sigma_bar_Pa / (bar.E * s.strain);
    EXPECT_NEAR(p.d_force[i], expected, 1e-13) << "state " << i;
    EXPECT_NEAR(p.d_energy[i], expected, 1e-12) << "state " << i;
    // Psi_bar = 1/2 sigma e exactly (Hill-Mandel holds for the bar).
    EXPECT_NEAR(p.psi_bar_J_m3[i], 0.5 * s.sigma_bar_Pa * s.strain, 1e-9 * bar.f_t * bar.e_t());
  }
  // Exactly 0 before the crack opens (the peak state included), exactly 1 at separation.
  for (std::size_t i = 0; i <= 10; ++i) {
    EXPECT_EQ(p.d_energy[i], 0.0);
    EXPECT_EQ(p.d_force[i], 0.0);
  }
  EXPECT_EQ(p.d_force.back(), 1.0);
  EXPECT_EQ(p.d_energy.back(), 1.0);
  EXPECT_LT(p.max_abs_difference, 1e-12);
}

TEST(MicroEnergyBridgingBar, StrainControlledCurveIsTheClosedForm) {
  const CohesiveBar bar;
  const CellResponse r = bar.response(10, 400);
  const BridgedPath p = bridge_energy(r);
  const ControlledCurve c = strain_controlled_curve(r, p, first_passage());
  EXPECT_FALSE(c.snap_back);
  EXPECT_EQ(c.jumps, 0u);
  EXPECT_TRUE(c.separated);
  // On the states' own strains the curve is the closed form to round-off ...
  std::vector<double> at_states;
  for (const CellState& s : r.states) at_states.push_back(s.strain);
  const ResampledCurve exact = resample(c, at_states, bar.E);
  for (std::size_t i = 0; i < at_states.size(); ++i) {
    EXPECT_NEAR(exact.damage[i], bar.damage(at_states[i]), 1e-12) << i;
    EXPECT_NEAR(exact.stress_Pa[i], bar.stress(at_states[i]), 1e-6 * bar.f_t) << i;
  }
  // ... and between them within the linear-interpolation error (d is smooth in e, spacing ~2.6e-6).
  const std::vector<double> grid = strain_grid(2.0 * bar.e_separation(), 301);
  const ResampledCurve g = resample(c, grid, bar.E);
  EXPECT_TRUE(g.complete);
  EXPECT_EQ(g.valid_points, static_cast<std::size_t>(std::count_if(
                                grid.begin(), grid.end(), [&](double e) { return e <= bar.e_separation(); })));
  double worst = 0.0;
  for (std::size_t j = 0; j < grid.size(); ++j) {
    ASSERT_TRUE(std::isfinite(g.damage[j]) && std::isfinite(g.stress_Pa[j]));
    worst = std::max(worst, std::abs(g.damage[j] - bar.damage(grid[j])));
    EXPECT_NEAR(g.stress_Pa[j], bar.stress(grid[j]), 2e-3 * bar.f_t) << grid[j];
    if (grid[j] <= bar.e_t()) {
      EXPECT_EQ(g.damage[j], 0.0);
    }
    if (grid[j] >= bar.e_separation()) {
      EXPECT_EQ(g.damage[j], 1.0);
      EXPECT_EQ(g.stress_Pa[j], 0.0);
    }
  }
  EXPECT_LT(worst, 2e-3);
  const CurveFeatures f = curve_features(r, p, c);
  EXPECT_DOUBLE_EQ(f.peak_stress_Pa, bar.f_t);
  EXPECT_DOUBLE_EQ(f.strain_at_peak, bar.e_t());
  ASSERT_TRUE(f.strain_at_half_damage.has_value());
  EXPECT_NEAR(*f.strain_at_half_damage, bar.strain_at_half_damage(), 1e-3 * bar.e_t());
  EXPECT_NEAR(f.dissipated_J_m, bar.G_f * bar.L, 1e-12 * bar.G_f * bar.L);  // G_f x crack length
  EXPECT_NEAR(f.dissipated_per_area_J_m3, bar.G_f / bar.L, 1e-9 * bar.G_f / bar.L);
}

TEST(MicroEnergyBridgingBar, SnapBackJumpsFromZeroToOneAtThePeakStrainUnderFirstPassage) {
  CohesiveBar bar;
  bar.L = 0.010;
  ASSERT_TRUE(bar.snaps_back());
  ASSERT_LT(bar.e_separation(), bar.e_t());
  const CellResponse r = bar.response(10, 200);
  const BridgedPath p = bridge_energy(r);
  EXPECT_LT(p.max_abs_difference, 1e-12);  // the per-state bridging does not care about the path's shape
  const ControlledCurve c = strain_controlled_curve(r, p, first_passage());
  EXPECT_TRUE(c.snap_back);
  const std::vector<double> grid = strain_grid(1e-3, 201);  // 5e-6 apart; e_t = 5.1246e-4
  const ResampledCurve g = resample(c, grid, bar.E);
  EXPECT_TRUE(g.complete);
  for (std::size_t j = 0; j < grid.size(); ++j) {
    EXPECT_EQ(g.damage[j], bar.damage(grid[j])) << grid[j];  // 0 up to e_t, 1 beyond
    EXPECT_NEAR(g.stress_Pa[j], bar.stress(grid[j]), 1e-6 * bar.f_t) << grid[j];
  }
  // Exactly at the peak strain a test still holds the peak state (the jump comes after).
  const ResampledCurve at_peak = resample(c, {0.0, bar.e_t(), bar.e_t() * (1 + 1e-12)}, bar.E);
  EXPECT_EQ(at_peak.damage[1], 0.0);
  EXPECT_NEAR(at_peak.stress_Pa[1], bar.f_t, 1e-6 * bar.f_t);
  EXPECT_EQ(at_peak.damage[2], 1.0);
  EXPECT_EQ(at_peak.stress_Pa[2], 0.0);
  const CurveFeatures f = curve_features(r, p, c);
  ASSERT_TRUE(f.strain_at_half_damage.has_value());
  EXPECT_DOUBLE_EQ(*f.strain_at_half_damage, bar.e_t());
  EXPECT_DOUBLE_EQ(f.peak_stress_Pa, bar.f_t);
}

TEST(MicroEnergyBridgingBar, MaxBelowPutsTheSnapBackJumpBeforeThePeak) {
  CohesiveBar bar;
  bar.L = 0.010;
  const CellResponse r = bar.response(10, 200);
  const BridgedPath p = bridge_energy(r);
  const ControlledCurve c = strain_controlled_curve(r, p, max_below());
  // The separated state (e = w_c / L < e_t, d = 1) counts for every e >= w_c / L.
  const double e_sep = bar.e_separation();
  const ResampledCurve g = resample(c, {0.5 * e_sep, e_sep, 0.5 * (e_sep + bar.e_t()), 1.1 * bar.e_t()}, bar.E);
  EXPECT_EQ(g.damage[0], 0.0);
  EXPECT_EQ(g.damage[1], 1.0);
  EXPECT_EQ(g.damage[2], 1.0);
  EXPECT_EQ(g.damage[3], 1.0);
  EXPECT_EQ(g.stress_Pa[2], 0.0);
}

// A path that snaps back and recovers before separating, with hand-computed answers. E0 = 1 Pa,
// side 1 m; energies consistent with Hill-Mandel (Psi_bar = 1/2 sigma e).
CellResponse recovering_path() {
  CellResponse r;
  r.side_m = 1.0;
  r.E0_bar_Pa = 1.0;
  const double path[][2] = {{0.0, 0.0}, {1.0, 1.0}, {0.8, 0.4}, {1.2, 0.3}, {2.0, 0.0}};
  for (std::size_t i = 0; i < 5; ++i) {
    CellState s;
    s.strain = path[i][0];
    s.sigma_bar_Pa = path[i][1];
    s.bulk_energy_J_m = 0.5 * s.strain * s.sigma_bar_Pa;
    s.open_segments = i >= 2 ? 1 : 0;
    r.states.push_back(s);
  }
  r.status = CellStatus::Separated;
  return r;
}

TEST(MicroEnergyBridgingPath, FirstPassageJumpsWhereThePathComesBackAboveThePeakStrain) {
  const CellResponse r = recovering_path();
  const BridgedPath p = bridge_energy(r);
  // d = 1 - sigma/e: 0, 0, 0.5, 0.75, 1
  EXPECT_DOUBLE_EQ(p.d_force[2], 0.5);
  EXPECT_DOUBLE_EQ(p.d_force[3], 0.75);
  EXPECT_DOUBLE_EQ(p.d_energy[3], 0.75);
  const ControlledCurve c = strain_controlled_curve(r, p, first_passage());
  EXPECT_TRUE(c.snap_back);
  EXPECT_EQ(c.jumps, 1u);
  // Vertices: (0, 0), (1, 0) the peak, (1, 0.625) where segment 0.8 -> 1.2 crosses e = 1 (halfway:
  // d = 0.625, sigma = 0.35), (1.2, 0.75), (2, 1).
  ASSERT_EQ(c.strain.size(), 5u);
  EXPECT_DOUBLE_EQ(c.strain[2], 1.0);
  EXPECT_DOUBLE_EQ(c.damage[1], 0.0);
  EXPECT_DOUBLE_EQ(c.damage[2], 0.625);
  EXPECT_DOUBLE_EQ(c.stress_Pa[2], 0.35);
  const ResampledCurve g = resample(c, {0.5, 1.0, 1.1, 1.6, 2.0, 3.0}, 1.0);
  EXPECT_DOUBLE_EQ(g.damage[0], 0.0);
  EXPECT_DOUBLE_EQ(g.stress_Pa[0], 0.5);
  EXPECT_DOUBLE_EQ(g.damage[1], 0.0);  // at the jump: the state before it
  EXPECT_DOUBLE_EQ(g.stress_Pa[1], 1.0);
  EXPECT_DOUBLE_EQ(g.damage[2], 0.6875);
  EXPECT_DOUBLE_EQ(g.stress_Pa[2], 0.325);
  EXPECT_DOUBLE_EQ(g.damage[3], 0.875);
  EXPECT_DOUBLE_EQ(g.stress_Pa[3], 0.15);
  EXPECT_DOUBLE_EQ(g.damage[4], 1.0);
  EXPECT_DOUBLE_EQ(g.damage[5], 1.0);
  EXPECT_DOUBLE_EQ(g.stress_Pa[5], 0.0);
  const CurveFeatures f = curve_features(r, p, c);
  EXPECT_DOUBLE_EQ(*f.strain_at_half_damage, 1.0);  // reached in the jump
  EXPECT_DOUBLE_EQ(f.peak_stress_Pa, 1.0);
  // The alternative rule sees the snap-back state (0.8, 0.5) from e = 0.8 on.
  const ControlledCurve m = strain_controlled_curve(r, p, max_below());
  const ResampledCurve gm = resample(m, {0.7, 0.8, 0.9}, 1.0);
  EXPECT_DOUBLE_EQ(gm.damage[0], 0.4375);  // 0.7 / 0.8 x 0.5
  EXPECT_DOUBLE_EQ(gm.damage[1], 0.5);
  EXPECT_DOUBLE_EQ(gm.damage[2], 0.5);
}

TEST(MicroEnergyBridgingPath, HillMandelErrorShowsOnlyOnceCracksOpen) {
  CellResponse r = recovering_path();
  for (CellState& s : r.states) s.bulk_energy_J_m *= 1.004;  // a discretization's energy mismatch
  const BridgedPath p = bridge_energy(r);
  EXPECT_EQ(p.d_energy[1], 0.0);  // uncracked: exactly 0 whatever the mismatch
  // Cracked: d_energy - d_force = -0.004 (1 - d_force).
  EXPECT_NEAR(p.d_energy[2] - p.d_force[2], -0.004 * 0.5, 1e-15);
  EXPECT_NEAR(p.max_abs_difference, 0.002, 1e-15);
  EXPECT_EQ(p.max_difference_state, 2u);
  // The damage measure option picks which one drives the curve.
  BridgingOptions o;
  o.damage_measure = DamageMeasure::Force;
  EXPECT_DOUBLE_EQ(strain_controlled_curve(r, p, o).damage[3], 0.75);
  o.damage_measure = DamageMeasure::Energy;
  EXPECT_NEAR(strain_controlled_curve(r, p, o).damage[3], 1.0 - 1.004 * 0.3 / 1.2, 1e-15);
}

TEST(MicroEnergyBridgingPath, UnseparatedCurveHoldsItsLastDamageAndSaysWhereDataEnd) {
  CellResponse r = recovering_path();
  r.states.pop_back();
  r.status = CellStatus::ReachedEnd;
  const BridgedPath p = bridge_energy(r);
  const ControlledCurve c = strain_controlled_curve(r, p, first_passage());
  EXPECT_FALSE(c.separated);
  const ResampledCurve g = resample(c, strain_grid(2.0, 11), 1.0);  // 0, 0.2, ..., 2
  EXPECT_FALSE(g.complete);
  EXPECT_EQ(g.valid_points, 7u);  // up to 1.2
  EXPECT_DOUBLE_EQ(g.damage[10], 0.75);
  EXPECT_DOUBLE_EQ(g.stress_Pa[10], 0.25 * 2.0);
  const CurveFeatures f = curve_features(r, p, c);
  EXPECT_TRUE(f.strain_at_half_damage.has_value());
}

TEST(MicroEnergyBridgingPath, RejectsWhatCannotBeBridged) {
  CellResponse r;
  EXPECT_THROW(bridge_energy(r), std::invalid_argument);  // no states
  r = recovering_path();
  r.E0_bar_Pa = 0.0;
  EXPECT_THROW(bridge_energy(r), std::invalid_argument);
  r = recovering_path();
  r.states[2].sigma_bar_Pa = NAN;
  EXPECT_THROW(bridge_energy(r), std::invalid_argument);
}

}  // namespace
}  // namespace uhpc::micro
