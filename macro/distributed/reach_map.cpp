#include "distributed/reach_map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace uhpc::macro::distributed {

ReachMap::ReachMap(const double* x, const double* reach, std::size_t n, double cell) : cell_(cell) {
  if (!(cell > 0.0) || !std::isfinite(cell)) throw std::invalid_argument("ReachMap: the cell size must be finite and > 0");
  if (n == 0) return;
  for (std::size_t i = 0; i < 3 * n; ++i)
    if (!std::isfinite(x[i])) throw std::invalid_argument("ReachMap: a position that is not finite");
  for (int d = 0; d < 3; ++d) origin_[d] = top_[d] = x[d];
  for (std::size_t i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) {
      origin_[d] = std::min(origin_[d], x[3 * i + d]);
      top_[d] = std::max(top_[d], x[3 * i + d]);
    }
  double cells = 1.0;
  for (int d = 0; d < 3; ++d) {
    const double along = std::floor((top_[d] - origin_[d]) / cell_) + 1.0;
    cells *= along;
    if (cells > 1e8) throw std::invalid_argument("ReachMap: more than 1e8 cells (the cell size is far too small)");
    dims_[d] = static_cast<int>(along);
  }
  largest_.assign(static_cast<std::size_t>(dims_[0]) * dims_[1] * dims_[2], -1.0);
  for (std::size_t i = 0; i < n; ++i) {
    int c[3];
    for (int d = 0; d < 3; ++d)
      c[d] = std::min(dims_[d] - 1, static_cast<int>(std::floor((x[3 * i + d] - origin_[d]) / cell_)));
    double& r = largest_[(static_cast<std::size_t>(c[2]) * dims_[1] + c[1]) * dims_[0] + c[0]];
    r = std::max(r, reach[i]);
    widest_ = std::max(widest_, reach[i]);
  }
}

bool ReachMap::needs(const double* x, double own_reach) const {
  if (largest_.empty()) return false;
  if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2]) || !std::isfinite(own_reach))
    return true;  // nowhere to judge it: every rank gets it (and the step's health check names it)
  // Only cells within own_reach + the widest reach can qualify (and none when x is farther than that
  // from the whole grid: the loops below are then empty).
  const double r = (own_reach + widest_) * (1.0 + 1e-12);
  int lo[3], hi[3];
  for (int d = 0; d < 3; ++d) {
    // Clamped in double before the cast: a point far from the grid gives indices far out of int's range.
    const double last = dims_[d] - 1;
    const double a = std::floor((x[d] - r - origin_[d]) / cell_), b = std::floor((x[d] + r - origin_[d]) / cell_);
    if (b < 0.0 || a > last) return false;
    lo[d] = static_cast<int>(std::max(a, 0.0));
    hi[d] = static_cast<int>(std::min(b, last));
  }
  for (int k = lo[2]; k <= hi[2]; ++k)
    for (int j = lo[1]; j <= hi[1]; ++j)
      for (int i = lo[0]; i <= hi[0]; ++i) {
        const double reach = cell_reach(i, j, k);
        if (reach < 0.0) continue;
        const int c[3] = {i, j, k};
        double d2 = 0.0;
        for (int d = 0; d < 3; ++d) {
          const double a = origin_[d] + c[d] * cell_, b = std::min(a + cell_, top_[d]);
          const double out = std::max({a - x[d], 0.0, x[d] - b});
          d2 += out * out;
        }
        const double limit = (own_reach + reach) * (1.0 + 1e-12);
        if (d2 < limit * limit) return true;
      }
  return false;
}

std::vector<ReachMap> ReachMap::gather(const ReachMap& mine, MPI_Comm comm) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  // Header: origin (3), top (3), cell, widest, dims (3, as doubles); then the cells.
  constexpr int kHeader = 11;
  std::vector<double> packed = {mine.origin_[0], mine.origin_[1], mine.origin_[2], mine.top_[0], mine.top_[1],
                                mine.top_[2], mine.cell_, mine.widest_, double(mine.dims_[0]), double(mine.dims_[1]),
                                double(mine.dims_[2])};
  packed.insert(packed.end(), mine.largest_.begin(), mine.largest_.end());
  int count = static_cast<int>(packed.size());
  std::vector<int> counts(static_cast<std::size_t>(size)), starts(static_cast<std::size_t>(size), 0);
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  for (int r = 1; r < size; ++r) starts[r] = starts[r - 1] + counts[r - 1];
  std::vector<double> all(static_cast<std::size_t>(starts.back() + counts.back()));
  MPI_Allgatherv(packed.data(), count, MPI_DOUBLE, all.data(), counts.data(), starts.data(), MPI_DOUBLE, comm);
  std::vector<ReachMap> maps(static_cast<std::size_t>(size));
  for (int r = 0; r < size; ++r) {
    const double* p = all.data() + starts[r];
    ReachMap& m = maps[static_cast<std::size_t>(r)];
    for (int d = 0; d < 3; ++d) {
      m.origin_[d] = p[d];
      m.top_[d] = p[3 + d];
      m.dims_[d] = static_cast<int>(p[8 + d]);
    }
    m.cell_ = p[6];
    m.widest_ = p[7];
    m.largest_.assign(p + kHeader, p + counts[r]);
  }
  return maps;
}

}  // namespace uhpc::macro::distributed
