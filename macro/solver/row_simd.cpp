#include "solver/row_simd.hpp"

#include "solver/second_gradients.hpp"

// The lanes are the 3 components of a vector plus one unused lane (4 doubles: one AVX2 register, two
// SSE2 ones); each lane is one of the scalar loops' accumulators, summed over the row in its order.
// (The compiler's own vectoriser, tried first with `omp simd` lane loops, went through the stack for
// the velocity differences; the vector type keeps them in registers.)
#if defined(__GNUC__) && defined(__x86_64__) && !defined(__clang__)
#define UHPC_ROW_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define UHPC_ROW_CLONES
#endif

namespace uhpc::macro {

namespace {
// x, y, z and an unused lane (GCC/Clang vector extension; split into two SSE2 registers in the
// baseline clone). vector * scalar multiplies every lane by the scalar.
typedef double Lanes __attribute__((vector_size(32)));
}  // namespace

UHPC_ROW_CLONES
void row_velocity_gradients(const std::int32_t* __restrict row, std::int64_t count, const double* __restrict grad,
                            const double* __restrict hess, const double* __restrict v, std::int64_t i,
                            double* __restrict L, double* __restrict G) {
  // g[c][r] = sum_J dv_r dPsi_J/dx_c; t[m][a] = sum_J dv_a Psi^(m)_J.
  Lanes g[3] = {}, t[6] = {};
  const Lanes vi = {v[3 * i], v[3 * i + 1], v[3 * i + 2], 0.0};
  for (std::int64_t k = 0; k < count; ++k) {
    const double* vj = v + 3 * static_cast<std::int64_t>(row[k]);
    const Lanes dv = Lanes{vj[0], vj[1], vj[2], 0.0} - vi;  // sum_J grad Psi_J = 0, so differences
    const double* dpsi = grad + 3 * k;
    // Streaming a stored table is bound by the loads of grad and hess: ask for them 64 entries ahead
    // (measured: +13 % on the paper disc; 32 or 128 ahead the same).
    __builtin_prefetch(grad + 3 * k + 192);
    for (int c = 0; c < 3; ++c) g[c] += dv * dpsi[c];
    if (hess) {
      __builtin_prefetch(hess + 6 * k + 384);
      const double* h2 = hess + 6 * k;
      for (int m = 0; m < 6; ++m) t[m] += dv * h2[m];
    }
  }
  if (L)
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) L[3 * r + c] = g[c][r];
  if (G && hess)
    for (int d = 0; d < 3; ++d)  // dv_a,c/dx_d = t[sym(d, c)][a]
      for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c) G[9 * d + 3 * a + c] = t[sym_index(d, c)][a];
}

UHPC_ROW_CLONES
void row_internal_force(const std::int32_t* __restrict row, std::int64_t count, const double* __restrict grad,
                        const double* __restrict hess, const double* __restrict s, const double* __restrict tg,
                        double* __restrict buf) {
  // Columns of s (sc[c][r] = s[3 r + c]) and of tg (tc[m][j] = tg[6 j + m]) as lanes.
  const Lanes sc[3] = {{s[0], s[3], s[6], 0.0}, {s[1], s[4], s[7], 0.0}, {s[2], s[5], s[8], 0.0}};
  Lanes tc[6] = {};
  if (hess)
    for (int m = 0; m < 6; ++m) tc[m] = Lanes{tg[m], tg[6 + m], tg[12 + m], 0.0};
  for (std::int64_t k = 0; k < count; ++k) {
    const double* dpsi = grad + 3 * k;
    double* fi = buf + 3 * static_cast<std::int64_t>(row[k]);
    // f_r = (s_r0 dPsi_0 + s_r1 dPsi_1) + s_r2 dPsi_2, the scalar loop's order
    const Lanes f = sc[0] * dpsi[0] + sc[1] * dpsi[1] + sc[2] * dpsi[2];
    if (!hess) {
      for (int r = 0; r < 3; ++r) fi[r] -= f[r];
      continue;
    }
    const double* h2 = hess + 6 * k;
    Lanes h = Lanes{0.0, 0.0, 0.0, 0.0};  // h_j = sum_m tg_jm Psi^(m), summed from 0 in order of m
    for (int m = 0; m < 6; ++m) h += tc[m] * h2[m];
    for (int r = 0; r < 3; ++r) fi[r] = (fi[r] - f[r]) - h[r];
  }
}

}  // namespace uhpc::macro
