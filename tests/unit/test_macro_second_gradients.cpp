// Implicit second derivatives of the RK shape functions (NSNI strain gradients, macro solver):
// exact second derivatives of quadratic fields where the quadratic fit is well posed, and, at every
// point including the regularised surface ones, zero second derivatives of constant and linear
// fields (the property that keeps rigid motions and momentum out of the stabilization).
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "bodies/generators.hpp"
#include "solver/particles.hpp"
#include "solver/second_gradients.hpp"
#include "solver/shape_cache.hpp"

namespace uhpc::macro {
namespace {

TEST(MacroSecondGradients, QuadraticsExactInsideLinearsZeroEverywhere) {
  const double h = 0.01;
  Particles p = Particles::from_body(box_body(7 * h, 6 * h, 6 * h, h), 1000.0, 2.0);
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  for (double& x : p.x) x += h * u(rng);  // an irregular cloud
  ShapeCache shapes;
  const SecondGradientOptions second;
  shapes.rebuild(rk::Options{}, p.x.data(), p.support.data(), p.n, &second);

  // q(x) = (x - x_L)^T A (x - x_L) / 2 about each point (the constant and linear parts are checked
  // separately below, and adding them would only add round-off): d2q/dx_i dx_j = A_ij.
  const double A[3][3] = {{2.0, -1.0, 0.5}, {-1.0, 3.0, 0.25}, {0.5, 0.25, -1.5}};
  auto q = [&](const double* x, const double* xl) {
    double s = 0.0;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) s += 0.5 * A[i][j] * (x[i] - xl[i]) * (x[j] - xl[j]);
    return s;
  };
  const int pair_i[6] = {0, 1, 2, 1, 0, 0}, pair_j[6] = {0, 1, 2, 2, 2, 1};
  double worst_quadratic = 0.0, worst_linear = 0.0;
  std::size_t full = 0;
  for (std::size_t L = 0; L < p.n; ++L) {
    const std::int32_t* row = shapes.support.row(L);
    const std::int64_t b = shapes.support.begin(L), count = shapes.support.count(L);
    for (int m = 0; m < 6; ++m) {
      double sq = 0.0, s1 = 0.0, sx[3] = {0, 0, 0}, scale = 0.0;
      for (std::int64_t k = 0; k < count; ++k) {
        const double psi = shapes.hess[6 * (b + k) + m];
        const double* xj = p.x.data() + 3 * static_cast<std::size_t>(row[k]);
        sq += psi * q(xj, p.x.data() + 3 * L);
        s1 += psi;
        for (int d = 0; d < 3; ++d) sx[d] += psi * (xj[d] - p.x[3 * L + d]);
        scale += std::fabs(psi);
      }
      // Zero second derivative of 1 and x (relative to sum |Psi| and sum |Psi| h).
      worst_linear = std::max(worst_linear, std::fabs(s1) / scale);
      for (int d = 0; d < 3; ++d) worst_linear = std::max(worst_linear, std::fabs(sx[d]) / (scale * h));
      if (shapes.hess_path[L] == SecondGradientPath::Full)
        worst_quadratic = std::max(worst_quadratic, std::fabs(sq - A[pair_i[m]][pair_j[m]]) / 3.0);
    }
    full += shapes.hess_path[L] == SecondGradientPath::Full ? 1 : 0;
  }
  std::printf("second gradients, jittered %zu-particle box: full path at %zu points; worst quadratic error %.2e "
              "(relative to |A|), worst linear defect %.2e\n", p.n, full, worst_quadratic, worst_linear);
  EXPECT_GT(full, p.n / 5);
  EXPECT_LT(worst_quadratic, 1e-10);
  EXPECT_LT(worst_linear, 1e-12);
}

// Fragments: a particle left with one to three points in its support, or with points that a linear
// field fits exactly, has no second derivatives (zeros, path Empty), never NaN or round-off blown up
// to 1/(eps h^2) (found on the paper's shots, where ejecta particles stopped the run).
TEST(MacroSecondGradients, FragmentsGetNoneRatherThanNaN) {
  const SecondGradientOptions options;
  for (double r : {3e-3, 5e-3, 7.2e-3, 7.499e-3}) {  // support 7.5 mm
    for (int k = 0; k <= 3; ++k) {
      std::vector<double> nodes = {0.0, 0.0, 0.0};
      for (int j = 0; j < k; ++j) {
        const double th = 2.1 * j + 0.3, ph = 0.7 * j + 0.2;
        nodes.insert(nodes.end(), {r * std::sin(ph) * std::cos(th), r * std::sin(ph) * std::sin(th), r * std::cos(ph)});
      }
      const int n = k + 1;
      std::vector<double> support(static_cast<std::size_t>(n), 7.5e-3);
      std::vector<std::int32_t> nbr(static_cast<std::size_t>(n));
      for (int j = 0; j < n; ++j) nbr[static_cast<std::size_t>(j)] = j;
      std::vector<double> hess(6 * static_cast<std::size_t>(n), 1.0);
      EXPECT_EQ(second_gradients(options, nodes.data(), nodes.data(), support.data(), nbr.data(), n, hess.data()),
                SecondGradientPath::Empty)
          << "r " << r << ", " << k << " neighbours";
      for (double v : hess) EXPECT_EQ(v, 0.0);
    }
  }
}

}  // namespace
}  // namespace uhpc::macro
