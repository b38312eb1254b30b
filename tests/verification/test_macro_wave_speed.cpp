// Elastic wave speed in a bar (macro solver core). A square bar along x is pushed at x = 0 with a step
// velocity v0 (the first layer of particles held at v0); the half-amplitude point of the front passes
// two stations at L/4 and 3L/4, and the measured speed is their distance over the time between.
// Timing between two stations removes the start-up delay of the front.
//
// Poisson's ratio is 0, so the bar is in uniaxial stress AND uniaxial strain at once: the slender-bar
// speed c0 = sqrt(E / rho) and the dilatational speed sqrt((K + 4G/3) / rho) coincide, and the answer
// does not depend on the bar's slenderness (with nu > 0 a bar of finite section is dispersive, and a
// 4-particle-wide bar would sit between the two speeds).
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "bodies/generators.hpp"
#include "solver/explicit_solver.hpp"

namespace uhpc::macro {
namespace {

constexpr double kE = 200e9, kRho = 7850.0;

double layer_velocity(const Particles& p, double x_ref, double h) {
  double sum = 0.0;
  int count = 0;
  for (std::size_t i = 0; i < p.n; ++i)
    if (std::fabs(p.x_prev[3 * i] - x_ref) < 0.5 * h) {  // layer picked by position (small strains)
      sum += p.v[3 * i];
      ++count;
    }
  return sum / count;
}

struct WaveResult {
  double speed, c0;
};

WaveResult measure(StrainConfiguration configuration, double h, double shape_reuse = 0.0) {
  const double length = 0.2, side = 4 * h;
  const ParticleBody body = box_body(length, side, side, h);
  ElasticParams ep{kRho, kE / 3.0, kE / 2.0};  // nu = 0: K = E/3, G = E/2
  SolverOptions options;
  options.strain_configuration = configuration;
  options.shape_reuse_tolerance = shape_reuse;
  ExplicitSolver solver(Particles::from_body(body, kRho, options.support_factor),
                        make_material_set(ElasticMaterial(ep), body.size()), options);
  const double v0 = 1.0;
  solver.add_prescribed_velocity(prescribe_velocity(solver.particles(), Region{{-1, -1, -1}, {h, 1, 1}}, {v0, 0, 0}));
  solver.initialize();

  const double c0 = std::sqrt(kE / kRho);
  // Station layers: the particle layer centres closest to L/4 and 3L/4.
  const double s1 = (std::floor(0.25 * length / h) + 0.5) * h, s2 = (std::floor(0.75 * length / h) + 0.5) * h;
  double t_cross[2] = {-1, -1};
  double prev[2] = {0, 0};
  double t_prev = 0.0;
  while (solver.time() < 1.0 * length / c0) {
    EXPECT_TRUE(solver.step());
    const double now[2] = {layer_velocity(solver.particles(), s1, h), layer_velocity(solver.particles(), s2, h)};
    for (int k = 0; k < 2; ++k)
      if (t_cross[k] < 0 && now[k] >= 0.5 * v0)
        t_cross[k] = t_prev + (solver.time() - t_prev) * (0.5 * v0 - prev[k]) / (now[k] - prev[k]);
    prev[0] = now[0];
    prev[1] = now[1];
    t_prev = solver.time();
  }
  EXPECT_GT(t_cross[0], 0.0);
  EXPECT_GT(t_cross[1], t_cross[0]);
  return {(s2 - s1) / (t_cross[1] - t_cross[0]), c0};
}

TEST(MacroWaveSpeed, BarFrontTravelsAtC0Within2Percent) {
  const WaveResult r = measure(StrainConfiguration::Midpoint, 2.5e-3);
  std::printf("wave speed (midpoint strain, h = 2.5 mm): measured %.2f m/s, c0 %.2f m/s, error %+.3f %%\n", r.speed,
              r.c0, 100.0 * (r.speed / r.c0 - 1.0));
  EXPECT_NEAR(r.speed / r.c0, 1.0, 0.02);
}

TEST(MacroWaveSpeed, EndOfStepStrainAlsoWithin2Percent) {
  const WaveResult r = measure(StrainConfiguration::End, 2.5e-3);
  std::printf("wave speed (end-of-step strain, h = 2.5 mm): measured %.2f m/s, c0 %.2f m/s, error %+.3f %%\n",
              r.speed, r.c0, 100.0 * (r.speed / r.c0 - 1.0));
  EXPECT_NEAR(r.speed / r.c0, 1.0, 0.02);
}

TEST(MacroWaveSpeed, EndpointAverageStrainAlsoWithin2Percent) {
  const WaveResult r = measure(StrainConfiguration::EndpointAverage, 2.5e-3);
  std::printf("wave speed (endpoint-average strain, h = 2.5 mm): measured %.2f m/s, c0 %.2f m/s, error %+.3f %%\n",
              r.speed, r.c0, 100.0 * (r.speed / r.c0 - 1.0));
  EXPECT_NEAR(r.speed / r.c0, 1.0, 0.02);
}

TEST(MacroWaveSpeed, EndpointAverageStrainWithLazyRowsAlsoWithin2Percent) {
  const WaveResult r = measure(StrainConfiguration::EndpointAverage, 2.5e-3, 3e-4);
  std::printf("wave speed (endpoint-average strain, lazy rows 3e-4, h = 2.5 mm): measured %.2f m/s, c0 %.2f m/s, "
              "error %+.3f %%\n", r.speed, r.c0, 100.0 * (r.speed / r.c0 - 1.0));
  EXPECT_NEAR(r.speed / r.c0, 1.0, 0.02);
}

}  // namespace
}  // namespace uhpc::macro
