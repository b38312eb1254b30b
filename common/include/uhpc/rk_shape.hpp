#pragma once
// Reproducing kernel (RK) shape functions in 2D and 3D (docs/physics.md section 2, eqs. 28-30):
//
//   Psi_I(x) = H^T((x - x_I)/h) b(x) phi_a(x - x_I),   M(x) b(x) = H(0),
//   M(x) = sum_I H((x - x_I)/h) H^T((x - x_I)/h) phi_a(x - x_I),
//
// with a linear (or quadratic) basis H that is shifted to x and scaled by h (the largest support radius
// among the point's nodes) so that M stays well conditioned whatever the units.
//
// Gradients are implicit (synchronized) RK gradients: Psi^i_I = H^T b^i phi_a with M b^i = -(1/h) e_i,
// e_i the entry of the linear monomial in direction i. One Cholesky factorization of M gives the shape
// functions and all first derivatives; no kernel derivative is needed. They reproduce the gradients of
// the basis exactly (sum_I Psi^i_I x_Ij = delta_ij, sum_I Psi^i_I = 0), which is what the Galerkin and
// nodal-integration schemes need; they are not the derivatives of Psi_I, only consistent with them.
//
// Ill-conditioned moment matrices (a point near a free surface, a fragment with few or aligned
// particles) are detected with the reciprocal condition number of the scaled M, and handled by one of:
//   QuasiLinear   (default; after Yreux and Chen's quasi-linear RK) regularise the non-constant block
//                 of M only: the eigenvalues of its Schur complement (the weighted second moment of the
//                 node positions) below ql_regularization * its largest eigenvalue are lifted to that
//                 floor. Partition of unity and the zero gradient of a constant stay exact (row 0 of
//                 M b = H(0) is untouched); linear reproduction is relaxed only in the directions
//                 where the nodes cannot support it (across a line of nodes, out of a plane).
//   OrderFallback lower the basis order (quadratic -> linear -> constant, i.e. Shepard functions),
//                 which also keeps partition of unity exact.
// The result of every evaluation says which path was taken.
#include <cstdint>
#include <string>
#include <vector>

#include "uhpc/kernels.hpp"
#include "uhpc/neighbour_search.hpp"

namespace uhpc::rk {

enum class Basis : std::uint8_t { Constant = 0, Linear = 1, Quadratic = 2 };
enum class IllConditioning : std::uint8_t { QuasiLinear, OrderFallback };
// Implicit: the synchronized gradients above (one solve, no kernel derivative). Direct: the exact
// derivatives of Psi_I, d/dx_i [H^T(y_I) b(x) phi_a(x - x_I)] with d b = -M^-1 (dM) b, which obey the
// divergence theorem (integral of grad Psi_I over a domain = boundary integral of Psi_I n) up to
// quadrature error only. Direct applies where M is well conditioned (Path::Full, any basis); the
// quasi-linear path keeps implicit gradients (the lifted moments have no derivative of their own) and
// Shepard functions always use direct ones.
enum class Derivatives : std::uint8_t { Implicit, Direct };

struct Options {
  KernelType kernel = KernelType::CubicBSpline;
  Basis basis = Basis::Linear;
  IllConditioning ill_conditioning = IllConditioning::QuasiLinear;
  // The neighbourhood counts as ill conditioned below this reciprocal condition number (1-norm
  // estimate) of S, the weighted covariance of the scaled basis (see rk_shape.cpp). Irregular but
  // sound clouds give 0.3 (linear) and 2e-3 (quadratic) at worst, corners included; a point 0.04
  // supports off a line of nodes gives 2e-5 and shape functions of magnitude 10.
  double rcond_min = 1e-4;
  // Floor of the quasi-linear path, relative to the largest eigenvalue of S: it bounds how far the
  // shape functions extrapolate across a line (plane) of nodes.
  double ql_regularization = 1e-2;
  bool gradients = true;
  Derivatives derivatives = Derivatives::Implicit;
};

// How one point was evaluated.
enum class Path : std::uint8_t {
  Full = 0,         // the requested basis, M well conditioned
  QuasiLinear = 1,  // the requested basis with the regularised moment matrix
  Fallback = 2,     // a lower-order basis (see PointResult::basis)
  Empty = 3,        // no node covers the point: all Psi are zero, nothing is reproduced
};

struct PointResult {
  Path path = Path::Empty;
  Basis basis = Basis::Constant;  // the basis actually used
  double rcond = 0.0;             // reciprocal condition estimate of the scaled M that was factorized
};

std::string path_name(Path path);
std::string basis_name(Basis basis);
Basis basis_from_name(const std::string& name);  // "constant" | "linear" | "quadratic"
Derivatives derivatives_from_name(const std::string& name);  // "implicit" | "direct"
std::string derivatives_name(Derivatives d);

// Number of monomials of the basis in Dim dimensions (3/6 in 2D, 4/10 in 3D for linear/quadratic).
constexpr int basis_size(int dim, Basis basis) {
  return basis == Basis::Constant ? 1 : basis == Basis::Linear ? dim + 1 : (dim + 1) * (dim + 2) / 2;
}

// Shape functions at one point x for the nodes nbr[0..n): node k is at nodes[nbr[k]*Dim ..] with
// support radius support_radius[nbr[k]]. Writes psi[k] and, when options.gradients, grad[k*Dim + i]
// = dPsi_k/dx_i. Allocation-free: safe in parallel loops. Nodes whose support does not cover x get 0.
template <int Dim>
PointResult evaluate(const Options& options, const double* x, const double* nodes, const double* support_radius,
                     const std::int32_t* nbr, int n, double* psi, double* grad);

// Shape functions of many points at once, in compressed rows matching a NeighbourList.
struct ShapeTable {
  NeighbourList support;          // support.row(p): nodes of point p
  std::vector<double> psi;        // one per (point, node) entry of support
  std::vector<double> grad;       // Dim per entry (empty without gradients)
  std::vector<PointResult> info;  // one per point
  int dim = 0;

  std::size_t count(Path path) const;
};

// Evaluates at every query point (OpenMP over points) with the nodes that cover it (nodes_covering).
template <int Dim>
ShapeTable build_shape_table(const Options& options, const double* queries, std::size_t n_queries,
                             const double* nodes, const double* support_radius, std::size_t n_nodes);

}  // namespace uhpc::rk
