// Quadrature rules and boundary segments of the microcell analysis (micro/analysis): every triangle
// rule integrates all monomials up to its degree exactly (and, for the check to be able to fail, not
// the next degree), Gauss-Legendre to degree 2n - 1; the boundary segments of a meshed cell cover the
// four edges and every pore, with outward normals.
#include <cmath>

#include <gtest/gtest.h>

#include "boundary_segments.hpp"
#include "cell_mesh.hpp"
#include "quadrature.hpp"

namespace uhpc::micro {
namespace {

// Integral of x^i y^j over the reference triangle (0,0), (1,0), (0,1): i! j! / (i + j + 2)!.
double exact_monomial(int i, int j) {
  return std::tgamma(i + 1.0) * std::tgamma(j + 1.0) / std::tgamma(i + j + 3.0);
}

double rule_monomial(const std::vector<TrianglePoint>& rule, int i, int j) {
  double s = 0.0;
  for (const TrianglePoint& p : rule) {
    const double x = p.barycentric[1], y = p.barycentric[2];
    s += 0.5 * p.weight * std::pow(x, i) * std::pow(y, j);  // reference area 1/2
  }
  return s;
}

TEST(microQuadrature, TriangleRulesAreExactToTheirDegree) {
  for (int n : {1, 3, 6, 7, 12}) {
    const std::vector<TrianglePoint>& rule = triangle_rule(n);
    ASSERT_EQ(rule.size(), static_cast<std::size_t>(n));
    const int degree = triangle_rule_degree(n);
    for (int total = 0; total <= degree; ++total)
      for (int i = 0; i <= total; ++i)
        EXPECT_NEAR(rule_monomial(rule, i, total - i), exact_monomial(i, total - i), 1e-14)
            << n << " points, x^" << i << " y^" << total - i;
    double worst = 0.0;  // degree + 1 is not exact for every monomial
    for (int i = 0; i <= degree + 1; ++i)
      worst = std::max(worst, std::abs(rule_monomial(rule, i, degree + 1 - i) - exact_monomial(i, degree + 1 - i)));
    EXPECT_GT(worst, 1e-8) << n << " points";
    for (const TrianglePoint& p : rule) {
      EXPECT_GT(p.weight, 0.0);
      EXPECT_NEAR(p.barycentric[0] + p.barycentric[1] + p.barycentric[2], 1.0, 1e-14);
    }
  }
  EXPECT_THROW(triangle_rule(4), std::invalid_argument);
  EXPECT_FALSE(is_triangle_rule(5));
}

TEST(microQuadrature, GaussLegendreIsExactToDegree2nMinus1) {
  for (int n = 1; n <= 5; ++n) {
    for (int k = 0; k <= 2 * n; ++k) {
      double s = 0.0;
      for (const LinePoint& p : line_rule(n)) s += p.weight * std::pow(p.t, k);
      if (k <= 2 * n - 1)
        EXPECT_NEAR(s, 1.0 / (k + 1.0), 1e-14) << n << " points, t^" << k;
      else
        EXPECT_GT(std::abs(s - 1.0 / (k + 1.0)), 1e-6) << n << " points, t^" << k;
    }
  }
  EXPECT_THROW(line_rule(6), std::invalid_argument);
}

TEST(microQuadrature, BoundarySegmentsCoverEdgesAndPoresWithOutwardNormals) {
  CellGeometry g;
  g.side_m = 1e-3;
  g.pores.push_back({{0.3e-3, 0.4e-3}, 0.2e-3});
  g.pores.push_back({{0.7e-3, 0.7e-3}, 0.1e-3});
  MeshOptions o;
  o.nominal_spacing_m = 0.5e-4;
  const CellDiscretization mesh = mesh_cell(g, o);
  const std::vector<BoundarySegment> segs = boundary_segments(mesh);
  double length[kBoundaryParts] = {0, 0, 0, 0, 0};
  std::vector<double> pore_length(2, 0.0);
  // Closed boundary: the normals weighted by the lengths sum to zero; each outer normal is the edge's.
  double nx = 0.0, ny = 0.0;
  const double outward[4][2] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}};
  for (const BoundarySegment& s : segs) {
    length[static_cast<int>(s.part)] += s.length_m;
    nx += s.normal[0] * s.length_m;
    ny += s.normal[1] * s.length_m;
    if (s.part == BoundaryPart::Pore) {
      pore_length[s.pore] += s.length_m;
      // Outward from the material = into the pore: towards the pore centre.
      const auto& a = mesh.nodes_m[s.nodes[0]];
      const Pore& p = g.pores[s.pore];
      EXPECT_GT(s.normal[0] * (p.center_m.x - a[0]) + s.normal[1] * (p.center_m.y - a[1]), 0.0);
    } else {
      const int e = static_cast<int>(s.part);
      EXPECT_NEAR(s.normal[0], outward[e][0], 1e-12);
      EXPECT_NEAR(s.normal[1], outward[e][1], 1e-12);
    }
  }
  for (int e = 0; e < 4; ++e) EXPECT_NEAR(length[e], g.side_m, 1e-15);
  for (std::size_t p = 0; p < 2; ++p) {
    // An inscribed polygon with N sides: N d sin(pi/N).
    const double n = static_cast<double>(mesh.pore_nodes[p].size());
    EXPECT_NEAR(pore_length[p], n * g.pores[p].diameter_m * std::sin(M_PI / n), 1e-12 * g.side_m);
  }
  EXPECT_NEAR(nx, 0.0, 1e-15);
  EXPECT_NEAR(ny, 0.0, 1e-15);
}

}  // namespace
}  // namespace uhpc::micro
