// RK shape functions: the reproducing conditions (partition of unity, linear or quadratic reproduction,
// gradient reproduction) on random irregular clouds in 2D and 3D, at interior and boundary points, and
// the quasi-linear / fallback paths on degenerate neighbourhoods.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <vector>

#include "uhpc/rk_shape.hpp"

namespace rk = uhpc::rk;

namespace {

constexpr double kTol = 1e-10;

// A jittered lattice on the unit square/cube with spacing s and supports drawn at random from
// [lo, hi] x s (1.5..2.0 for a linear basis; a quadratic basis needs about 2.5..3.0 to have enough
// nodes at the corners of the cloud).
template <int Dim>
struct Cloud {
  std::vector<double> x, a;
  double s;
  std::size_t size() const { return a.size(); }
};

template <int Dim>
Cloud<Dim> irregular_cloud(int per_side, std::uint32_t seed, double lo = 1.5, double hi = 2.0) {
  Cloud<Dim> c;
  c.s = 1.0 / (per_side - 1);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3), support(lo, hi);
  const int total = Dim == 2 ? per_side * per_side : per_side * per_side * per_side;
  for (int n = 0; n < total; ++n) {
    int idx[3] = {n % per_side, (n / per_side) % per_side, n / (per_side * per_side)};
    for (int d = 0; d < Dim; ++d) {
      // Boundary nodes stay on the boundary so the cloud has a well-defined edge.
      const bool edge = idx[d] == 0 || idx[d] == per_side - 1;
      c.x.push_back(c.s * (idx[d] + (edge ? 0.0 : jitter(rng))));
    }
    c.a.push_back(support(rng) * c.s);
  }
  return c;
}

// Random interior points, points on faces, edges and corners of the cloud's box.
template <int Dim>
std::vector<double> evaluation_points(std::uint32_t seed, int n_random) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> q;
  for (int i = 0; i < n_random; ++i)
    for (int d = 0; d < Dim; ++d) q.push_back(u(rng));
  for (int corner = 0; corner < (1 << Dim); ++corner)
    for (int d = 0; d < Dim; ++d) q.push_back((corner >> d) & 1 ? 1.0 : 0.0);
  for (int i = 0; i < 20; ++i)
    for (int d = 0; d < Dim; ++d) q.push_back(d == i % Dim ? (i % 2 ? 1.0 : 0.0) : u(rng));
  return q;
}

// Monomials x^p for the reproduction checks: exponents per direction, total degree <= order.
template <int Dim>
std::vector<std::array<int, 3>> monomials(int order) {
  std::vector<std::array<int, 3>> out;
  for (int i = 0; i <= order; ++i)
    for (int j = 0; j <= order; ++j)
      for (int k = 0; k <= (Dim == 3 ? order : 0); ++k)
        if (i + j + k <= order) out.push_back({i, j, k});
  return out;
}

double monomial(const double* x, const std::array<int, 3>& p, int dim) {
  double v = 1.0;
  for (int d = 0; d < dim; ++d) v *= std::pow(x[d], p[d]);
  return v;
}

double monomial_derivative(const double* x, const std::array<int, 3>& p, int dim, int i) {
  if (p[i] == 0) return 0.0;
  double v = p[i];
  for (int d = 0; d < dim; ++d) v *= std::pow(x[d], d == i ? p[d] - 1 : p[d]);
  return v;
}

template <int Dim>
void expect_reproduction(rk::Basis basis, std::uint32_t seed, rk::Derivatives derivatives = rk::Derivatives::Implicit) {
  const bool quadratic = basis == rk::Basis::Quadratic;
  const Cloud<Dim> c = irregular_cloud<Dim>(Dim == 2 ? 21 : 9, seed, quadratic ? 2.5 : 1.5, quadratic ? 3.0 : 2.0);
  const std::vector<double> q = evaluation_points<Dim>(seed + 1, 200);
  const std::size_t nq = q.size() / Dim;
  rk::Options opt;
  opt.basis = basis;
  opt.derivatives = derivatives;
  const rk::ShapeTable t = rk::build_shape_table<Dim>(opt, q.data(), nq, c.x.data(), c.a.data(), c.size());
  ASSERT_EQ(t.count(rk::Path::Full), nq) << "every point of a regular-enough cloud takes the full path";

  const int order = static_cast<int>(basis);
  double worst = 0.0, worst_grad = 0.0;
  for (std::size_t p = 0; p < nq; ++p) {
    const double* xp = &q[p * Dim];
    ASSERT_GE(t.support.count(p), rk::basis_size(Dim, basis));
    for (const auto& m : monomials<Dim>(order)) {
      double value = 0.0, grad[Dim] = {};
      for (std::int64_t e = t.support.begin(p); e < t.support.end(p); ++e) {
        const double f = monomial(&c.x[static_cast<std::size_t>(t.support.indices[e]) * Dim], m, Dim);
        value += t.psi[e] * f;
        for (int i = 0; i < Dim; ++i) grad[i] += t.grad[e * Dim + i] * f;
      }
      worst = std::max(worst, std::abs(value - monomial(xp, m, Dim)));
      for (int i = 0; i < Dim; ++i)
        worst_grad = std::max(worst_grad, std::abs(grad[i] - monomial_derivative(xp, m, Dim, i)));
    }
  }
  std::printf("  %dD %s basis, %s gradients, %zu points: worst reproduction error %.2e, worst gradient error x "
              "spacing %.2e\n",
              Dim, rk::basis_name(basis).c_str(), rk::derivatives_name(derivatives).c_str(), nq, worst, worst_grad * c.s);
  EXPECT_LT(worst, kTol) << "worst reproduction error";
  // Gradients carry a factor 1/h (h ~ 2 spacings): compare on the scale of the function's variation.
  EXPECT_LT(worst_grad * c.s, kTol) << "worst gradient reproduction error " << worst_grad;
}

