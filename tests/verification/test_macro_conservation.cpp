// Conservation and reversibility of the macro solver core on a free elastic body.
//  - Linear momentum: with no external force the total momentum may change only by round-off, since
//    the nodal-integration forces sum to zero at every step (RK implicit gradients sum to zero).
//  - Angular momentum: conserved too while every particle is on the full linear-basis path (linear
//    reproduction, symmetric stress): velocity Verlet conserves it exactly for such forces.
//  - Reversibility: with a constant step, no bulk viscosity and the mid-step (or endpoint-average)
//    strain configuration, running N steps, negating the velocities and running N more returns to the
//    start to round-off (the symmetric Cayley rotation and the exponential volume update are exactly
//    reversible). The end-of-step strain is not time-symmetric and does not return.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include "bodies/generators.hpp"
#include "solver/explicit_solver.hpp"

namespace uhpc::macro {
namespace {

constexpr double kRho = 2500.0, kK = 20e9, kG = 15e9;
constexpr double kH = 0.01;

ExplicitSolver make_free_body(const SolverOptions& options, double speed) {
  const ParticleBody body = box_body(8 * kH, 6 * kH, 5 * kH, kH);
  ExplicitSolver solver(Particles::from_body(body, kRho, options.support_factor),
                        make_material_set(ElasticMaterial(ElasticParams{kRho, kK, kG}), body.size()), options);
  // An arbitrary velocity field: a drift, a spin and random particle velocities.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  set_initial_velocity(solver.particles(), [&](const double* x) -> Vec3 {
    return {speed * (0.3 + u(rng)) + 40.0 * (x[1] - 0.03), speed * u(rng) - 40.0 * (x[0] - 0.04),
            speed * (u(rng) - 0.2)};
  });
  solver.initialize();
  return solver;
}

std::array<double, 3> angular_momentum(const Particles& p) {
  std::array<double, 3> l{};
  for (std::size_t i = 0; i < p.n; ++i) {
    const double* x = p.x.data() + 3 * i;
    const double* v = p.v.data() + 3 * i;
    l[0] += p.mass[i] * (x[1] * v[2] - x[2] * v[1]);
    l[1] += p.mass[i] * (x[2] * v[0] - x[0] * v[2]);
    l[2] += p.mass[i] * (x[0] * v[1] - x[1] * v[0]);
  }
  return l;
}

double norm(const std::array<double, 3>& a) { return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

const char* name(StrainConfiguration c) {
  return c == StrainConfiguration::Midpoint ? "midpoint" : c == StrainConfiguration::End ? "end" : "endpoint average";
}

SolverOptions with_strain(StrainConfiguration c) {
  SolverOptions o;
  o.strain_configuration = c;
  return o;
}

void keeps_linear_and_angular_momentum(StrainConfiguration config) {
  ExplicitSolver solver = make_free_body(with_strain(config), 2.0);
  const Particles& p = solver.particles();
  double scale = 0.0, l_scale = 0.0;  // sum m |v| and sum m |x| |v|: the sizes round-off acts on
  for (std::size_t i = 0; i < p.n; ++i) {
    const double* v = p.v.data() + 3 * i;
    const double* x = p.x.data() + 3 * i;
    const double speed = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    scale += p.mass[i] * speed;
    l_scale += p.mass[i] * speed * std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
  }
  const std::array<double, 3> p0 = solver.ledger().momentum, l0 = angular_momentum(p);
  double worst_p = 0.0, worst_l = 0.0, worst_e = 0.0;
  for (int s = 0; s < 400; ++s) {
    ASSERT_TRUE(solver.step());
    const std::array<double, 3> p1 = solver.ledger().momentum, l1 = angular_momentum(p);
    worst_p = std::max(worst_p, norm({p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]}) / scale);
    worst_l = std::max(worst_l, norm({l1[0] - l0[0], l1[1] - l0[1], l1[2] - l0[2]}) / l_scale);
    worst_e = std::max(worst_e, std::fabs(solver.ledger().balance_error()) / solver.ledger().kinetic_initial);
  }
  std::printf("free body (%s strain), %zu particles, 400 steps: |dp| / sum m|v| = %.3e, |dL| / sum m|x||v| = %.3e, "
              "|p| / sum m|v| = %.3f, worst energy balance %.3e, quasi-linear points at the end %zu\n",
              name(config), p.n, worst_p, worst_l, norm(p0) / scale, worst_e,
              solver.shapes().count(rk::Path::QuasiLinear));
  EXPECT_LT(worst_p, 1e-13);
  EXPECT_LT(worst_l, 1e-12);
  // The random particle-scale velocities excite the highest frequencies of the body, where the
  // Verlet energy error (omega dt)^2 is largest; the next test checks that it is the integrator's.
  (void)worst_e;
}

