#include "solver/internal_force.hpp"

#include "solver/kinematics.hpp"
#include "solver/nsni_moment.hpp"
#include "solver/parallel.hpp"
#include "solver/row_simd.hpp"
#include "uhpc/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>


namespace uhpc::macro {

void InternalForce::compute(const ShapeCache& shapes, const double* stress, const double* bulk_q,
                            const double* volume, std::size_t n, double* f, const double* stress_grad,
                            double nsni_coefficient) {
  if (!shapes.has_second_gradients()) stress_grad = nullptr;
  const std::int64_t nn = static_cast<std::int64_t>(n);
#pragma omp parallel if (nn >= kParallelMinParticles)
  {
    double* buf = begin(n);
#pragma omp for schedule(static, kRowChunk)
    for (std::int64_t L = 0; L < nn; ++L) add_row(shapes, L, stress, bulk_q, volume, stress_grad, buf, nsni_coefficient);
    finish(n, f);
  }
}

double* InternalForce::begin(std::size_t n) {
#pragma omp single
  {
    if (buffers_.size() < static_cast<std::size_t>(team_size())) buffers_.resize(team_size());
    for (auto& b : buffers_)
      if (b.size() < 3 * n) b.resize(3 * n);
  }
  double* buf = buffers_[team_index()].data();
  std::fill(buf, buf + 3 * n, 0.0);
  return buf;
}

void InternalForce::add_row(const ShapeCache& shapes, std::int64_t L, const double* stress, const double* bulk_q,
                            const double* volume, const double* stress_grad, double* buf, double nsni_coefficient) {
  double s[9];
  const double q = bulk_q ? bulk_q[L] : 0.0;
  for (int m = 0; m < 9; ++m) s[m] = volume[L] * stress[9 * L + m];
  for (int d = 0; d < 3; ++d) s[4 * d] -= volume[L] * q;
  const std::int32_t* row = shapes.row_nodes(L);
  const std::int64_t b = shapes.row_begin(L), count = shapes.row_size(L);
  if (shapes.fragment(L)) return;  // a fragment carries no internal force (ShapeCache::fragment)
  if (!stress_grad) {
    row_internal_force(row, count, shapes.grad.data() + 3 * b, nullptr, s, nullptr, buf);
    return;
  }
  // tg[j][m] = M_L * sum over the pairs (d, k) with sym_index m of dsigma_jk/dx_d: Psi^(dk) is
  // symmetric in (d, k), so the off-diagonal pairs add up.
  const double moment = nsni_moment(volume[L], nsni_coefficient);
  const double* sg = stress_grad + 27 * L;
  double tg[3][6];
  for (int j = 0; j < 3; ++j) {
    for (int m = 0; m < 6; ++m) tg[j][m] = 0.0;
    for (int d = 0; d < 3; ++d)
      for (int c = 0; c < 3; ++c) tg[j][sym_index(d, c)] += moment * sg[9 * d + 3 * j + c];
  }
  // One pass over the row: each node appears once in it, so every buffer entry still receives the
  // nodal-integration term and then the NSNI term of this L, as with two passes.
  row_internal_force(row, count, shapes.grad.data() + 3 * b, shapes.hess.data() + 6 * b, s, &tg[0][0], buf);
}

void InternalForce::finish(std::size_t n, double* f) {
  const int threads = team_size();
  const std::int64_t nn = static_cast<std::int64_t>(n);
#pragma omp barrier
  // (every buffer complete before the sum)
#pragma omp for schedule(static)
  for (std::int64_t i = 0; i < 3 * nn; ++i) {
    double sum = 0.0;
    for (int u = 0; u < threads; ++u) sum += buffers_[u][i];
    f[i] = sum;
  }
}

}  // namespace uhpc::macro
