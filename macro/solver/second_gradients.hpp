#pragma once
// Implicit second derivatives of RK shape functions, for the NSNI strain gradients (docs/physics.md
// section 5). With the quadratic basis H(y), y = (x - x_J)/h, shifted to x and scaled by h,
//   Psi^(ij)_J(x) = H^T(y_J) b^(ij) w_J,   M b^(ij) = r^(ij),
// where r^(ij) holds the second derivatives of the monomials at x: (delta_ai delta_bj + delta_aj
// delta_bi) / h^2 for y_a y_b, zero for 1 and y_a. Then sum_J Psi^(ij)_J p(x_J) = d2p/dx_i dx_j for
// every quadratic p: in particular sum_J Psi^(ij)_J = 0 and sum_J Psi^(ij)_J x_J = 0 (a stabilization
// force built on them conserves linear and angular momentum). No kernel derivative is needed.
// The linear part [1, y] is eliminated first (its moment block is the well-conditioned linear RK
// one): with M = [[Mpp, Mpq], [Mqp, Mqq]], the quadratic coefficients solve S c = r_q with
// S = Mqq - Mqp Mpp^-1 Mpq, and the linear ones follow from sum_J Psi^(ij)_J [1, x_J] = 0, which
// therefore holds to round-off whatever S is. Where S is ill conditioned (edges and corners see too
// few particles for a quadratic fit within two spacings) its small eigenvalues are lifted to
// `regularization` times the largest (the quasi-linear treatment of rk_shape, applied to the
// quadratic block): the second derivatives of quadratics are then only approximated there, but
// those of constant and linear fields stay exactly zero, so rigid motions never load the NSNI term.
//
// When to lift (`continuous_regularization`, default true): every eigenvalue below the floor is
// lifted, wherever it occurs, so S^-1 is bounded by 1 / (regularization lambda_max) and is a
// continuous function of the particle positions. The original criterion (false) lifted only when the
// condition estimate of S fell below rcond_min = 1e-4, i.e. a point with lambda_min between 1e-4 and
// 1e-2 of lambda_max kept the nearly singular S: its second derivatives grow like 1/lambda_min and
// the NSNI stiffness M_L B_d^T C B_d like their square. A surface particle pushed 0.05 h inward at
// support 2.0 h puts its neighbours in that band: the largest squared frequency of the body becomes
// 413 times that of plain nodal integration (which sets the critical step), so no CFL is stable and
// the run diverges (the "NSNI at 2.0 h" finding of macro/README.md;
// tests/verification/test_macro_nsni_surface_load.cpp).
#include <cstdint>

#include "uhpc/kernels.hpp"
#include "uhpc/rk_shape.hpp"

namespace uhpc::macro {

struct SecondGradientOptions {
  KernelType kernel = KernelType::CubicBSpline;
  double rcond_min = 1e-4;       // original criterion only: below this rcond of S, regularise
  double regularization = 1e-2;  // floor of the lifted eigenvalues, relative to the largest
  // true: lift every eigenvalue of S below the floor (continuous in the configuration; rcond_min unused).
  // false: the original criterion, regularise only when rcond(S) < rcond_min (see the header).
  bool continuous_regularization = true;
};

enum class SecondGradientPath : std::uint8_t { Full = 0, Regularized = 1, Empty = 2 };

// For the nodes nbr[0..n) of point x (node k at nodes[3 nbr[k]], support radius support[nbr[k]]):
// hess[6k + m] = Psi^(m)_k with m = xx, yy, zz, yz, xz, xy. Allocation-free.
SecondGradientPath second_gradients(const SecondGradientOptions& options, const double* x, const double* nodes,
                                    const double* support, const std::int32_t* nbr, int n, double* hess);

// The RK shape functions and first gradients (rk::evaluate<3>, linear basis) and the second
// derivatives above in one pass: one kernel evaluation and one set of moments per neighbour (the
// linear moment matrix is a block of the quadratic one). Same results as the two routines up to
// round-off; points where rk_shape leaves its full path (quasi-linear, fallback, empty), other bases,
// kernels or direct derivatives, and more than 512 nodes go through the two routines themselves. Allocation-free.
SecondGradientPath shape_and_second_gradients(const rk::Options& rk_options, const SecondGradientOptions& options,
                                              const double* x, const double* nodes, const double* support,
                                              const std::int32_t* nbr, int n, double* psi, double* grad,
                                              double* hess, rk::PointResult& result);

// rk::evaluate<3> for the linear basis, by the same code as above without the quadratic part (one
// kernel pass, moments as dot products, explicit 3 x 3 inverse); the same results up to round-off, the
// same fallbacks. Allocation-free.
rk::PointResult shape_gradients(const rk::Options& rk_options, const double* x, const double* nodes,
                                const double* support, const std::int32_t* nbr, int n, double* psi, double* grad);

// Index of the symmetric pair (i, j) in the 6-vector above.
constexpr int sym_index(int i, int j) {
  return i == j ? i : (i + j == 3 ? 3 : (i + j == 2 ? 4 : 5));  // (1,2)->3, (0,2)->4, (0,1)->5
}

}  // namespace uhpc::macro
