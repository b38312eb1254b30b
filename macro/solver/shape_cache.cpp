#include "solver/shape_cache.hpp"
#include "solver/parallel.hpp"

#include <algorithm>
#include <cstdint>

namespace uhpc::macro {

namespace {
// Grow with headroom so that the slow drift of neighbour counts during a run does not reallocate.
void resize_with_headroom(std::vector<double>& v, std::size_t size) {
  if (v.capacity() < size) v.reserve(size + size / 5);
  v.resize(size);
}
}  // namespace

void ShapeCache::rebuild(const rk::Options& options, const double* x, const double* support_radius, std::size_t n,
                         const SecondGradientOptions* second) {
  nodes_covering<3>(x, n, x, support_radius, n, support, workspace);
  const std::size_t entries = support.indices.size();
  // The search sizes its lists exactly; give them (and its per-thread buffers) headroom so that the
  // slow growth of neighbour counts does not reallocate on the next steps.
  if (support.indices.capacity() < entries + entries / 10) support.indices.reserve(entries + entries / 4);
  for (auto& block : workspace.blocks)
    if (block.capacity() < block.size() + block.size() / 10) block.reserve(block.size() + block.size() / 4);
  resize_with_headroom(psi, entries);
  resize_with_headroom(grad, 3 * entries);
  info.resize(n);
  if (second) {
    resize_with_headroom(hess, 6 * entries);
    hess_path.resize(n);
  } else {
    hess.clear();
  }
  const std::int64_t nq = static_cast<std::int64_t>(n);
  rk::Options opt = options;
  opt.gradients = true;
#pragma omp parallel for schedule(dynamic, 128) if (nq >= kParallelMinParticles)
  for (std::int64_t p = 0; p < nq; ++p) {
    const std::int64_t b = support.begin(p);
    info[p] = rk::evaluate<3>(opt, x + 3 * p, x, support_radius, support.row(p), static_cast<int>(support.count(p)),
                              psi.data() + b, grad.data() + 3 * b);
    if (second)
      hess_path[p] = second_gradients(*second, x + 3 * p, x, support_radius, support.row(p),
                                      static_cast<int>(support.count(p)), hess.data() + 6 * b);
  }
}

std::size_t ShapeCache::count(rk::Path path) const {
  return static_cast<std::size_t>(
      std::count_if(info.begin(), info.end(), [path](const rk::PointResult& r) { return r.path == path; }));
}

std::size_t ShapeCache::count(SecondGradientPath path) const {
  if (hess.empty()) return 0;
  return static_cast<std::size_t>(std::count(hess_path.begin(), hess_path.end(), path));
}

}  // namespace uhpc::macro
