// Conservation and reversibility of the macro solver core on a free elastic body.
//  - Linear momentum: with no external force the total momentum may change only by round-off, since
//    the nodal-integration forces sum to zero at every step (RK implicit gradients sum to zero).
//  - Angular momentum: conserved too while every particle is on the full linear-basis path (linear
//    reproduction, symmetric stress): velocity Verlet conserves it exactly for such forces.
//  - Reversibility: with a constant step, no bulk viscosity and the mid-step strain configuration,
//    running N steps, negating the velocities and running N more returns to the start to round-off
//    (the symmetric Cayley rotation and the exponential volume update are exactly reversible).
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

TEST(MacroConservation, FreeBodyKeepsLinearAndAngularMomentum) {
  ExplicitSolver solver = make_free_body(SolverOptions{}, 2.0);
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
  std::printf("free body, %zu particles, 400 steps: |dp| / sum m|v| = %.3e, |dL| / sum m|x||v| = %.3e, "
              "|p| / sum m|v| = %.3f, worst energy balance %.3e, quasi-linear points at the end %zu\n",
              p.n, worst_p, worst_l, norm(p0) / scale, worst_e, solver.shapes().count(rk::Path::QuasiLinear));
  EXPECT_LT(worst_p, 1e-13);
  EXPECT_LT(worst_l, 1e-12);
  // The random particle-scale velocities excite the highest frequencies of the body, where the
  // Verlet energy error (omega dt)^2 is largest; the next test checks that it is the integrator's.
  (void)worst_e;
}

// The energy balance error of a step is the integrator's (second order in dt): halving the CFL
// number divides the worst balance error by about four.
TEST(MacroConservation, EnergyBalanceErrorIsSecondOrderInDt) {
  double worst[2] = {0.0, 0.0};
  const double cfl[2] = {0.4, 0.2};
  for (int k = 0; k < 2; ++k) {
    SolverOptions options;
    options.cfl = cfl[k];
    ExplicitSolver solver = make_free_body(options, 2.0);
    while (solver.time() < 4e-4) {
      ASSERT_TRUE(solver.step());
      worst[k] = std::max(worst[k], std::fabs(solver.ledger().balance_error()) / solver.ledger().kinetic_initial);
    }
  }
  std::printf("free body with random velocities, worst energy balance error: CFL 0.4 %.3e, CFL 0.2 %.3e (ratio %.2f)\n",
              worst[0], worst[1], worst[0] / worst[1]);
  EXPECT_GT(worst[0] / worst[1], 3.0);
  EXPECT_LT(worst[1], 0.01);
}

TEST(MacroConservation, ElasticStepsAreReversible) {
  SolverOptions options;
  options.viscosity = BulkViscosity{0.0, 0.0};
  options.strain_configuration = StrainConfiguration::Midpoint;
  ExplicitSolver start = make_free_body(options, 20.0);
  const std::vector<double> x0 = start.particles().x, v0 = start.particles().v;
  // A constant step: the stable step of the body at rest.
  ExplicitSolver probe = make_free_body(options, 20.0);
  const double dt = probe.stable_dt();
  ExplicitSolver forward = make_free_body([&] { SolverOptions o = options; o.fixed_dt_s = dt; return o; }(), 20.0);
  const int steps = 600;
  for (int s = 0; s < steps; ++s) ASSERT_TRUE(forward.step());
  double moved = 0.0;
  for (std::size_t i = 0; i < x0.size(); ++i) moved = std::max(moved, std::fabs(forward.particles().x[i] - x0[i]));
  for (double& v : forward.particles().v) v = -v;
  for (int s = 0; s < steps; ++s) ASSERT_TRUE(forward.step());
  double dx = 0.0, dv = 0.0, vmax = 0.0;
  for (std::size_t i = 0; i < x0.size(); ++i) {
    dx = std::max(dx, std::fabs(forward.particles().x[i] - x0[i]));
    dv = std::max(dv, std::fabs(forward.particles().v[i] + v0[i]));
    vmax = std::max(vmax, std::fabs(v0[i]));
  }
  std::printf("reversibility, %d + %d steps of %.3e s: largest displacement %.3e m (%.2f h); return error "
              "|x - x0| %.3e m (%.3e h), |v + v0| %.3e of max |v0|\n",
              steps, steps, dt, moved, moved / kH, dx, dx / kH, dv / vmax);
  EXPECT_GT(moved, 0.3 * kH);  // a real excursion, not a few round-off steps
  EXPECT_LT(dx / kH, 1e-11);
  EXPECT_LT(dv / vmax, 1e-9);
}

}  // namespace
}  // namespace uhpc::macro