TEST(RKShape, Linear2DReproducesLinearFieldsAndGradients) { expect_reproduction<2>(rk::Basis::Linear, 1); }
TEST(RKShape, Linear3DReproducesLinearFieldsAndGradients) { expect_reproduction<3>(rk::Basis::Linear, 2); }
TEST(RKShape, Quadratic2DReproducesQuadraticFieldsAndGradients) { expect_reproduction<2>(rk::Basis::Quadratic, 3); }
TEST(RKShape, Quadratic3DReproducesQuadraticFieldsAndGradients) { expect_reproduction<3>(rk::Basis::Quadratic, 4); }

TEST(RKShape, DirectDerivatives2DReproduceLinearAndQuadraticGradients) {
  expect_reproduction<2>(rk::Basis::Linear, 11, rk::Derivatives::Direct);
  expect_reproduction<2>(rk::Basis::Quadratic, 12, rk::Derivatives::Direct);
}
TEST(RKShape, DirectDerivatives3DReproduceLinearGradients) {
  expect_reproduction<3>(rk::Basis::Linear, 13, rk::Derivatives::Direct);
}

// The direct derivatives are those of Psi_I itself: central differences of psi (step 1e-6 spacing,
// error O(step^2) plus round-off over step) agree to 1e-6 of the gradients' scale 1/spacing; the
// implicit gradients differ from them by O(1) of that scale on an irregular cloud.
TEST(RKShape, DirectDerivativesAreTheDerivativesOfTheShapeFunctions) {
  const Cloud<2> c = irregular_cloud<2>(11, 7);
  std::vector<std::int32_t> all(c.size());
  for (std::size_t i = 0; i < c.size(); ++i) all[i] = static_cast<std::int32_t>(i);
  const int n = static_cast<int>(all.size());
  rk::Options direct;
  direct.derivatives = rk::Derivatives::Direct;
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double worst = 0.0, implicit_gap = 0.0;
  for (int sample = 0; sample < 50; ++sample) {
    const double x[2] = {u(rng), u(rng)};
    std::vector<double> psi(n), grad(2 * n), implicit_grad(2 * n), plus(n), minus(n), unused(2 * n);
    ASSERT_EQ(rk::evaluate<2>(direct, x, c.x.data(), c.a.data(), all.data(), n, psi.data(), grad.data()).path,
              rk::Path::Full);
    rk::evaluate<2>(rk::Options{}, x, c.x.data(), c.a.data(), all.data(), n, psi.data(), implicit_grad.data());
    const double step = 1e-6 * c.s;
    for (int d = 0; d < 2; ++d) {
      double xp[2] = {x[0], x[1]}, xm[2] = {x[0], x[1]};
      xp[d] += step;
      xm[d] -= step;
      rk::evaluate<2>(direct, xp, c.x.data(), c.a.data(), all.data(), n, plus.data(), unused.data());
      rk::evaluate<2>(direct, xm, c.x.data(), c.a.data(), all.data(), n, minus.data(), unused.data());
      for (int k = 0; k < n; ++k) {
        const double fd = (plus[k] - minus[k]) / (2.0 * step);
        worst = std::max(worst, std::abs(grad[2 * k + d] - fd) * c.s);
        implicit_gap = std::max(implicit_gap, std::abs(implicit_grad[2 * k + d] - fd) * c.s);
      }
    }
  }
  std::printf("  direct - central difference: %.2e, implicit - central difference: %.2e (x spacing)\n", worst,
              implicit_gap);
  EXPECT_LT(worst, 1e-6);
  EXPECT_GT(implicit_gap, 1e-3) << "the check must be able to tell the two kinds of gradient apart";
}

