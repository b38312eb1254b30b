#pragma once
// Where a rank's rows reach: a coarse grid over its particles, each cell holding the largest row reach
// (support radius) of the particles in it. A particle K of another rank is needed here when it lies
// within node_reach_K + row_reach_J of some particle J of this rank; the grid answers that without
// the particles, as a superset: J in cell C is at least the distance from x_K to C's box away, and
// its reach is at most C's largest. So a finely spaced core asks only for its own small reach while
// a coarse rim, in the same rank, asks for its large one. The cells are clipped to the points' bounding
// box, so a rank's face along a cut is where its outermost points are, not where its last cell ends.
// Small enough (a cell per largest support radius or so) to be sent to every rank.
#include <cstdint>
#include <vector>

#include <mpi.h>

namespace uhpc::macro::distributed {

class ReachMap {
 public:
  ReachMap() = default;
  // The grid over the points x (3n) with cells of side `cell`, each holding its points' largest reach.
  ReachMap(const double* x, const double* reach, std::size_t n, double cell);
  // Does some cell come closer to x than own_reach + its reach? (Widened by 1e-12 relative: a tie in
  // exact arithmetic counts as near.)
  bool needs(const double* x, double own_reach) const;
  double widest() const { return widest_; }  // the largest reach of any cell
  // Every rank's map, in rank order (collective).
  static std::vector<ReachMap> gather(const ReachMap& mine, MPI_Comm comm);

 private:
  double origin_[3] = {0, 0, 0}, top_[3] = {0, 0, 0}, cell_ = 1.0, widest_ = 0.0;  // top_: the points' largest coordinates
  int dims_[3] = {0, 0, 0};
  std::vector<double> largest_;  // per cell (x fastest), -1 where no point is
  double cell_reach(int i, int j, int k) const { return largest_[(static_cast<std::size_t>(k) * dims_[1] + j) * dims_[0] + i]; }
};

}  // namespace uhpc::macro::distributed
