#pragma once
// Fixed-radius neighbour search with cell lists (2D and 3D).
//
// Points are binned into a uniform grid of cubic cells; a query visits the cells that intersect the
// bounding box of its search ball. The points are stored sorted by cell (counting sort), so each row
// of cells is one contiguous range. Building is O(n); a query costs O(points in the box). The
// searches below use cells of half the search radius: a 5^Dim box holds about half the candidates of
// the classic 3^Dim stencil of radius-sized cells, for the same hits.
//
// A grid covering a very sparse cloud (debris flying far away in the 3D runs) would have far more
// cells than points; the cell edge is then enlarged until the grid has at most kMaxCellsPerPoint cells
// per point. That keeps memory O(n) and queries correct (the stencil still covers the radius), at the
// price of visiting more candidates in the sparse parts only.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace uhpc {

// Compressed rows: the neighbours of query i are indices[offsets[i] .. offsets[i+1]), ascending.
struct NeighbourList {
  std::vector<std::int64_t> offsets{0};
  std::vector<std::int32_t> indices;

  std::size_t size() const { return offsets.size() - 1; }
  std::int64_t begin(std::size_t i) const { return offsets[i]; }
  std::int64_t end(std::size_t i) const { return offsets[i + 1]; }
  std::int64_t count(std::size_t i) const { return offsets[i + 1] - offsets[i]; }
  const std::int32_t* row(std::size_t i) const { return indices.data() + offsets[i]; }
};

template <int Dim>
class CellGrid {
 public:
  static constexpr double kMaxCellsPerPoint = 4.0;

  CellGrid() = default;
  // `points`: n points, Dim coordinates each, contiguous; `cell_size` > 0. The grid keeps a pointer to
  // `points`: they must outlive it and not move.
  CellGrid(const double* points, std::size_t n, double cell_size);
  // Rebuilds the grid for new points, reusing this grid's memory.
  void build(const double* points, std::size_t n, double cell_size);

  double cell_size() const { return cell_; }
  std::size_t cell_count() const { return cell_start_.empty() ? 0 : cell_start_.size() - 1; }

  // Calls f(j, squared_distance) for every point j with |x - p_j| <= radius (any radius; the cost
  // grows with the number of cells the radius spans).
  template <class F>
  void for_each_within(const double* x, double radius, F&& f) const {
    const double r2 = radius * radius;
    visit_box(x, radius, [&](std::int32_t j) {
      const double d2 = squared_distance(x, points_ + static_cast<std::size_t>(j) * Dim);
      if (d2 <= r2) f(j, d2);
    });
  }

  // Calls f(j, squared_distance) for every point j whose own radius covers x: |x - p_j| < radius[j].
  // `max_radius` >= every radius[j].
  template <class F>
  void for_each_covering(const double* x, const double* radius, double max_radius, F&& f) const {
    visit_box(x, max_radius, [&](std::int32_t j) {
      const double d2 = squared_distance(x, points_ + static_cast<std::size_t>(j) * Dim);
      if (d2 < radius[j] * radius[j]) f(j, d2);
    });
  }

 private:
  static double squared_distance(const double* a, const double* b) {
    double s = 0.0;
    for (int d = 0; d < Dim; ++d) s += (a[d] - b[d]) * (a[d] - b[d]);
    return s;
  }

  // Visits every point in the cells that intersect the box [x - reach, x + reach].
  template <class G>
  void visit_box(const double* x, double reach, G&& g) const {
    if (cell_start_.empty()) return;
    std::array<std::int64_t, Dim> lo{}, hi{};
    for (int d = 0; d < Dim; ++d) {
      if (!std::isfinite(x[d])) return;
      const double a = std::floor((x[d] - reach - origin_[d]) / cell_);
      const double b = std::floor((x[d] + reach - origin_[d]) / cell_);
      if (b < 0.0 || a > static_cast<double>(dims_[d] - 1)) return;  // the box misses the grid
      lo[d] = a < 0.0 ? 0 : static_cast<std::int64_t>(a);
      hi[d] = std::min(static_cast<std::int64_t>(b), dims_[d] - 1);
    }
    if constexpr (Dim == 2) {
      for (std::int64_t j = lo[1]; j <= hi[1]; ++j) {
        // Cells of one row are adjacent in the sorted order: one contiguous range per row.
        const std::int64_t first = lo[0] + dims_[0] * j, last = hi[0] + dims_[0] * j;
        for (std::int64_t p = cell_start_[first]; p < cell_start_[last + 1]; ++p) g(sorted_[p]);
      }
    } else {
      for (std::int64_t k = lo[2]; k <= hi[2]; ++k)
        for (std::int64_t j = lo[1]; j <= hi[1]; ++j) {
          const std::int64_t base = dims_[0] * (j + dims_[1] * k);
          for (std::int64_t p = cell_start_[base + lo[0]]; p < cell_start_[base + hi[0] + 1]; ++p) g(sorted_[p]);
        }
    }
  }

  const double* points_ = nullptr;
  double cell_ = 0.0;
  std::array<double, Dim> origin_{};
  std::array<std::int64_t, Dim> dims_{};
  std::vector<std::int64_t> cell_start_;  // size cells+1: points of cell c are sorted_[start[c]..start[c+1])
  std::vector<std::int32_t> sorted_;      // point indices ordered by cell
  std::vector<std::int64_t> cell_of_, fill_;  // build scratch, kept for the next build
};

// Memory kept between repeated searches (a 3D run rebuilds its lists every step): the grid and the
// per-thread buffers keep their capacity, so a search into an existing NeighbourList allocates
// nothing once sizes have settled.
template <int Dim>
struct NeighbourWorkspace {
  CellGrid<Dim> grid;
  std::vector<std::vector<std::int32_t>> blocks;
};

// For every query i, all points j with |q_i - p_j| <= radius. Parallel over queries (OpenMP).
template <int Dim>
NeighbourList neighbours_within(const double* queries, std::size_t n_queries, const double* points,
                                std::size_t n_points, double radius);

// For every query i, all nodes j whose support covers it: |q_i - x_j| < support_radius[j].
// This is the list RK shape functions at q_i need. Parallel over queries (OpenMP).
template <int Dim>
NeighbourList nodes_covering(const double* queries, std::size_t n_queries, const double* nodes,
                             const double* support_radius, std::size_t n_nodes);

// The same two searches into an existing list, reusing its memory and the workspace's.
template <int Dim>
void neighbours_within(const double* queries, std::size_t n_queries, const double* points, std::size_t n_points,
                       double radius, NeighbourList& out, NeighbourWorkspace<Dim>& workspace);
template <int Dim>
void nodes_covering(const double* queries, std::size_t n_queries, const double* nodes, const double* support_radius,
                    std::size_t n_nodes, NeighbourList& out, NeighbourWorkspace<Dim>& workspace);

}  // namespace uhpc
