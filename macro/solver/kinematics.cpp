#include "solver/kinematics.hpp"
#include "solver/parallel.hpp"

#include <cstdint>

namespace uhpc::macro {

namespace {
// L and/or G (either may be null) of every point, one pass over each row.
void gradients_of_rows(const ShapeCache& shapes, const double* v, std::size_t n, double* L, double* G) {
  const std::int64_t nn = static_cast<std::int64_t>(n);
  const double* hess = G ? shapes.hess.data() : nullptr;
#pragma omp parallel for schedule(static, kRowChunk) if (nn >= kParallelMinParticles)
  for (std::int64_t i = 0; i < nn; ++i) {
    const std::int64_t b = shapes.row_begin(i);
    point_velocity_gradients(shapes.fragment(i), shapes.row_nodes(i), shapes.row_size(i), shapes.grad.data() + 3 * b,
                             hess ? hess + 6 * b : nullptr, v, i, L ? L + 9 * i : nullptr, G ? G + 27 * i : nullptr);
  }
}
}  // namespace

void velocity_gradient(const ShapeCache& shapes, const double* v, std::size_t n, double* L) {
  gradients_of_rows(shapes, v, n, L, nullptr);
}

void velocity_gradient_gradient(const ShapeCache& shapes, const double* v, std::size_t n, double* G) {
  gradients_of_rows(shapes, v, n, nullptr, G);
}

void velocity_gradients(const ShapeCache& shapes, const double* v, std::size_t n, double* L, double* G) {
  gradients_of_rows(shapes, v, n, L, G);
}

}  // namespace uhpc::macro
