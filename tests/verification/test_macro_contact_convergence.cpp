// The sphere's contact on a strengthless target under refinement (docs/physics.md section 5.5): the
// resisting impulse M (v0 - v) of the 9.071 g sphere shot at 300 m/s into a free 54 x 54 x 9 mm block of
// an elastic fluid (the AFC bulk modulus, a shear modulus of 1 kPa: no strength), taken when the sphere's
// centre reaches the exit face, at spacings 3.0, 2.25 and 1.5 mm (18, 24 and 36 particles across, so the
// flight line passes between four columns at every spacing), for contact distances R + r_I with
// r_I = factor h_I. The sphere sweeps the
// particles whose centres lie within R + r_I of its line, a mass rho pi (R + factor h)^2 per unit of
// travel; only factor 0 sweeps its own cross-section at every spacing.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "bodies/generators.hpp"
#include "solver/explicit_solver.hpp"

namespace uhpc::macro {
namespace {

constexpr double kRho = 2555.7, kK = 2.20704e10;
constexpr double kMass = 9.071e-3, kRadius = 0.00635, kV0 = 300.0;
constexpr double kSide = 0.054, kThick = 0.009;

// What the block (thickness t) has taken from the sphere when the sphere's centre reaches depth `stop`.
struct Resistance {
  double impulse;        // M (v0 - v), N s
  double contact_share;  // the contact's dissipation over the sphere's lost kinetic energy
};

Resistance resistance(double h, double factor, double t = kThick, double stop = kThick,
                      ContactSurface surface = ContactSurface::Offset) {
  ParticleBody body = box_body(kSide, kSide, t, h);
  for (std::size_t i = 0; i < body.size(); ++i) {
    body.position[3 * i] -= 0.5 * kSide;
    body.position[3 * i + 1] -= 0.5 * kSide;
  }
  SolverOptions o;
  o.support_factor = 2.5;
  ExplicitSolver s(Particles::from_body(body, kRho, o.support_factor),
                   make_material_set(ElasticMaterial(ElasticParams{kRho, kK, 1e3}), body.size()), o);
  RigidSphere sphere;
  sphere.mass_kg = kMass;
  sphere.radius_m = kRadius;
  sphere.x = {0.0, 0.0, -kRadius - 1e-4};
  sphere.v = {0.0, 0.0, kV0};
  sphere.contact.contact_radius_factor = factor;
  sphere.contact.surface = surface;
  s.set_sphere(sphere);
  s.initialize();
  while (s.time() < 2e-4) {
    if (!s.step()) {
      ADD_FAILURE() << "step failed at " << s.time() << " s: kind " << static_cast<int>(s.failure().kind) << ", particle "
                    << s.failure().particle << ", energy error " << s.failure().energy_error;
      return {std::nan(""), std::nan("")};
    }
    if (s.sphere().x[2] >= stop) break;
  }
  EXPECT_GE(s.sphere().x[2], stop) << "the sphere did not reach depth " << stop;
  const double v = s.sphere().v[2];
  return {kMass * (kV0 - v), s.ledger().contact / (0.5 * kMass * (kV0 * kV0 - v * v))};
}

// The observed order p of I(h) = I0 + C h^p through three spacings (unequal ratios): the root of
// (I1 - I2) / (I2 - I3) = (h1^p - h2^p) / (h2^p - h3^p), by bisection on (0.05, 8); NaN without one.
double observed_order(const double h[3], const double I[3]) {
  const double target = (I[0] - I[1]) / (I[1] - I[2]);
  const auto f = [&](double p) {
    return (std::pow(h[0], p) - std::pow(h[1], p)) / (std::pow(h[1], p) - std::pow(h[2], p)) - target;
  };
  double lo = 0.05, hi = 8.0;
  if (f(lo) * f(hi) > 0) return std::nan("");
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (f(lo) * f(mid) <= 0 ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(MacroContactConvergence, TheImpulseOnAStrengthlessTargetUnderRefinement) {
  // Measured (docs/studies/2026-12-06-slow-sphere.md): the impulse falls under refinement for every
  // contact distance (0.85 / 0.45 / 0.32 N s with h / 2), because at 3 mm the 9 mm block is three layers
  // pushed as a plug and the flow around the sphere is not resolved (R / h = 2.1); the contact distance
  // moves it by a fifth at every spacing, so it is not what makes the resistance depend on the spacing.
  // Checked: each factor's impulse falls monotonically with an observed order >= 1, and the centres-on-
  // surface contact (factor 0) resists 10-40 % less than h / 2 at every spacing (measured 20-21 %).
  const double h[3] = {0.003, 0.00225, 0.0015};
  double I_half[3] = {}, I_zero[3] = {};
  for (const double factor : {0.5, 0.0}) {
    double* I = factor > 0 ? I_half : I_zero;
    double share[3] = {};
    for (int k = 0; k < 3; ++k) {
      const Resistance r = resistance(h[k], factor);
      I[k] = r.impulse;
      share[k] = r.contact_share;
    }
    const double p = observed_order(h, I);
    std::printf("contact radius %.2f h: impulse %.5f / %.5f / %.5f N s at 3.0 / 2.25 / 1.5 mm (spread %.1f %%), "
                "observed order %.2f; contact's share of the lost energy %.4f / %.4f / %.4f\n",
                factor, I[0], I[1], I[2], 100.0 * (std::max({I[0], I[1], I[2]}) - std::min({I[0], I[1], I[2]})) / I[2], p,
                share[0], share[1], share[2]);
    EXPECT_GT(I[0], I[1]);
    EXPECT_GT(I[1], I[2]);
    EXPECT_GE(p, 1.0);
  }
  for (int k = 0; k < 3; ++k) {
    const double less = 1.0 - I_zero[k] / I_half[k];
    std::printf("spacing %.2f mm: factor 0 resists %.1f %% less than h / 2\n", 1e3 * h[k], 100.0 * less);
    EXPECT_GT(less, 0.10) << "spacing " << h[k];
    EXPECT_LT(less, 0.40) << "spacing " << h[k];
  }
}

// The study behind docs/studies/2026-12-07-contact-refinement.md (not a check: run with
// --gtest_also_run_disabled_tests): a block three times as thick (27 mm), so that no spacing pushes it
// as a plug, the impulse taken when the sphere's centre is one radius deep, at 3.0 / 2.25 / 1.5 mm for both
// factors and 1.125 mm for h / 2. Finer than that the elastic fluid (it holds tension and has no shear to
// stabilize) breaks the energy check before that depth: at 1.125 mm with factor 0 at 36 us, at 0.75 mm
// with h / 2 at 25 us.
TEST(MacroContactConvergence, DISABLED_StudyThickBlock) {
  for (const double factor : {0.5, 0.0}) {
    for (const double hk : {0.003, 0.00225, 0.0015, 0.001125}) {
      if (factor == 0.0 && hk < 0.0015) continue;
      const Resistance r = resistance(hk, factor, 3.0 * kThick, kRadius);
      std::printf("contact radius %.2f h, spacing %.3f mm: impulse %.5f N s, contact's share %.4f\n", factor,
                  1e3 * hk, r.impulse, r.contact_share);
      std::fflush(stdout);
    }
  }
}

// The leading surface (h / 2 ahead, R across the motion) on the thin and the thick block, for the study.
TEST(MacroContactConvergence, DISABLED_StudyLeadingSurface) {
  for (const double t : {kThick, 3.0 * kThick}) {
    for (const double hk : {0.003, 0.00225, 0.0015, 0.001125}) {
      if (t == kThick && hk < 0.0015) continue;
      const Resistance r = resistance(hk, 0.5, t, t == kThick ? kThick : kRadius, ContactSurface::Leading);
      std::printf("leading surface, block %.0f mm, spacing %.3f mm: impulse %.5f N s, contact's share %.4f\n", 1e3 * t,
                  1e3 * hk, r.impulse, r.contact_share);
      std::fflush(stdout);
    }
  }
}

}  // namespace
}  // namespace uhpc::macro