TEST(RKShape, DerivativesNames) {
  EXPECT_EQ(rk::derivatives_from_name("direct"), rk::Derivatives::Direct);
  EXPECT_EQ(rk::derivatives_from_name("implicit"), rk::Derivatives::Implicit);
  EXPECT_EQ(rk::derivatives_name(rk::Derivatives::Direct), "direct");
  EXPECT_THROW(rk::derivatives_from_name("exact"), std::invalid_argument);
}

TEST(RKShape, ShapeFunctionsAreZeroOutsideTheirSupport) {
  const Cloud<2> c = irregular_cloud<2>(11, 5);
  const double x[2] = {0.37, 0.61};
  std::vector<std::int32_t> all(c.size());
  for (std::size_t i = 0; i < c.size(); ++i) all[i] = static_cast<std::int32_t>(i);
  std::vector<double> psi(c.size()), grad(2 * c.size());
  rk::evaluate<2>(rk::Options{}, x, c.x.data(), c.a.data(), all.data(), static_cast<int>(all.size()), psi.data(),
                  grad.data());
  for (std::size_t i = 0; i < c.size(); ++i) {
    const double r = std::hypot(x[0] - c.x[2 * i], x[1] - c.x[2 * i + 1]);
    if (r >= c.a[i]) {
      EXPECT_EQ(psi[i], 0.0);
      EXPECT_EQ(grad[2 * i], 0.0);
    }
  }
}

TEST(RKShape, UnitsDoNotMatterThanksToTheScaledBasis) {
  // The same cloud in metres and in micrometres gives the same shape functions.
  Cloud<3> c = irregular_cloud<3>(7, 6);
  const double x[3] = {0.41, 0.52, 0.33};
  std::vector<std::int32_t> all(c.size());
  for (std::size_t i = 0; i < c.size(); ++i) all[i] = static_cast<std::int32_t>(i);
  std::vector<double> psi(c.size()), grad(3 * c.size()), psi_um(c.size()), grad_um(3 * c.size());
  rk::evaluate<3>(rk::Options{}, x, c.x.data(), c.a.data(), all.data(), static_cast<int>(all.size()), psi.data(),
                  grad.data());
  const double k = 1e-6;
  for (double& v : c.x) v *= k;
  for (double& v : c.a) v *= k;
  const double x_um[3] = {x[0] * k, x[1] * k, x[2] * k};
  const auto r = rk::evaluate<3>(rk::Options{}, x_um, c.x.data(), c.a.data(), all.data(),
                                 static_cast<int>(all.size()), psi_um.data(), grad_um.data());
  EXPECT_EQ(r.path, rk::Path::Full);
  for (std::size_t i = 0; i < c.size(); ++i) {
    EXPECT_NEAR(psi_um[i], psi[i], 1e-12);
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(grad_um[3 * i + d] * k, grad[3 * i + d], 1e-10);
  }
}

// A near-degenerate neighbourhood: nodes (almost) on a line in 2D / a plane in 3D, so M has a
// (near-)zero eigenvalue in the transverse direction.
template <int Dim>
struct Degenerate {
  std::vector<double> x, a;
  std::vector<std::int32_t> nbr;
};

template <int Dim>
Degenerate<Dim> aligned_nodes(double transverse_offset) {
  Degenerate<Dim> g;
  int id = 0;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < (Dim == 3 ? 5 : 1); ++j) {
      const double off = (id % 3 == 1) ? transverse_offset : 0.0;
      g.x.push_back(0.1 * i);
      if (Dim == 3) {
        g.x.push_back(0.1 * j);
      }
      g.x.push_back(off);  // last coordinate: across the line / plane
      g.a.push_back(0.35);
      g.nbr.push_back(id++);
    }
  return g;
}

template <int Dim>
void expect_exact_partition_of_unity_on_degenerate(rk::IllConditioning how, rk::Basis basis, double offset,
                                                   rk::Path expected_path) {
  const Degenerate<Dim> g = aligned_nodes<Dim>(offset);
  rk::Options opt;
  opt.ill_conditioning = how;
  opt.basis = basis;
  const double x[3] = {0.17, 0.21, 0.013};  // slightly off the line / plane
  const int n = static_cast<int>(g.nbr.size());
  std::vector<double> psi(n), grad(n * Dim);
  const auto r = rk::evaluate<Dim>(opt, x, g.x.data(), g.a.data(), g.nbr.data(), n, psi.data(), grad.data());
  EXPECT_EQ(r.path, expected_path) << rk::path_name(r.path);
  double sum = 0.0, gsum[Dim] = {}, abs_sum = 0.0;
  for (int k = 0; k < n; ++k) {
    EXPECT_TRUE(std::isfinite(psi[k]));
    sum += psi[k];
    abs_sum += std::abs(psi[k]);
    for (int d = 0; d < Dim; ++d) gsum[d] += grad[k * Dim + d];
  }
  EXPECT_NEAR(sum, 1.0, 1e-14) << "partition of unity";
  for (int d = 0; d < Dim; ++d) EXPECT_NEAR(gsum[d], 0.0, 1e-11) << "gradient of a constant, direction " << d;
  EXPECT_LT(abs_sum, 10.0) << "bounded shape functions (no blow-up from a near-singular M)";
  // Reproduction along the line (direction 0) still holds on the quasi-linear path.
  if (how == rk::IllConditioning::QuasiLinear && basis == rk::Basis::Linear) {
    double lin = 0.0, dlin = 0.0;
    for (int k = 0; k < n; ++k) {
      lin += psi[k] * g.x[static_cast<std::size_t>(k) * Dim];
      dlin += grad[k * Dim] * g.x[static_cast<std::size_t>(k) * Dim];
    }
    EXPECT_NEAR(lin, x[0], 1e-3);
    EXPECT_NEAR(dlin, 1.0, 1e-2);
  }
}

