// Unit checks of the macro solver core at a fixed configuration: the RK velocity gradient reproduces
// affine fields; nodal-integration forces sum to zero (linear momentum) and have zero moment (angular
// momentum); a uniform stress gives zero force at interior particles of a regular lattice (the force
// half of the linear patch test); a rigid motion creates no strain rate.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "bodies/generators.hpp"
#include "solver/internal_force.hpp"
#include "solver/nsni_moment.hpp"
#include "solver/kinematics.hpp"
#include "solver/particles.hpp"
#include "solver/shape_cache.hpp"

namespace uhpc::macro {
namespace {

struct Cloud {
  Particles p;
  ShapeCache shapes;
};

// A 6 x 5 x 4 box of spacing 1 cm, optionally with particles moved randomly by up to `jitter` h.
Cloud make_cloud(double jitter) {
  const double h = 0.01;
  Cloud c{Particles::from_body(box_body(6 * h, 5 * h, 4 * h, h), 1000.0, 2.0), {}};
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (double& x : c.p.x) x += jitter * h * u(rng);
  c.shapes.rebuild(rk::Options{}, c.p.x.data(), c.p.support.data(), c.p.n);
  return c;
}

TEST(MacroKinematics, VelocityGradientOfAnAffineFieldIsExactEverywhere) {
  Cloud c = make_cloud(0.2);
  const double A[9] = {1.0, -2.0, 0.5, 3.0, 0.25, -1.0, 0.7, 0.1, -0.4};
  const double v0[3] = {5.0, -3.0, 2.0};
  for (std::size_t i = 0; i < c.p.n; ++i)
    for (int r = 0; r < 3; ++r) {
      double s = v0[r];
      for (int k = 0; k < 3; ++k) s += A[3 * r + k] * c.p.x[3 * i + k];
      c.p.v[3 * i + r] = s;
    }
  velocity_gradient(c.shapes, c.p.v.data(), c.p.n, c.p.vel_grad.data());
  double worst = 0.0;
  for (std::size_t i = 0; i < c.p.n; ++i)
    for (int m = 0; m < 9; ++m) worst = std::max(worst, std::fabs(c.p.vel_grad[9 * i + m] - A[m]));
  std::printf("affine velocity field, jittered cloud of %zu: worst |L - A| = %.3e (quasi-linear points: %zu)\n",
              c.p.n, worst, c.shapes.count(rk::Path::QuasiLinear));
  EXPECT_EQ(c.shapes.count(rk::Path::QuasiLinear), 0u);  // a sound box: every point on the full path
  EXPECT_LT(worst, 1e-11);
}

TEST(MacroKinematics, RigidMotionHasNoStrainRate) {
  Cloud c = make_cloud(0.2);
  const double w[3] = {30.0, -20.0, 10.0}, t[3] = {100.0, 50.0, -70.0};
  for (std::size_t i = 0; i < c.p.n; ++i) {
    const double* x = c.p.x.data() + 3 * i;
    c.p.v[3 * i + 0] = t[0] + w[1] * x[2] - w[2] * x[1];
    c.p.v[3 * i + 1] = t[1] + w[2] * x[0] - w[0] * x[2];
    c.p.v[3 * i + 2] = t[2] + w[0] * x[1] - w[1] * x[0];
  }
  velocity_gradient(c.shapes, c.p.v.data(), c.p.n, c.p.vel_grad.data());
  double worst = 0.0;
  for (std::size_t i = 0; i < c.p.n; ++i)
    for (int r = 0; r < 3; ++r)
      for (int k = 0; k < 3; ++k)
        worst = std::max(worst, std::fabs(0.5 * (c.p.vel_grad[9 * i + 3 * r + k] + c.p.vel_grad[9 * i + 3 * k + r])));
  EXPECT_LT(worst, 1e-10);  // |L| = 30 1/s
}

TEST(MacroInternalForce, ArbitrarySymmetricStressGivesZeroNetForceAndMoment) {
  Cloud c = make_cloud(0.3);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1e8, 1e8);
  for (std::size_t i = 0; i < c.p.n; ++i)
    for (int r = 0; r < 3; ++r)
      for (int k = r; k < 3; ++k) c.p.stress[9 * i + 3 * r + k] = c.p.stress[9 * i + 3 * k + r] = u(rng);
  for (std::size_t i = 0; i < c.p.n; ++i) c.p.bulk_q[i] = 0.1 * u(rng);
  InternalForce force;
  force.compute(c.shapes, c.p.stress.data(), c.p.bulk_q.data(), c.p.volume.data(), c.p.n, c.p.f_int.data());
  double sum[3] = {0, 0, 0}, moment[3] = {0, 0, 0}, scale = 0.0;
  for (std::size_t i = 0; i < c.p.n; ++i) {
    const double* f = c.p.f_int.data() + 3 * i;
    const double* x = c.p.x.data() + 3 * i;
    for (int d = 0; d < 3; ++d) {
      sum[d] += f[d];
      scale += std::fabs(f[d]);
    }
    moment[0] += x[1] * f[2] - x[2] * f[1];
    moment[1] += x[2] * f[0] - x[0] * f[2];
    moment[2] += x[0] * f[1] - x[1] * f[0];
  }
  const double net = std::sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]) / scale;
  const double torque = std::sqrt(moment[0] * moment[0] + moment[1] * moment[1] + moment[2] * moment[2]) / (0.06 * scale);
  std::printf("random stress field: |sum f| / sum |f| = %.3e, |sum x x f| / (L sum |f|) = %.3e\n", net, torque);
  EXPECT_LT(net, 1e-14);
  EXPECT_LT(torque, 1e-13);
}

