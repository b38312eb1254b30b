#pragma once
// The per-row loops over neighbours of the step (velocity gradients, internal force), written so that
// the compiler vectorises them, and compiled twice: for AVX2 and for the baseline x86-64 (SSE2), the
// clone picked once at load time (GCC target_clones). Results are bitwise those of the plain scalar
// loops: every sum still runs over the row in order (lanes are the independent accumulators, or the
// independent entries of the force row), and neither clone may contract a*b + c into an FMA (avx2
// alone does not enable FMA, and the file is built with -ffp-contract=off).
#include <cstdint>

namespace uhpc::macro {

// L_i (9, may be null) and, with hess non-null, G_i (27) of point i from its row: the `count` nodes
// `row`, their gradients grad (3 per node), second derivatives hess (6 per node) and velocities v:
//   L_rc = sum_J (v_J - v_i)_r dPsi_J/dx_c,   G[9 d + 3 a + c] = sum_J (v_J - v_i)_a Psi^(sym(d, c))_J.
void row_velocity_gradients(const std::int32_t* row, std::int64_t count, const double* grad, const double* hess,
                            const double* v, std::int64_t i, double* L, double* G);

// Nodal-integration force of one integration point onto its row: buf_J -= s grad Psi_J for every node
// J (s: 9, row-major, V (sigma - q I)); with hess non-null then buf_Jj -= sum_m tg[6 j + m] Psi^(m)_J
// (the NSNI term, tg: 18). Each node appears once in a row, so the entries are independent.
void row_internal_force(const std::int32_t* row, std::int64_t count, const double* grad, const double* hess,
                        const double* s, const double* tg, double* buf);

}  // namespace uhpc::macro