TEST(MacroConservation, FreeBodyKeepsLinearAndAngularMomentum) {
  keeps_linear_and_angular_momentum(StrainConfiguration::Midpoint);
}
TEST(MacroConservation, FreeBodyKeepsLinearAndAngularMomentumWithEndpointAverageStrain) {
  keeps_linear_and_angular_momentum(StrainConfiguration::EndpointAverage);
}

// The energy balance error of a step is the integrator's (second order in dt): halving the CFL
// number divides the worst balance error by about four.
void energy_balance_error_is_second_order(StrainConfiguration config) {
  double worst[2] = {0.0, 0.0};
  const double cfl[2] = {0.4, 0.2};
  for (int k = 0; k < 2; ++k) {
    SolverOptions options = with_strain(config);
    options.cfl = cfl[k];
    ExplicitSolver solver = make_free_body(options, 2.0);
    while (solver.time() < 4e-4) {
      ASSERT_TRUE(solver.step());
      worst[k] = std::max(worst[k], std::fabs(solver.ledger().balance_error()) / solver.ledger().kinetic_initial);
    }
  }
  std::printf("free body with random velocities (%s strain), worst energy balance error: CFL 0.4 %.3e, CFL 0.2 "
              "%.3e (ratio %.2f)\n",
              name(config), worst[0], worst[1], worst[0] / worst[1]);
  EXPECT_GT(worst[0] / worst[1], 3.0);
  EXPECT_LT(worst[1], 0.01);
}

TEST(MacroConservation, EnergyBalanceErrorIsSecondOrderInDt) {
  energy_balance_error_is_second_order(StrainConfiguration::Midpoint);
}
TEST(MacroConservation, EnergyBalanceErrorIsSecondOrderInDtWithEndpointAverageStrain) {
  energy_balance_error_is_second_order(StrainConfiguration::EndpointAverage);
}

struct Reversal {
  double moved, dx, dv;  // largest excursion and return errors (|x - x0| / h, |v + v0| / max |v0|)
};

Reversal run_and_reverse(StrainConfiguration config) {
  SolverOptions options = with_strain(config);
  options.viscosity = BulkViscosity{0.0, 0.0};
  options.energy_error_limit = 0.0;  // off: End gains energy step after step (past 5 % by step 80)
  ExplicitSolver start = make_free_body(options, 20.0);
  const std::vector<double> x0 = start.particles().x, v0 = start.particles().v;
  // A constant step: the stable step of the body at rest.
  ExplicitSolver probe = make_free_body(options, 20.0);
  const double dt = probe.stable_dt();
  ExplicitSolver forward = make_free_body([&] { SolverOptions o = options; o.fixed_dt_s = dt; return o; }(), 20.0);
  const int steps = 600;
  for (int s = 0; s < steps; ++s) EXPECT_TRUE(forward.step());
  double moved = 0.0;
  for (std::size_t i = 0; i < x0.size(); ++i) moved = std::max(moved, std::fabs(forward.particles().x[i] - x0[i]));
  for (double& v : forward.particles().v) v = -v;
  for (int s = 0; s < steps; ++s) EXPECT_TRUE(forward.step());
  double dx = 0.0, dv = 0.0, vmax = 0.0;
  for (std::size_t i = 0; i < x0.size(); ++i) {
    dx = std::max(dx, std::fabs(forward.particles().x[i] - x0[i]));
    dv = std::max(dv, std::fabs(forward.particles().v[i] + v0[i]));
    vmax = std::max(vmax, std::fabs(v0[i]));
  }
  std::printf("reversibility (%s strain), %d + %d steps of %.3e s: largest displacement %.3e m (%.2f h); return "
              "error |x - x0| %.3e m (%.3e h), |v + v0| %.3e of max |v0|\n",
              name(config), steps, steps, dt, moved, moved / kH, dx, dx / kH, dv / vmax);
  return {moved / kH, dx / kH, dv / vmax};
}

