#include "uhpc/neighbour_search.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "uhpc/parallel.hpp"

namespace uhpc {

template <int Dim>
CellGrid<Dim>::CellGrid(const double* points, std::size_t n, double cell_size) {
  build(points, n, cell_size);
}

template <int Dim>
void CellGrid<Dim>::build(const double* points, std::size_t n, double cell_size) {
  points_ = points;
  cell_ = cell_size;
  cell_start_.clear();
  sorted_.clear();
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
  cell_of_.resize(n);
  cell_start_.assign(static_cast<std::size_t>(cells) + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    std::int64_t c = 0, stride = 1;
    for (int d = 0; d < Dim; ++d) {
      std::int64_t k = static_cast<std::int64_t>(std::floor((points[i * Dim + d] - origin_[d]) / cell_));
      k = std::clamp<std::int64_t>(k, 0, dims_[d] - 1);
      c += k * stride;
      stride *= dims_[d];
    }
    cell_of_[i] = c;
    ++cell_start_[c + 1];
  }
  for (std::int64_t c = 0; c < cells; ++c) cell_start_[c + 1] += cell_start_[c];
  sorted_.resize(n);
  fill_.assign(cell_start_.begin(), cell_start_.end() - 1);  // counting sort: next free slot per cell
  for (std::size_t i = 0; i < n; ++i) sorted_[fill_[cell_of_[i]]++] = static_cast<std::int32_t>(i);
}

namespace {

// Cell edge relative to the search radius (see the header).
constexpr double kCellFraction = 0.5;

// One pass: each thread searches a contiguous block of queries into its own buffer, then the blocks
// are copied into place. The result is one contiguous array built without locks, and identical
// whatever the thread count (rows are sorted). The buffers and `out` keep their capacity from one
// call to the next, so repeated searches (every step of a 3D run) do not allocate.
template <class Visit>
void build_rows(std::size_t n_queries, Visit&& visit, NeighbourList& out,
                std::vector<std::vector<std::int32_t>>& blocks) {
  out.offsets.resize(n_queries + 1);
  out.offsets[0] = 0;
  const std::int64_t nq = static_cast<std::int64_t>(n_queries);
#pragma omp parallel
  {
    const int threads = team_size(), t = team_index();
#pragma omp single
    if (blocks.size() < static_cast<std::size_t>(threads)) blocks.resize(threads);
    const std::int64_t first = nq * t / threads, last = nq * (t + 1) / threads;
    std::vector<std::int32_t>& buffer = blocks[t];
    buffer.clear();
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
}

double largest_radius(const double* support_radius, std::size_t n_nodes) {
  double a_max = 0.0;
  for (std::size_t j = 0; j < n_nodes; ++j) {
    if (!(support_radius[j] > 0.0)) throw std::invalid_argument("nodes_covering: support radius must be > 0");
    a_max = std::max(a_max, support_radius[j]);
  }
  return a_max;
}

}  // namespace

template <int Dim>
void neighbours_within(const double* queries, std::size_t n_queries, const double* points, std::size_t n_points,
                       double radius, NeighbourList& out, NeighbourWorkspace<Dim>& workspace) {
  workspace.grid.build(points, n_points, kCellFraction * radius);
  const CellGrid<Dim>& grid = workspace.grid;
  build_rows(
      n_queries,
      [&](std::size_t i, auto&& emit) {
        grid.for_each_within(queries + i * Dim, radius, [&](std::int32_t j, double) { emit(j); });
      },
      out, workspace.blocks);
}

template <int Dim>
void nodes_covering(const double* queries, std::size_t n_queries, const double* nodes, const double* support_radius,
                    std::size_t n_nodes, NeighbourList& out, NeighbourWorkspace<Dim>& workspace) {
  const double a_max = largest_radius(support_radius, n_nodes);
  workspace.grid.build(nodes, n_nodes, n_nodes == 0 ? 1.0 : kCellFraction * a_max);
  const CellGrid<Dim>& grid = workspace.grid;
  build_rows(
      n_queries,
      [&](std::size_t i, auto&& emit) {
        grid.for_each_covering(queries + i * Dim, support_radius, a_max, [&](std::int32_t j, double) { emit(j); });
      },
      out, workspace.blocks);
}

template <int Dim>
NeighbourList neighbours_within(const double* queries, std::size_t n_queries, const double* points,
                                std::size_t n_points, double radius) {
  NeighbourList out;
  NeighbourWorkspace<Dim> workspace;
  neighbours_within<Dim>(queries, n_queries, points, n_points, radius, out, workspace);
  return out;
}

template <int Dim>
NeighbourList nodes_covering(const double* queries, std::size_t n_queries, const double* nodes,
                             const double* support_radius, std::size_t n_nodes) {
  NeighbourList out;
  NeighbourWorkspace<Dim> workspace;
  nodes_covering<Dim>(queries, n_queries, nodes, support_radius, n_nodes, out, workspace);
  return out;
}

template class CellGrid<2>;
template class CellGrid<3>;
template NeighbourList neighbours_within<2>(const double*, std::size_t, const double*, std::size_t, double);
template NeighbourList neighbours_within<3>(const double*, std::size_t, const double*, std::size_t, double);
template NeighbourList nodes_covering<2>(const double*, std::size_t, const double*, const double*, std::size_t);
template NeighbourList nodes_covering<3>(const double*, std::size_t, const double*, const double*, std::size_t);
template void neighbours_within<2>(const double*, std::size_t, const double*, std::size_t, double, NeighbourList&,
                                   NeighbourWorkspace<2>&);
template void neighbours_within<3>(const double*, std::size_t, const double*, std::size_t, double, NeighbourList&,
                                   NeighbourWorkspace<3>&);
template void nodes_covering<2>(const double*, std::size_t, const double*, const double*, std::size_t, NeighbourList&,
                                NeighbourWorkspace<2>&);
template void nodes_covering<3>(const double*, std::size_t, const double*, const double*, std::size_t, NeighbourList&,
                                NeighbourWorkspace<3>&);

}  // namespace uhpc
