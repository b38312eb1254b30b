#pragma once
// Velocity gradient of every particle from the RK implicit gradients of the shape table:
//   L_I = sum_J v_J (x) grad Psi_J(x_I),   L_ij = dv_i/dx_j.
// The implicit gradients sum to zero, so v_I is subtracted first: the sum is then of differences and
// a rigid translation gives L = 0 to round-off whatever the speed.
#include <cstddef>

#include "solver/shape_cache.hpp"

namespace uhpc::macro {

// L (9n, row-major) from the velocities v (3n) with the gradients of `shapes` (built at the n particles).
void velocity_gradient(const ShapeCache& shapes, const double* v, std::size_t n, double* L);

// NSNI: the gradient of the velocity gradient from the implicit second derivatives of `shapes`
// (built with second gradients): G[27 i + 9 d + 3 a + b] = d L_ab / d x_d = sum_J v_Ja Psi^(db)_J(x_i).
void velocity_gradient_gradient(const ShapeCache& shapes, const double* v, std::size_t n, double* G);

}  // namespace uhpc::macro