TEST(MacroConservation, ElasticStepsAreReversible) {
  const Reversal r = run_and_reverse(StrainConfiguration::Midpoint);
  EXPECT_GT(r.moved, 0.3);  // a real excursion, not a few round-off steps
  EXPECT_LT(r.dx, 1e-11);
  EXPECT_LT(r.dv, 1e-9);
}

TEST(MacroConservation, ElasticStepsAreReversibleWithEndpointAverageStrain) {
  const Reversal r = run_and_reverse(StrainConfiguration::EndpointAverage);
  EXPECT_GT(r.moved, 0.3);
  EXPECT_LT(r.dx, 1e-11);
  EXPECT_LT(r.dv, 1e-9);
}

// Objectivity: a step that is an exact finite rotation (x_n+1 = R x_n, 0.02 rad) has zero strain. With
// linear reproduction the midpoint gradient is the Cayley form 2 (R - I)(R + I)^-1 / dt and the mean of
// the end gradients (R - R^T) / 2 dt, both skew; the end gradient (I - R^T) / dt is not.
TEST(MacroConservation, ARigidRotationStepLeavesNoStress) {
  const double dt = 1e-6, theta = 0.02;
  for (const StrainConfiguration config :
       {StrainConfiguration::Midpoint, StrainConfiguration::EndpointAverage, StrainConfiguration::End}) {
    SolverOptions options = with_strain(config);
    options.viscosity = BulkViscosity{0.0, 0.0};
    options.fixed_dt_s = dt;
    const ParticleBody body = box_body(5 * kH, 4 * kH, 3 * kH, kH);
    ExplicitSolver solver(Particles::from_body(body, kRho, options.support_factor),
                          make_material_set(ElasticMaterial(ElasticParams{kRho, kK, kG}), body.size()), options);
    set_initial_velocity(solver.particles(), [&](const double* x) -> Vec3 {
      const double X = x[0] - 2.5 * kH, Y = x[1] - 2 * kH;
      return {((std::cos(theta) - 1) * X - std::sin(theta) * Y) / dt,
              (std::sin(theta) * X + (std::cos(theta) - 1) * Y) / dt, 0.0};
    });
    solver.initialize();  // at rest: no stress, no acceleration, so the step drifts by exactly dt v
    ASSERT_TRUE(solver.step());
    double stress = 0.0;
    for (double s : solver.particles().stress) stress = std::max(stress, std::fabs(s));
    std::printf("rigid rotation step of %.2f rad (%s strain): max |stress| %.3e of G theta\n", theta, name(config),
                stress / (kG * theta));
    if (config == StrainConfiguration::End) EXPECT_GT(stress / (kG * theta), 1e-3);
    else EXPECT_LT(stress / (kG * theta), 1e-12);
  }
}

// The contrast: the end-of-step strain reads the configuration at one end of the step only, so the
// backward run does not retrace the forward one.
TEST(MacroConservation, EndOfStepStrainIsNotReversible) {
  const Reversal r = run_and_reverse(StrainConfiguration::End);
  EXPECT_GT(r.dx, 1e-6);
}

}  // namespace
}  // namespace uhpc::macro