TEST(MacroInternalForce, UniformStressLeavesInteriorOfRegularLatticeUnloaded) {
  // Force half of the linear patch test. On a regular lattice the particles two supports away from
  // the surface see a symmetric neighbourhood, and sum_L V_L grad Psi_I(x_L) = 0 there, so a uniform
  // stress produces no force. (On irregular clouds direct nodal integration does not satisfy this
  // integration constraint exactly; that is a known limit of the scheme, not tested here.)
  const double h = 0.01;
  Cloud c{Particles::from_body(box_body(10 * h, 10 * h, 10 * h, h), 1000.0, 2.0), {}};
  c.shapes.rebuild(rk::Options{}, c.p.x.data(), c.p.support.data(), c.p.n);
  const double s[9] = {1e6, 2e5, -3e5, 2e5, -4e5, 1e5, -3e5, 1e5, 7e5};
  for (std::size_t i = 0; i < c.p.n; ++i)
    for (int m = 0; m < 9; ++m) c.p.stress[9 * i + m] = s[m];
  InternalForce force;
  force.compute(c.shapes, c.p.stress.data(), nullptr, c.p.volume.data(), c.p.n, c.p.f_int.data());
  const double f_scale = 1e6 * h * h;  // |sigma| times a particle face
  double worst_interior = 0.0;
  for (std::size_t i = 0; i < c.p.n; ++i) {
    const double* x = c.p.x.data() + 3 * i;
    bool interior = true;
    for (int d = 0; d < 3; ++d) interior = interior && x[d] > 4 * h && x[d] < 6 * h;
    const double f = std::sqrt(c.p.f_int[3 * i] * c.p.f_int[3 * i] + c.p.f_int[3 * i + 1] * c.p.f_int[3 * i + 1] +
                               c.p.f_int[3 * i + 2] * c.p.f_int[3 * i + 2]) / f_scale;
    if (interior) worst_interior = std::max(worst_interior, f);
  }
  std::printf("uniform stress, 10^3 lattice: interior |f| / (sigma h^2) = %.3e\n", worst_interior);
  EXPECT_LT(worst_interior, 1e-12);
}

// The NSNI coefficient c scales the moments M_L = c V^(5/3) / 12 and nothing else: with no stress and a
// stress gradient only, the force is linear in c.
TEST(MacroInternalForce, TheNsniForceScalesWithTheCoefficient) {
  const double h = 0.01;
  Particles p = Particles::from_body(box_body(6 * h, 6 * h, 6 * h, h), 1000.0, 2.5);
  std::mt19937 rng(45);
  std::uniform_real_distribution<double> u(-1e8, 1e8);
  std::vector<double> grad(27 * p.n);
  for (double& g : grad) g = u(rng);
  std::fill(p.stress.begin(), p.stress.end(), 0.0);
  ShapeCache shapes;
  const SecondGradientOptions second;
  shapes.rebuild(rk::Options{}, p.x.data(), p.support.data(), p.n, &second);
  std::vector<double> f1(3 * p.n), fc(3 * p.n);
  InternalForce force;
  force.compute(shapes, p.stress.data(), nullptr, p.volume.data(), p.n, f1.data(), grad.data(), 1.0);
  force.compute(shapes, p.stress.data(), nullptr, p.volume.data(), p.n, fc.data(), grad.data(), 0.3);
  double worst = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < f1.size(); ++i) {
    worst = std::max(worst, std::fabs(fc[i] - 0.3 * f1[i]));
    scale = std::max(scale, std::fabs(f1[i]));
  }
  ASSERT_GT(scale, 0.0);
  EXPECT_LT(worst / scale, 1e-14);
  EXPECT_DOUBLE_EQ(nsni_moment(8.0, 0.3), 0.3 * 32.0 / 12.0);  // 8^(5/3) = 32
}

// A body above the solver's parallel threshold: forces on 1 and 2 threads (per-thread buffers summed)
// agree to round-off.
TEST(MacroInternalForce, OneAndTwoThreadsAgree) {
#ifdef _OPENMP
  const double h = 0.01;
  Particles p = Particles::from_body(box_body(17 * h, 16 * h, 16 * h, h), 1000.0, 2.0);
  ASSERT_GE(p.n, 4096u);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1e6, 1e6);
  for (double& s : p.stress) s = u(rng);
  ShapeCache shapes;
  shapes.rebuild(rk::Options{}, p.x.data(), p.support.data(), p.n);
  std::vector<double> f1(3 * p.n), f2(3 * p.n);
  InternalForce force;
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  force.compute(shapes, p.stress.data(), nullptr, p.volume.data(), p.n, f1.data());
  omp_set_num_threads(2);
  force.compute(shapes, p.stress.data(), nullptr, p.volume.data(), p.n, f2.data());
  omp_set_num_threads(saved);
  double worst = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < f1.size(); ++i) {
    worst = std::max(worst, std::fabs(f1[i] - f2[i]));
    scale = std::max(scale, std::fabs(f1[i]));
  }
  EXPECT_LT(worst / scale, 1e-13);
#else
  GTEST_SKIP() << "built without OpenMP";
#endif
}

}  // namespace
}  // namespace uhpc::macro