TEST(RKShape, QuasiLinearKeepsPartitionOfUnityOnCollinearNodes2D) {
  expect_exact_partition_of_unity_on_degenerate<2>(rk::IllConditioning::QuasiLinear, rk::Basis::Linear, 0.0,
                                                   rk::Path::QuasiLinear);
}
TEST(RKShape, QuasiLinearKeepsPartitionOfUnityOnNearlyCollinearNodes2D) {
  expect_exact_partition_of_unity_on_degenerate<2>(rk::IllConditioning::QuasiLinear, rk::Basis::Linear, 1e-7,
                                                   rk::Path::QuasiLinear);
}
TEST(RKShape, QuasiLinearKeepsPartitionOfUnityOnNearlyCoplanarNodes3D) {
  expect_exact_partition_of_unity_on_degenerate<3>(rk::IllConditioning::QuasiLinear, rk::Basis::Linear, 1e-7,
                                                   rk::Path::QuasiLinear);
}
TEST(RKShape, QuasiLinearQuadraticOnCoplanarNodes3D) {
  expect_exact_partition_of_unity_on_degenerate<3>(rk::IllConditioning::QuasiLinear, rk::Basis::Quadratic, 0.0,
                                                   rk::Path::QuasiLinear);
}
TEST(RKShape, OrderFallbackKeepsPartitionOfUnityOnCollinearNodes2D) {
  expect_exact_partition_of_unity_on_degenerate<2>(rk::IllConditioning::OrderFallback, rk::Basis::Linear, 1e-9,
                                                   rk::Path::Fallback);
}
TEST(RKShape, OrderFallbackKeepsPartitionOfUnityOnCoplanarNodes3D) {
  expect_exact_partition_of_unity_on_degenerate<3>(rk::IllConditioning::OrderFallback, rk::Basis::Quadratic, 0.0,
                                                   rk::Path::Fallback);
}

TEST(RKShape, SingleNodeGivesUnitShapeFunction) {
  const double node[3] = {0.0, 0.0, 0.0}, a = 1.0, x[3] = {0.2, 0.1, -0.1};
  const std::int32_t nbr = 0;
  double psi = 0.0, grad[3] = {9, 9, 9};
  for (auto how : {rk::IllConditioning::QuasiLinear, rk::IllConditioning::OrderFallback}) {
    rk::Options opt;
    opt.ill_conditioning = how;
    const auto r = rk::evaluate<3>(opt, x, node, &a, &nbr, 1, &psi, grad);
    EXPECT_NE(r.path, rk::Path::Full);
    EXPECT_NEAR(psi, 1.0, 1e-14);
    for (double g : grad) EXPECT_NEAR(g, 0.0, 1e-12);
  }
}

TEST(RKShape, PointOutsideEverySupportIsFlaggedEmpty) {
  const double node[2] = {0.0, 0.0}, a = 1.0, x[2] = {2.0, 0.0};
  const std::int32_t nbr = 0;
  double psi = 7.0, grad[2] = {7.0, 7.0};
  const auto r = rk::evaluate<2>(rk::Options{}, x, node, &a, &nbr, 1, &psi, grad);
  EXPECT_EQ(r.path, rk::Path::Empty);
  EXPECT_EQ(psi, 0.0);
  EXPECT_EQ(grad[0], 0.0);
}

TEST(RKShape, NamesRoundTrip) {
  for (auto b : {rk::Basis::Constant, rk::Basis::Linear, rk::Basis::Quadratic})
    EXPECT_EQ(rk::basis_from_name(rk::basis_name(b)), b);
  EXPECT_EQ(rk::path_name(rk::Path::QuasiLinear), "quasi_linear");
  EXPECT_THROW(rk::basis_from_name("cubic"), std::invalid_argument);
}

}  // namespace
