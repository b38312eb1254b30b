#pragma once
// Velocity gradient of every particle from the RK implicit gradients of the shape table:
//   L_I = sum_J v_J (x) grad Psi_J(x_I),   L_ij = dv_i/dx_j.
// The implicit gradients sum to zero, so v_I is subtracted first: the sum is then of differences and
// a rigid translation gives L = 0 to round-off whatever the speed.
#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "solver/row_simd.hpp"
#include "solver/second_gradients.hpp"
#include "solver/shape_cache.hpp"

namespace uhpc::macro {

// L (9n, row-major) from the velocities v (3n) with the gradients of `shapes` (built at the n particles).
void velocity_gradient(const ShapeCache& shapes, const double* v, std::size_t n, double* L);

// NSNI: the gradient of the velocity gradient from the implicit second derivatives of `shapes`
// (built with second gradients): G[27 i + 9 d + 3 a + b] = d L_ab / d x_d = sum_J v_Ja Psi^(db)_J(x_i).
void velocity_gradient_gradient(const ShapeCache& shapes, const double* v, std::size_t n, double* G);

// Both in one pass over each row (one read of the indices and of v_J); G may be null (L only).
void velocity_gradients(const ShapeCache& shapes, const double* v, std::size_t n, double* L, double* G);

// L_i (9) and, with hess non-null, G_i (27) of point i from its row: the `count` nodes `row`, their
// gradients grad (3 per node) and second derivatives hess (6 per node). Every sum runs over the row
// in order, so all the routines above (and ShapeCache::rebuild's) give bitwise the same values. Zero
// for a fragment (ShapeCache::fragment: it moves as a rigid body).
inline void point_velocity_gradients(bool fragment, const std::int32_t* row, std::int64_t count,
                                     const double* grad, const double* hess, const double* v, std::int64_t i,
                                     double* L, double* G) {
  if (fragment) {
    if (L) std::fill(L, L + 9, 0.0);
    if (G) std::fill(G, G + 27, 0.0);
    return;
  }
  row_velocity_gradients(row, count, grad, G ? hess : nullptr, v, i, L, G);  // (row_simd.hpp)
}

}  // namespace uhpc::macro
