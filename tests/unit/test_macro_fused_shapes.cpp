// The fused evaluation of the shape cache (shape_and_second_gradients: RK shape functions, first
// gradients and NSNI second derivatives from one set of kernel weights and moments) against the two
// reference routines it replaces (rk::evaluate<3> and second_gradients), on a jittered cloud with free
// surfaces (full, quasi-linear and regularised points) and on a regular lattice, at supports 2.0 and
// 2.5 h. Differences must be round-off only.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "bodies/generators.hpp"
#include "solver/particles.hpp"
#include "solver/shape_cache.hpp"

namespace uhpc::macro {
namespace {

void compare(double support_factor, double jitter) {
  const double h = 0.01;
  Particles p = Particles::from_body(box_body(7 * h, 6 * h, 5 * h, h), 1000.0, support_factor);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-jitter, jitter);
  for (double& x : p.x) x += h * u(rng);
  ShapeCache shapes;
  const SecondGradientOptions second;
  const rk::Options options;
  shapes.rebuild(options, p.x.data(), p.support.data(), p.n, &second);
  double worst_psi = 0.0, worst_grad = 0.0, worst_hess = 0.0;
  std::size_t path_mismatch = 0;
  for (std::size_t L = 0; L < p.n; ++L) {
    const int n = static_cast<int>(shapes.support.count(L));
    const std::int64_t b = shapes.support.begin(L);
    std::vector<double> psi(n), grad(3 * n), hess(6 * n);
    const rk::PointResult r =
        rk::evaluate<3>(options, p.x.data() + 3 * L, p.x.data(), p.support.data(), shapes.support.row(L), n,
                        psi.data(), grad.data());
    const SecondGradientPath path =
        second_gradients(second, p.x.data() + 3 * L, p.x.data(), p.support.data(), shapes.support.row(L), n, hess.data());
    if (r.path != shapes.info[L].path || path != shapes.hess_path[L]) ++path_mismatch;
    for (int k = 0; k < n; ++k) {
      worst_psi = std::max(worst_psi, std::abs(psi[k] - shapes.psi[b + k]));
      for (int d = 0; d < 3; ++d) worst_grad = std::max(worst_grad, std::abs(grad[3 * k + d] - shapes.grad[3 * (b + k) + d]) * h);
      for (int m = 0; m < 6; ++m)
        worst_hess = std::max(worst_hess, std::abs(hess[6 * k + m] - shapes.hess[6 * (b + k) + m]) * h * h);
    }
  }
  std::printf("support %.1f h, jitter %.2f h: %zu points (%zu quasi-linear, %zu regularised), worst |dPsi| %.2e, "
              "|d grad| h %.2e, |d hess| h^2 %.2e\n",
              support_factor, jitter, p.n, shapes.count(rk::Path::QuasiLinear),
              shapes.count(SecondGradientPath::Regularized), worst_psi, worst_grad, worst_hess);
  EXPECT_EQ(path_mismatch, 0u);
  EXPECT_LT(worst_psi, 1e-12);
  EXPECT_LT(worst_grad, 1e-12);
  EXPECT_LT(worst_hess, 1e-10);

  // Without second derivatives: the linear-only path (shape_gradients) against rk::evaluate<3>.
  ShapeCache plain;
  plain.rebuild(options, p.x.data(), p.support.data(), p.n, nullptr);
  double worst_plain = 0.0;
  std::size_t plain_mismatch = 0;
  for (std::size_t L = 0; L < p.n; ++L) {
    const int n = static_cast<int>(plain.support.count(L));
    const std::int64_t b = plain.support.begin(L);
    std::vector<double> psi(n), grad(3 * n);
    const rk::PointResult r = rk::evaluate<3>(options, p.x.data() + 3 * L, p.x.data(), p.support.data(),
                                              plain.support.row(L), n, psi.data(), grad.data());
    if (r.path != plain.info[L].path) ++plain_mismatch;
    for (int k = 0; k < n; ++k) {
      worst_plain = std::max(worst_plain, std::abs(psi[k] - plain.psi[b + k]));
      for (int d = 0; d < 3; ++d)
        worst_plain = std::max(worst_plain, std::abs(grad[3 * k + d] - plain.grad[3 * (b + k) + d]) * h);
    }
  }
  std::printf("  linear only: worst |dPsi|, |d grad| h %.2e\n", worst_plain);
  EXPECT_EQ(plain_mismatch, 0u);
  EXPECT_LT(worst_plain, 1e-12);
}

TEST(MacroFusedShapes, MatchesTheReferenceRoutinesOnAJitteredCloud) {
  compare(2.0, 0.2);
  compare(2.5, 0.2);
}

TEST(MacroFusedShapes, MatchesTheReferenceRoutinesOnALattice) {
  compare(2.0, 0.0);
  compare(2.5, 0.0);
}

}  // namespace
}  // namespace uhpc::macro
