// VerletCandidates gives exactly the list of a fresh cell-list search (same nodes, same ascending
// order) while the outer lists are reused: on a jittered lattice with graded supports where a few
// particles move fast (partial searches) and then many do (a new full search).
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "solver/verlet_candidates.hpp"

namespace uhpc::macro {
namespace {

TEST(MacroVerletCandidates, SameListsAsAFreshSearch) {
  const int m = 14;
  const double h = 1.0;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.2, 0.2);
  std::vector<double> x, support;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j)
      for (int k = 0; k < m; ++k) {
        x.insert(x.end(), {i * h + jitter(rng), j * h + jitter(rng), k * h + jitter(rng)});
        support.push_back((2.5 + 0.3 * (i % 3)) * h);  // graded: a node covers more than its row holds
      }
  const std::size_t n = support.size();
  double a_min = support[0];
  for (const double a : support) a_min = std::min(a_min, a);
  const double s = 0.1 * a_min;
  std::vector<double> radius(n);
  for (std::size_t i = 0; i < n; ++i) radius[i] = support[i] + s;

  VerletCandidates candidates;
  NeighbourList got, expected;
  NeighbourWorkspace<3> workspace, fresh;
  std::size_t compared = 0, with_fast = 0;
  for (int round = 0; round < 12; ++round) {
    // Round r: the first few particles move fast (up to several skins); from round 8 on most move.
    const std::size_t movers = round < 8 ? 40 : n / 2;
    for (std::size_t i = 0; i < movers; ++i)
      for (int d = 0; d < 3; ++d) x[3 * i + d] += 0.3 * s * std::sin(1.0 + i + 3 * d + round);
    candidates.search(x.data(), support.data(), radius.data(), s, n, got, workspace);
    nodes_covering<3>(x.data(), n, x.data(), radius.data(), n, expected, fresh);
    ASSERT_EQ(got.offsets, expected.offsets) << "round " << round;
    ASSERT_EQ(got.indices, expected.indices) << "round " << round;
    ++compared;
    if (candidates.fast_particles > 0) ++with_fast;
  }
  EXPECT_EQ(compared, 12u);
  EXPECT_GT(with_fast, 3u);                        // partial searches with fast particles were compared
  EXPECT_GT(candidates.partial_searches, 5u);      // most rounds did not search every particle
  EXPECT_GE(candidates.outer_searches, 2u);        // and many movers forced a new full search
}

}  // namespace
}  // namespace uhpc::macro
