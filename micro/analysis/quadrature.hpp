#pragma once
// Quadrature rules for the Galerkin integrals: symmetric Gauss rules on triangles (Dunavant) for the
// domain, Gauss-Legendre on segments for the boundary. RK shape functions are rational functions with
// a piecewise-cubic kernel whose support boundaries cut through the triangles, so no rule integrates
// B^T D B exactly: the rule only sets the accuracy, while the linear patch test is restored exactly
// by the variationally consistent correction (vci.hpp). Degree 4 (6 points) is the default: the
// supports span about four triangles, so a triangle sees a smooth part of each kernel, and the
// 12-point rule changes E0_bar by less than 1e-3 (tests/verification/test_micro_elastic_cell.cpp).
#include <array>
#include <vector>

namespace uhpc::micro {

struct TrianglePoint {
  std::array<double, 3> barycentric;
  double weight;  // fraction of the triangle area; the weights of a rule sum to 1
};

// Rules by point count: 1 (degree 1), 3 (degree 2), 6 (degree 4), 7 (degree 5), 12 (degree 6).
// Throws std::invalid_argument for another count.
const std::vector<TrianglePoint>& triangle_rule(int points);
int triangle_rule_degree(int points);
bool is_triangle_rule(int points);

struct LinePoint {
  double t;       // position on [0, 1]
  double weight;  // fraction of the segment length; sums to 1
};

// Gauss-Legendre with 1..5 points (exact to degree 2n - 1). Throws std::invalid_argument otherwise.
const std::vector<LinePoint>& line_rule(int points);

}  // namespace uhpc::micro
