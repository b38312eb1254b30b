#pragma once
// A linear elastic boundary value problem on a discretized cell: per boundary part, each displacement
// component is either prescribed (a Dirichlet condition imposed weakly by Nitsche's method, because
// RK functions are not interpolating) or free with a given traction (zero if none is given), plus
// optional point constraints on one component (imposed by a penalty; they remove rigid translations).
//
// Nitsche's method (symmetric form), for the prescribed components P of a part Gamma_D:
//   a(u, v) - int_{Gamma_D} v . P t(u) - int_{Gamma_D} t(v) . P (u - g) + beta int_{Gamma_D} v . P (u - g)
//   = int_{Gamma_N} v . t_bar,          t(u) = sigma(u) n,   beta = nitsche_factor x E' / h,
// h the mean nodal spacing of the segment. Consistent (the exact solution satisfies it), symmetric,
// and coercive for a large enough factor; the reaction on Gamma_D is the consistent flux
// int P (t(u_h) - beta (u_h - g)) (elastic_solution.hpp).
#include <array>
#include <functional>
#include <vector>

#include "boundary_segments.hpp"
#include "plane_strain.hpp"

namespace uhpc::micro {

using Vec2Field = std::function<std::array<double, 2>(const double* x)>;
using TractionField = std::function<std::array<double, 2>(const double* x, const double* normal)>;

struct BoundaryCondition {
  std::array<bool, 2> prescribed{false, false};  // per component (x, y)
  Vec2Field displacement;                         // g(x), read for the prescribed components
  TractionField traction;                         // t_bar(x, n) for the free components; empty = free surface
};

struct PointConstraint {
  std::array<double, 2> x_m;
  int component = 1;
  double value_m = 0.0;
};

struct ElasticProblem {
  PlaneStrain material;
  std::array<BoundaryCondition, kBoundaryParts> boundary;  // by BoundaryPart
  std::vector<PointConstraint> points;
  double nitsche_factor = 100.0;  // [choice] beta = factor x E' / h (also the point penalty factor x E')
};

}  // namespace uhpc::micro
