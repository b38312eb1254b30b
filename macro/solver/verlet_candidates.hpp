#pragma once
// The candidate search of the Verlet skin (ShapeCache::skin) without a full cell-list search each time.
// The skin's candidates of point p are every node j with |x_p - x_j| < r_j = a_j + s, ascending: that
// exact list (the lazy-row decisions read it, so it must not hold more or fewer nodes) is rebuilt
// here from longer "outer" lists, searched with radii a_j + 2 s at the positions x_o of an outer
// search. While two particles have each moved at most s/2 from x_o, every pair within r_j now was
// within a_j + 2 s then: filtering the outer row of p with the search's own test (d^2 < r_j^2) gives
// the exact list. Only pairs with a fast particle (moved more than s/2 since x_o: the few near the
// impact) can be missing, so those are searched afresh: the rows of the fast points over all nodes,
// and the fast nodes covering each point, merged in ascending order. A new outer search only once too
// many particles are fast. The result equals nodes_covering(x, n, x, r, n) bitwise.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "uhpc/neighbour_search.hpp"

namespace uhpc::macro {

// The nodes j of `row` (in its order) whose support covers the point xp, |xp - x_j|^2 < radius[j]^2 (the
// search's own test, the axes summed in order) and for which accept(j) holds, written to `kept`;
// returns how many. The one filter of candidate rows, shared by ShapeCache and VerletCandidates.
template <class Accept>
inline std::int64_t covering_nodes(const double* xp, const std::int32_t* row, std::int64_t count, const double* x,
                                   const double* radius, std::int32_t* kept, Accept accept) {
  std::int64_t m = 0;
  for (std::int64_t k = 0; k < count; ++k) {
    const std::int32_t j = row[k];
    const double* xj = x + 3 * static_cast<std::int64_t>(j);
    double d2 = 0.0;
    for (int d = 0; d < 3; ++d) d2 += (xp[d] - xj[d]) * (xp[d] - xj[d]);
    if (d2 < radius[j] * radius[j] && accept(j)) kept[m++] = j;
  }
  return m;
}

class VerletCandidates {
 public:
  // `out`: for every point p of the n points x (also the nodes), every j with |x_p - x_j| < radius[j],
  // ascending, with radius[j] = support[j] + s (the caller's inflated radii). Memory is kept between
  // calls. The positions must be finite (the solver checks before it searches).
  void search(const double* x, const double* support, const double* radius, double s, std::size_t n,
              NeighbourList& out, NeighbourWorkspace<3>& workspace);

  std::size_t outer_searches = 0;    // full cell-list searches (radii a_j + 2 s)
  std::size_t partial_searches = 0;  // lists rebuilt from the outer lists plus the fast particles
  std::size_t fast_particles = 0;    // fast particles at the last partial search

 private:
  bool outer_valid(const double* x, const double* support, double s, std::size_t n);
  void outer_search(const double* x, const double* support, double s, std::size_t n, NeighbourWorkspace<3>& workspace);

  NeighbourList outer_;
  std::vector<double> outer_x_, outer_support_, outer_radius_;
  double outer_s_ = 0.0;
  // Fast particles (ascending), their local index (-1: slow), positions and radii gathered.
  std::vector<std::int32_t> fast_, fast_index_;
  std::vector<double> fast_x_, fast_radius_;
  NeighbourList fast_covering_;  // per point: the fast nodes (local indices) covering it
  NeighbourList fast_rows_;      // per fast point: every node covering it
  std::vector<std::int32_t> filtered_;  // outer rows filtered in place (outer offsets)
};

}  // namespace uhpc::macro
