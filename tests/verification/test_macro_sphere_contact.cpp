// The rigid sphere projectile in penalty contact with a free elastic block (rigid_sphere.hpp).
//  - Momentum: the contact forces are equal and opposite and the internal forces sum to zero, so the
//    total linear momentum (particles + sphere) stays at M v0 to round-off through the whole impact
//    (issue: 1e-8 relative), while a large part of it moves from the sphere into the block.
//  - Energy: kinetic + internal + viscous + contact = initial kinetic within the stated tolerance,
//    and the work-based contact account follows the exact penalty potential sum 1/2 k delta^2.
//  - Step-collapse guard: a stiff penalty (scale 100) makes the stable step collapse to a fifth at the
//    first contact; the guard repeats that step with the smaller one, and the run stays balanced. With
//    the guard off the same run goes unstable.
// The block: 48 x 48 x 16 mm, h = 4 mm (576 particles), K and G of the AFC set, NSNI with support
// 2.5 h (the shipped case's settings, see macro/README.md for why not 2.0).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "bodies/generators.hpp"
#include "solver/explicit_solver.hpp"

namespace uhpc::macro {
namespace {

constexpr double kRho = 2555.7, kK = 2.20704e10, kG = 1.8457e10;
constexpr double kMass = 9.071e-3, kRadius = 0.00635;

ExplicitSolver make_impact(double velocity, double penalty_scale, const SolverOptions& options) {
  ParticleBody body = box_body(0.048, 0.048, 0.016, 0.004);
  for (std::size_t i = 0; i < body.size(); ++i) {
    body.position[3 * i] -= 0.024;
    body.position[3 * i + 1] -= 0.024;
  }
  ExplicitSolver solver(Particles::from_body(body, kRho, options.support_factor),
                        make_material_set(ElasticMaterial(ElasticParams{kRho, kK, kG}), body.size()), options);
  RigidSphere sphere;
  sphere.mass_kg = kMass;
  sphere.radius_m = kRadius;
  sphere.x = {0.0, 0.0, -kRadius - 2e-4};
  sphere.v = {0.0, 0.0, velocity};
  sphere.contact.penalty_scale = penalty_scale;
  solver.set_sphere(sphere);
  solver.initialize();
  return solver;
}

SolverOptions shipped_options() {
  SolverOptions o;
  o.support_factor = 2.5;
  return o;
}

double momentum_error(const ExplicitSolver& s) {
  const EnergyLedger& e = s.ledger();
  double err = 0.0;
  for (int d = 0; d < 3; ++d) err += std::pow(e.momentum[d] - e.momentum_initial[d], 2);
  return std::sqrt(err) / std::fabs(e.momentum_initial[2]);
}

TEST(MacroSphereContact, ConservesMomentumAndEnergyThroughTheImpact) {
  ExplicitSolver s = make_impact(100.0, 1.0, shipped_options());
  double worst_p = 0.0, worst_e = 0.0, worst_ledger_gap = 0.0, peak_stored = 0.0;
  bool touched = false;
  while (s.time() < 6e-5) {
    ASSERT_TRUE(s.step());
    touched = touched || s.contact().particles_in_contact > 0;
    worst_p = std::max(worst_p, momentum_error(s));
    worst_e = std::max(worst_e, std::fabs(s.ledger().balance_error()) / s.ledger().kinetic_initial);
    worst_ledger_gap = std::max(worst_ledger_gap, std::fabs(s.ledger().contact - s.ledger().contact_stored));
    peak_stored = std::max(peak_stored, s.ledger().contact_stored);
    if (touched && s.contact().particles_in_contact == 0 && s.sphere().v[2] < 0) break;  // rebounded, free
  }
  const double vz = s.sphere().v[2];
  const double block_pz = s.ledger().momentum[2] - s.ledger().momentum_sphere[2];
  std::printf("sphere 100 m/s into a free elastic block: %lld steps, sphere leaves at %.3f m/s, block momentum "
              "%.5f of M v0; worst momentum error %.3e, worst energy balance error %.3e of the initial kinetic "
              "energy; contact ledger vs exact penalty potential %.3e J (peak stored %.3e J), contact energy left "
              "after release %.3e J\n",
              static_cast<long long>(s.steps()), vz, block_pz / (kMass * 100.0), worst_p, worst_e, worst_ledger_gap,
              peak_stored, s.ledger().contact);
  EXPECT_TRUE(touched);
  EXPECT_LT(vz, 0.0);                             // it bounced off the elastic block
  EXPECT_GT(block_pz, 1.2 * kMass * 100.0);       // more than M v0 went into the block
  EXPECT_LT(worst_p, 1e-8);
  EXPECT_LT(worst_e, 5e-3);
  EXPECT_LT(worst_ledger_gap, 0.05 * peak_stored);
  EXPECT_EQ(s.step_repeats(), 0);
}

// A stiff penalty (scale 100: contact frequency 10 c/h) cuts the stable step at the first contact to
// 2 sqrt(m/k) = 0.2 h/c from h/c: the guard sees the new stable step fall below half the step taken and
// repeats that step with it.
TEST(MacroSphereContact, StepCollapseGuardRepeatsTheFirstContactStep) {
  ExplicitSolver s = make_impact(100.0, 100.0, shipped_options());
  const double dt_free = s.dt();
  int after = -1;
  for (int k = 0; k < 400 && after < 60; ++k) {
    ASSERT_TRUE(s.step());
    if (s.step_repeats() > 0 && after < 0) {
      after = 0;
      std::printf("guard: repeated %lld time(s) at step %lld: step %.3e s -> %.3e s (%.3f of the free step)\n",
                  static_cast<long long>(s.step_repeats()), static_cast<long long>(s.steps()), dt_free, s.last_dt(),
                  s.last_dt() / dt_free);
      // The rejected attempt's stable step: CFL 2 sqrt(m_I / k_I) = 0.2 (CFL h / c) for scale 100.
      EXPECT_NEAR(s.last_dt() / dt_free, 0.2, 0.002);
    }
    if (after >= 0) ++after;
  }
  ASSERT_GE(after, 0) << "the guard never fired";
  const double e = std::fabs(s.ledger().balance_error()) / s.ledger().kinetic_initial;
  std::printf("guard on: %d steps after the repeat, energy balance error %.3e, momentum error %.3e\n", after, e,
              momentum_error(s));
  // The stiff spring is integrated at omega dt = 0.8 (Verlet's energy error grows with (omega dt)^2), so
  // the balance is looser than with the default penalty; the point is the contrast with the next run.
  EXPECT_LT(e, 2e-2);
  EXPECT_LT(momentum_error(s), 1e-8);

  // The same impact without the guard: the contact spring is integrated with five times its stable step.
  SolverOptions off = shipped_options();
  off.dt_collapse_fraction = 0.0;
  ExplicitSolver u = make_impact(100.0, 100.0, off);
  bool failed = false;
  double worst = 0.0;
  for (int k = 0; k < 200 && !failed; ++k) {
    failed = !u.step();
    worst = std::max(worst, std::fabs(u.ledger().balance_error()) / u.ledger().kinetic_initial);
  }
  std::printf("guard off: %s, worst energy balance error %.3e\n", failed ? "the run failed" : "ran", worst);
  EXPECT_TRUE(failed || worst > 1.0);
}

}  // namespace
}  // namespace uhpc::macro
