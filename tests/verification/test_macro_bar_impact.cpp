// An elastic bar hitting a rigid wall (macro solver core). A square bar of length L moving at -v0
// along x meets a frictionless penalty wall at x = 0. One-dimensional theory: a compression wave runs
// to the free end and back, the bar stays in contact for 2 L / c0 and leaves stress-free at +v0 with
// all its kinetic energy. Poisson's ratio is 0 so the bar is exactly one-dimensional (see
// test_macro_wave_speed.cpp). Measured: the contact duration (first to last step with a wall force),
// the bar's mean velocity after release, and the energy balance kinetic + internal + viscous -
// external work = initial kinetic energy throughout the run.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "bodies/generators.hpp"
#include "solver/explicit_solver.hpp"

namespace uhpc::macro {
namespace {

constexpr double kE = 200e9, kRho = 7850.0;

struct ImpactResult {
  double contact_time, expected_time, rebound_velocity, v0, worst_balance, kinetic_initial, kinetic_final;
};

ImpactResult impact(double h, const BulkViscosity& viscosity,
                    StrainConfiguration strain = SolverOptions{}.strain_configuration, double shape_reuse = 0.0) {
  const double length = 0.1, side = 4 * h, v0 = 10.0;
  const ParticleBody body = box_body(length, side, side, h);
  SolverOptions options;
  options.viscosity = viscosity;
  options.strain_configuration = strain;
  options.shape_reuse_tolerance = shape_reuse;
  ExplicitSolver solver(Particles::from_body(body, kRho, options.support_factor),
                        make_material_set(ElasticMaterial(ElasticParams{kRho, kE / 3.0, kE / 2.0}), body.size()),
                        options);
  // The bar's face starts a hundredth of a spacing off the wall.
  for (std::size_t i = 0; i < solver.particles().n; ++i) solver.particles().x[3 * i] += 0.01 * h;
  set_initial_velocity(solver.particles(), Region{{-1, -1, -1}, {1, 1, 1}}, {-v0, 0, 0});
  Wall wall;
  wall.point = {0, 0, 0};
  wall.normal = {1, 0, 0};
  solver.add_wall(wall);
  solver.initialize();

  const double c0 = std::sqrt(kE / kRho), expected = 2.0 * length / c0;
  double t_first = -1, t_last = -1, worst = 0.0;
  while (solver.time() < 1.6 * expected) {
    const double t0 = solver.time();
    EXPECT_TRUE(solver.step());
    if (solver.wall_force_magnitude() > 0.0) {
      if (t_first < 0) t_first = t0;  // the force acts over the step that ends in contact
      t_last = solver.time();
    }
    worst = std::max(worst, std::fabs(solver.ledger().balance_error()));
  }
  double mass = 0.0;
  for (double m : solver.particles().mass) mass += m;
  return {t_last - t_first, expected, solver.ledger().momentum[0] / mass, v0, worst / solver.ledger().kinetic_initial,
          solver.ledger().kinetic_initial, solver.ledger().kinetic};
}

void report(const char* label, const ImpactResult& r) {
  std::printf(
      "%s: contact %.4f us vs 2L/c0 %.4f us (error %+.3f %%); rebound %.4f m/s vs %.1f (%+.3f %%); worst energy "
      "balance error %.3e of the initial kinetic energy; final/initial kinetic %.5f\n",
      label, 1e6 * r.contact_time, 1e6 * r.expected_time, 100.0 * (r.contact_time / r.expected_time - 1.0),
      r.rebound_velocity, r.v0, 100.0 * (r.rebound_velocity / r.v0 - 1.0), r.worst_balance,
      r.kinetic_final / r.kinetic_initial);
}

// 80 particles along the bar (h = 1.25 mm, 4 x 4 across). The shortfall of the rebound speed is the
// part of the reflected wave still trailing behind the front (discrete dispersion) plus what the
// bulk viscosity took; both shrink with h (next test).
TEST(MacroBarImpact, ContactTimeReboundAndEnergyWithDefaultViscosity) {
  const ImpactResult r = impact(1.25e-3, BulkViscosity{});
  report("bar impact, h = 1.25 mm, default bulk viscosity", r);
  EXPECT_NEAR(r.contact_time / r.expected_time, 1.0, 0.03);
  EXPECT_NEAR(r.rebound_velocity / r.v0, 1.0, 0.03);
  EXPECT_LT(r.worst_balance, 0.01);
}

TEST(MacroBarImpact, ContactTimeReboundAndEnergyWithoutViscosity) {
  const ImpactResult r = impact(1.25e-3, BulkViscosity{0.0, 0.0});
  report("bar impact, h = 1.25 mm, no bulk viscosity", r);
  EXPECT_NEAR(r.contact_time / r.expected_time, 1.0, 0.03);
  EXPECT_NEAR(r.rebound_velocity / r.v0, 1.0, 0.03);
  EXPECT_LT(r.worst_balance, 0.01);
}

// The default strain is the endpoint average; the same with the midpoint strain.
TEST(MacroBarImpact, ContactTimeReboundAndEnergyWithMidpointStrain) {
  const ImpactResult r = impact(1.25e-3, BulkViscosity{}, StrainConfiguration::Midpoint);
  report("bar impact, h = 1.25 mm, default bulk viscosity, midpoint strain", r);
  EXPECT_NEAR(r.contact_time / r.expected_time, 1.0, 0.03);
  EXPECT_NEAR(r.rebound_velocity / r.v0, 1.0, 0.03);
  EXPECT_LT(r.worst_balance, 0.01);
}

// Lazy RK rows (the shipped cases' shape_reuse_tolerance 3e-4): the same bounds.
TEST(MacroBarImpact, ContactTimeReboundAndEnergyWithLazyRows) {
  const ImpactResult r = impact(1.25e-3, BulkViscosity{}, SolverOptions{}.strain_configuration, 3e-4);
  report("bar impact, h = 1.25 mm, default bulk viscosity, lazy rows 3e-4", r);
  EXPECT_NEAR(r.contact_time / r.expected_time, 1.0, 0.03);
  EXPECT_NEAR(r.rebound_velocity / r.v0, 1.0, 0.03);
  EXPECT_LT(r.worst_balance, 0.01);
}

// Halving the spacing must bring both the contact time and the rebound speed closer to theory.
TEST(MacroBarImpact, ErrorsShrinkWithSpacing) {
  const ImpactResult coarse = impact(2.5e-3, BulkViscosity{}), fine = impact(1.25e-3, BulkViscosity{});
  report("bar impact, h = 2.5 mm, default bulk viscosity", coarse);
  EXPECT_LT(std::fabs(fine.contact_time / fine.expected_time - 1.0),
            0.7 * std::fabs(coarse.contact_time / coarse.expected_time - 1.0));
  EXPECT_LT(std::fabs(fine.rebound_velocity / fine.v0 - 1.0), 0.8 * std::fabs(coarse.rebound_velocity / coarse.v0 - 1.0));
  EXPECT_LT(coarse.worst_balance, 0.01);
}

// A plastic impact (J2 steel-like bar, yield 300 MPa, at 100 m/s: the elastic impact stress rho c v0
// = 4 GPa is far above yield). No closed form for the rebound here; what must hold is the energy
// balance with the plastic work booked: kinetic + internal (elastic + plastic) + viscous - external
// work = initial kinetic energy, and the plastic work a sizeable, positive part of it.
void plastic_impact_keeps_the_energy_balance(StrainConfiguration strain) {
  const double h = 2.5e-3, length = 0.1, side = 4 * h, v0 = 100.0;
  const ParticleBody body = box_body(length, side, side, h);
  J2Params jp;
  jp.density_kg_m3 = kRho;
  jp.bulk_modulus_Pa = kE / 3.0;
  jp.shear_modulus_Pa = kE / 2.0;
  jp.yield_stress_Pa = 300e6;
  jp.hardening_modulus_Pa = 1e9;
  SolverOptions options;
  options.strain_configuration = strain;
  ExplicitSolver solver(Particles::from_body(body, kRho, options.support_factor),
                        make_material_set(J2Material(jp), body.size()), options);
  for (std::size_t i = 0; i < solver.particles().n; ++i) solver.particles().x[3 * i] += 0.01 * h;
  set_initial_velocity(solver.particles(), Region{{-1, -1, -1}, {1, 1, 1}}, {-v0, 0, 0});
  solver.add_wall(Wall{});
  solver.initialize();
  double worst = 0.0;
  while (solver.time() < 4.0 * length / std::sqrt(kE / kRho)) {
    ASSERT_TRUE(solver.step());
    worst = std::max(worst, std::fabs(solver.ledger().balance_error()));
  }
  const EnergyLedger& e = solver.ledger();
  std::printf("plastic bar impact at %.0f m/s (%s strain): plastic work %.4f, internal %.4f, viscous %.4f, kinetic %.4f of the "
              "initial kinetic energy; worst balance error %.3e\n",
              v0, strain == StrainConfiguration::Midpoint ? "midpoint" : "endpoint-average",
              e.material_dissipated / e.kinetic_initial, e.internal / e.kinetic_initial,
              e.viscous / e.kinetic_initial, e.kinetic / e.kinetic_initial, worst / e.kinetic_initial);
  EXPECT_LT(worst / e.kinetic_initial, 0.01);
  EXPECT_GT(e.material_dissipated, 0.1 * e.kinetic_initial);
  EXPECT_LT(e.material_dissipated, e.internal);
}

TEST(MacroBarImpact, PlasticImpactKeepsTheEnergyBalance) {
  plastic_impact_keeps_the_energy_balance(StrainConfiguration::Midpoint);
}
TEST(MacroBarImpact, PlasticImpactKeepsTheEnergyBalanceWithEndpointAverageStrain) {
  plastic_impact_keeps_the_energy_balance(StrainConfiguration::EndpointAverage);
}

}  // namespace
}  // namespace uhpc::macro
