#include "uhpc/neighbour_search.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace uhpc {

template <int Dim>
CellGrid<Dim>::CellGrid(const double* points, std::size_t n, double cell_size) : points_(points), cell_(cell_size) {
  if (!(cell_size > 0.0) || !std::isfinite(cell_size)) throw std::invalid_argument("CellGrid: cell size must be > 0");
  if (n > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
    throw std::invalid_argument("CellGrid: more points than 32-bit indices allow");
  if (n == 0) return;

  std::array<double, Dim> lo, hi;
  lo.fill(std::numeric_limits<double>::infinity());
  hi.fill(-std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < n; ++i)
    for (int d = 0; d < Dim; ++d) {
      const double v = points[i * Dim + d];
      if (!std::isfinite(v)) throw std::invalid_argument("CellGrid: non-finite point coordinate");
      lo[d] = std::min(lo[d], v);
      hi[d] = std::max(hi[d], v);
    }

  // Enlarge the cells of a sparse cloud so that the grid stays O(n) in memory.
  const double max_cells = kMaxCellsPerPoint * static_cast<double>(n) + 64.0;
  for (;;) {
    double cells = 1.0;
    for (int d = 0; d < Dim; ++d) {
      dims_[d] = static_cast<std::int64_t>(std::floor((hi[d] - lo[d]) / cell_)) + 1;
      cells *= static_cast<double>(dims_[d]);
    }
    if (cells <= max_cells) break;
    cell_ *= 1.5;
  }
  origin_ = lo;

  std::int64_t cells = 1;
  for (int d = 0; d < Dim; ++d) cells *= dims_[d];
  std::vector<std::int64_t> cell_of(n);
  cell_start_.assign(static_cast<std::size_t>(cells) + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    std::int64_t c = 0, stride = 1;
    for (int d = 0; d < Dim; ++d) {
      std::int64_t k = static_cast<std::int64_t>(std::floor((points[i * Dim + d] - origin_[d]) / cell_));
      k = std::clamp<std::int64_t>(k, 0, dims_[d] - 1);
      c += k * stride;
      stride *= dims_[d];
    }
    cell_of[i] = c;
    ++cell_start_[c + 1];
  }
  for (std::int64_t c = 0; c < cells; ++c) cell_start_[c + 1] += cell_start_[c];
  sorted_.resize(n);
  std::vector<std::int64_t> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (std::size_t i = 0; i < n; ++i) sorted_[fill[cell_of[i]]++] = static_cast<std::int32_t>(i);
}

namespace {

// Cell edge relative to the search radius (see the header).
constexpr double kCellFraction = 0.5;

// One pass: each thread searches a contiguous block of queries into its own buffer, then the blocks
// are copied into place. The result is one contiguous array built without locks, and identical
// whatever the thread count (rows are sorted).
template <class Visit>
NeighbourList build_rows(std::size_t n_queries, Visit&& visit) {
  NeighbourList out;
  out.offsets.assign(n_queries + 1, 0);
  const std::int64_t nq = static_cast<std::int64_t>(n_queries);
  std::vector<std::vector<std::int32_t>> blocks;
  std::vector<std::int64_t> block_begin;
#pragma omp parallel
  {
#ifdef _OPENMP
    const int threads = omp_get_num_threads(), t = omp_get_thread_num();
#else
    const int threads = 1, t = 0;
#endif
#pragma omp single
    {
      blocks.resize(threads);
      block_begin.resize(threads + 1);
    }
    const std::int64_t first = nq * t / threads, last = nq * (t + 1) / threads;
    std::vector<std::int32_t>& buffer = blocks[t];
    for (std::int64_t i = first; i < last; ++i) {
      const std::size_t start = buffer.size();
      visit(static_cast<std::size_t>(i), [&](std::int32_t j) { buffer.push_back(j); });
      std::sort(buffer.begin() + static_cast<std::ptrdiff_t>(start), buffer.end());
      out.offsets[i + 1] = static_cast<std::int64_t>(buffer.size() - start);
    }
#pragma omp barrier
#pragma omp single
    {
      for (std::int64_t i = 0; i < nq; ++i) out.offsets[i + 1] += out.offsets[i];
      out.indices.resize(static_cast<std::size_t>(out.offsets[nq]));
    }
    std::copy(buffer.begin(), buffer.end(), out.indices.begin() + out.offsets[first]);
  }
  return out;
}

}  // namespace

template <int Dim>
NeighbourList neighbours_within(const double* queries, std::size_t n_queries, const double* points,
                                std::size_t n_points, double radius) {
  const CellGrid<Dim> grid(points, n_points, kCellFraction * radius);
  return build_rows(n_queries, [&](std::size_t i, auto&& emit) {
    grid.for_each_within(queries + i * Dim, radius, [&](std::int32_t j, double) { emit(j); });
  });
}

template <int Dim>
NeighbourList nodes_covering(const double* queries, std::size_t n_queries, const double* nodes,
                             const double* support_radius, std::size_t n_nodes) {
  double a_max = 0.0;
  for (std::size_t j = 0; j < n_nodes; ++j) {
    if (!(support_radius[j] > 0.0)) throw std::invalid_argument("nodes_covering: support radius must be > 0");
    a_max = std::max(a_max, support_radius[j]);
  }
  if (n_nodes == 0) return build_rows(n_queries, [](std::size_t, auto&&) {});
  const CellGrid<Dim> grid(nodes, n_nodes, kCellFraction * a_max);
  return build_rows(n_queries, [&](std::size_t i, auto&& emit) {
    grid.for_each_covering(queries + i * Dim, support_radius, a_max, [&](std::int32_t j, double) { emit(j); });
  });
}

template class CellGrid<2>;
template class CellGrid<3>;
template NeighbourList neighbours_within<2>(const double*, std::size_t, const double*, std::size_t, double);
template NeighbourList neighbours_within<3>(const double*, std::size_t, const double*, std::size_t, double);
template NeighbourList nodes_covering<2>(const double*, std::size_t, const double*, const double*, std::size_t);
template NeighbourList nodes_covering<3>(const double*, std::size_t, const double*, const double*, std::size_t);

}  // namespace uhpc
