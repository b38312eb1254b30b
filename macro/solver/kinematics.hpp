#pragma once
// Velocity gradient of every particle from the RK implicit gradients of the shape table:
//   L_I = sum_J v_J (x) grad Psi_J(x_I),   L_ij = dv_i/dx_j.
// The implicit gradients sum to zero, so v_I is subtracted first: the sum is then of differences and
// a rigid translation gives L = 0 to round-off whatever the speed.
#include <cstddef>
#include <cstdint>

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
// in order, so all the routines above (and ShapeCache::rebuild's) give bitwise the same values.
inline void point_velocity_gradients(const std::int32_t* row, std::int64_t count, const double* grad,
                                     const double* hess, const double* v, std::int64_t i, double* L, double* G) {
  double g[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  // t[a][m] = sum_J (v_J - v_I)_a Psi^(m)_J over the 6 symmetric pairs m; dv_a,c/dx_d = t[a][sym(d, c)]
  // (the same sums as accumulating the 27 entries directly, a third of the work).
  double t[3][6] = {};
  const double* vi = v + 3 * i;
  for (std::int64_t k = 0; k < count; ++k) {
    const double* vj = v + 3 * static_cast<std::int64_t>(row[k]);
    const double dv[3] = {vj[0] - vi[0], vj[1] - vi[1], vj[2] - vi[2]};  // sum_J grad Psi_J = 0, etc.
    const double* dpsi = grad + 3 * k;
    // Streaming a stored table (not a row just built) is bound by the loads of grad and hess: ask for
    // them 64 entries ahead (measured: +13 % on the paper disc; 32 or 128 ahead the same).
    __builtin_prefetch(grad + 3 * k + 192);
    if (hess) __builtin_prefetch(hess + 6 * k + 384);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) g[3 * r + c] += dv[r] * dpsi[c];
    if (hess) {
      const double* h2 = hess + 6 * k;
      for (int a = 0; a < 3; ++a)
        for (int m = 0; m < 6; ++m) t[a][m] += dv[a] * h2[m];
    }
  }
  if (L)
    for (int m = 0; m < 9; ++m) L[m] = g[m];
  if (G)
    for (int d = 0; d < 3; ++d)
      for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c) G[9 * d + 3 * a + c] = t[a][sym_index(d, c)];
}

}  // namespace uhpc::macro
