// Cell-list neighbour search against brute force, in 2D and 3D, for fixed radii and per-node supports.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "uhpc/neighbour_search.hpp"

namespace {

template <int Dim>
std::vector<double> random_cloud(std::size_t n, double extent, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.5 * extent, 0.5 * extent);
  std::vector<double> p(n * Dim);
  for (double& v : p) v = u(rng);
  return p;
}

template <int Dim>
double dist2(const double* a, const double* b) {
  double s = 0;
  for (int d = 0; d < Dim; ++d) s += (a[d] - b[d]) * (a[d] - b[d]);
  return s;
}

template <int Dim>
void expect_within_matches_brute_force(const std::vector<double>& q, const std::vector<double>& p, double r) {
  const std::size_t nq = q.size() / Dim, np = p.size() / Dim;
  const uhpc::NeighbourList list = uhpc::neighbours_within<Dim>(q.data(), nq, p.data(), np, r);
  ASSERT_EQ(list.size(), nq);
  std::size_t total = 0;
  for (std::size_t i = 0; i < nq; ++i) {
    std::vector<std::int32_t> brute;
    for (std::size_t j = 0; j < np; ++j)
      if (dist2<Dim>(&q[i * Dim], &p[j * Dim]) <= r * r) brute.push_back(static_cast<std::int32_t>(j));
    const std::vector<std::int32_t> found(list.row(i), list.row(i) + list.count(i));
    ASSERT_EQ(found, brute) << "query " << i;
    total += brute.size();
  }
  EXPECT_GT(total, nq);  // the test is not vacuous
}

TEST(NeighbourSearch, Within2DMatchesBruteForce) {
  const auto p = random_cloud<2>(3000, 1.0, 1);
  const auto q = random_cloud<2>(500, 1.2, 2);  // some queries outside the cloud
  expect_within_matches_brute_force<2>(q, p, 0.04);
}

TEST(NeighbourSearch, Within3DMatchesBruteForce) {
  const auto p = random_cloud<3>(4000, 1.0, 3);
  const auto q = random_cloud<3>(400, 1.2, 4);
  expect_within_matches_brute_force<3>(q, p, 0.12);
}

TEST(NeighbourSearch, SelfQueriesFindThemselves) {
  const auto p = random_cloud<3>(1000, 1.0, 5);
  const auto list = uhpc::neighbours_within<3>(p.data(), 1000, p.data(), 1000, 0.1);
  for (std::size_t i = 0; i < 1000; ++i) {
    const auto* row = list.row(i);
    EXPECT_TRUE(std::binary_search(row, row + list.count(i), static_cast<std::int32_t>(i)));
  }
}

TEST(NeighbourSearch, SparseCloudWithFarOutliersStaysCorrect) {
  // Debris far from the body would make a naive grid enormous; the grid coarsens instead.
  auto p = random_cloud<3>(2000, 1.0, 6);
  const double far[] = {1e4, -3e3, 2e4, -1e4, 5e3, 1e3};
  p.insert(p.end(), far, far + 6);
  const uhpc::CellGrid<3> grid(p.data(), p.size() / 3, 0.05);
  EXPECT_LE(static_cast<double>(grid.cell_count()), 4.0 * 2002 + 64);
  auto q = random_cloud<3>(200, 1.0, 7);
  q.insert(q.end(), far, far + 3);
  expect_within_matches_brute_force<3>(q, p, 0.05);
}

template <int Dim>
void expect_covering_matches_brute_force(std::uint32_t seed) {
  auto nodes = random_cloud<Dim>(2000, 1.0, seed);
  std::mt19937 rng(seed + 100);
  std::uniform_real_distribution<double> u(0.03, 0.15);  // graded supports
  std::vector<double> a(nodes.size() / Dim);
  for (double& v : a) v = u(rng);
  const auto q = random_cloud<Dim>(300, 1.1, seed + 1);
  const std::size_t nq = q.size() / Dim, nn = a.size();
  const auto list = uhpc::nodes_covering<Dim>(q.data(), nq, nodes.data(), a.data(), nn);
  for (std::size_t i = 0; i < nq; ++i) {
    std::vector<std::int32_t> brute;
    for (std::size_t j = 0; j < nn; ++j)
      if (dist2<Dim>(&q[i * Dim], &nodes[j * Dim]) < a[j] * a[j]) brute.push_back(static_cast<std::int32_t>(j));
    const std::vector<std::int32_t> found(list.row(i), list.row(i) + list.count(i));
    ASSERT_EQ(found, brute) << "query " << i;
  }
}

TEST(NeighbourSearch, Covering2DMatchesBruteForce) { expect_covering_matches_brute_force<2>(11); }
TEST(NeighbourSearch, Covering3DMatchesBruteForce) { expect_covering_matches_brute_force<3>(12); }

TEST(NeighbourSearch, EmptyInputsGiveEmptyRows) {
  const double q[] = {0.0, 0.0};
  const auto list = uhpc::neighbours_within<2>(q, 1, nullptr, 0, 1.0);
  ASSERT_EQ(list.size(), 1u);
  EXPECT_EQ(list.count(0), 0);
}

}  // namespace

namespace {

TEST(NeighbourSearch, ReusedWorkspaceGivesTheSameListsAsAFreshSearch) {
  uhpc::NeighbourWorkspace<3> workspace;
  uhpc::NeighbourList reused;
  for (std::uint32_t seed : {21u, 22u, 23u}) {
    // Clouds of different sizes, so the buffers grow and shrink between calls.
    const auto nodes = random_cloud<3>(500 + 700 * (seed - 20), 1.0, seed);
    std::vector<double> a(nodes.size() / 3, 0.08 + 0.02 * (seed - 20));
    const auto q = random_cloud<3>(300 * (seed - 20), 1.0, seed + 50);
    uhpc::nodes_covering<3>(q.data(), q.size() / 3, nodes.data(), a.data(), a.size(), reused, workspace);
    const auto fresh = uhpc::nodes_covering<3>(q.data(), q.size() / 3, nodes.data(), a.data(), a.size());
    EXPECT_EQ(reused.offsets, fresh.offsets);
    EXPECT_EQ(reused.indices, fresh.indices);
    uhpc::neighbours_within<3>(q.data(), q.size() / 3, nodes.data(), a.size(), 0.07, reused, workspace);
    const auto fresh_within = uhpc::neighbours_within<3>(q.data(), q.size() / 3, nodes.data(), a.size(), 0.07);
    EXPECT_EQ(reused.offsets, fresh_within.offsets);
    EXPECT_EQ(reused.indices, fresh_within.indices);
  }
}

}  // namespace
