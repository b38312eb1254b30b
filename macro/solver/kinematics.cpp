#include "solver/kinematics.hpp"
#include "solver/parallel.hpp"

#include <cstdint>

namespace uhpc::macro {

void velocity_gradient(const ShapeCache& shapes, const double* v, std::size_t n, double* L) {
  const std::int64_t nn = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static) if (nn >= kParallelMinParticles)
  for (std::int64_t i = 0; i < nn; ++i) {
    double g[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
    const double* vi = v + 3 * i;
    const std::int32_t* row = shapes.support.row(i);
    const std::int64_t b = shapes.support.begin(i), count = shapes.support.count(i);
    for (std::int64_t k = 0; k < count; ++k) {
      const double* vj = v + 3 * static_cast<std::int64_t>(row[k]);
      const double* dpsi = shapes.grad.data() + 3 * (b + k);
      for (int r = 0; r < 3; ++r) {
        const double dv = vj[r] - vi[r];
        for (int c = 0; c < 3; ++c) g[3 * r + c] += dv * dpsi[c];
      }
    }
    for (int m = 0; m < 9; ++m) L[9 * i + m] = g[m];
  }
}

void velocity_gradient_gradient(const ShapeCache& shapes, const double* v, std::size_t n, double* G) {
  const std::int64_t nn = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static) if (nn >= kParallelMinParticles)
  for (std::int64_t i = 0; i < nn; ++i) {
    // t[a][m] = sum_J (v_J - v_I)_a Psi^(m)_J over the 6 symmetric pairs m; dv_a,c/dx_d = t[a][sym(d, c)]
    // (the same sums as accumulating the 27 entries directly, a third of the work).
    double t[3][6] = {};
    const double* vi = v + 3 * i;
    const std::int32_t* row = shapes.support.row(i);
    const std::int64_t b = shapes.support.begin(i), count = shapes.support.count(i);
    for (std::int64_t k = 0; k < count; ++k) {
      const double* vj = v + 3 * static_cast<std::int64_t>(row[k]);
      const double* h2 = shapes.hess.data() + 6 * (b + k);
      const double dv[3] = {vj[0] - vi[0], vj[1] - vi[1], vj[2] - vi[2]};  // sum_J Psi^(db)_J = 0
      for (int a = 0; a < 3; ++a)
        for (int m = 0; m < 6; ++m) t[a][m] += dv[a] * h2[m];
    }
    for (int d = 0; d < 3; ++d)
      for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c) G[27 * i + 9 * d + 3 * a + c] = t[a][sym_index(d, c)];
  }
}

}  // namespace uhpc::macro
