// Crack initiation and growth (micro/analysis/crack_growth.hpp) on its own: seeds become planned paths
// of about one increment per segment with nothing active; a tip activates its planned path first and
// then grows by one increment in the direction it is given; it stops on the cell edge, a pore or another
// crack without leaving a sliver; the criterion is the normal stress across the next planned segment or
// the largest principal stress (and the crack turns normal to it); the stress is sampled on a half disc
// ahead of the tip, in the matrix only. The mesh only supplies the local spacing.
#include <cmath>

#include <gtest/gtest.h>

#include "cell_mesh.hpp"
#include "crack_growth.hpp"

namespace uhpc::micro {
namespace {

constexpr double kSide = 1e-3;

CellGeometry plain_cell() {
  CellGeometry g;
  g.side_m = kSide;
  return g;
}

const CellDiscretization& mesh() {
  static const CellDiscretization m = [] {
    MeshOptions o;
    o.nominal_spacing_m = 100e-6;
    return mesh_cell(plain_cell(), o);
  }();
  return m;
}

// A crack with only its root point and `active` = 0, whose free growth starts at `root` heading `dir`.
Crack free_crack(Vec2 root, Vec2 tip) {
  Crack c;
  c.root = CrackEnd::Edge;
  c.points = {root, tip};
  c.active = 1;
  return c;
}

double length(const Vec2& a, const Vec2& b) { return std::hypot(b.x - a.x, b.y - a.y); }

TEST(microCrackGrowth, SeedsBecomePlannedPathsOfAboutOneIncrementWithNothingActive) {
  CellGeometry g = plain_cell();
  g.pores.push_back({{0.2e-3, 0.5e-3}, 0.2e-3});
  g.seeds.push_back({0, {0.3e-3, 0.5e-3}, {0.65e-3, 0.5e-3}});  // from the pore into the matrix
  g.seeds.push_back({-1, {0.5e-3, 0.0}, {0.5e-3, 0.25e-3}});    // from the edge
  g.seeds.push_back({-1, {0.9e-3, 0.5e-3}, {kSide, 0.5e-3}});   // reaching the edge
  const std::vector<Crack> cracks = cracks_from_seeds(g, mesh(), GrowthOptions{});
  ASSERT_EQ(cracks.size(), 3u);
  for (std::size_t s = 0; s < cracks.size(); ++s) {
    const Crack& c = cracks[s];
    EXPECT_EQ(c.active, 0u);
    EXPECT_EQ(c.seed, static_cast<int>(s));
    const double h = local_spacing(mesh(), c.points.front());
    for (std::size_t k = 0; k + 1 < c.points.size(); ++k) {
      const double l = length(c.points[k], c.points[k + 1]);
      EXPECT_GT(l, 0.66 * h) << s;
      EXPECT_LT(l, 1.5 * h) << s;
    }
    EXPECT_NEAR(c.points.front().x, g.seeds[s].root_m.x, 1e-15);
    EXPECT_NEAR(c.points.back().x, g.seeds[s].tip_m.x, 1e-15);
    EXPECT_NEAR(c.points.back().y, g.seeds[s].tip_m.y, 1e-15);
  }
  EXPECT_EQ(cracks[0].root, CrackEnd::Pore);
  EXPECT_EQ(cracks[1].root, CrackEnd::Edge);
  EXPECT_EQ(cracks[0].tip_end, CrackEnd::Open);
  EXPECT_EQ(cracks[2].tip_end, CrackEnd::Edge);
}

TEST(microCrackGrowth, ATipActivatesItsPlannedPathFirstThenGrowsOneIncrementAsDirected) {
  CellGeometry g = plain_cell();
  g.seeds.push_back({-1, {0.0, 0.5e-3}, {0.3e-3, 0.5e-3}});
  std::vector<Crack> cracks = cracks_from_seeds(g, mesh(), GrowthOptions{});
  const std::size_t planned = cracks[0].planned_segments();
  for (std::size_t k = 1; k <= planned; ++k) {
    // The direction is ignored while the path is planned.
    ASSERT_TRUE(advance_crack(cracks, 0, {0.0, 1.0}, g, mesh(), GrowthOptions{}));
    EXPECT_EQ(cracks[0].active, k);
  }
  const Vec2 tip = cracks[0].tip();
  const Vec2 dir{std::cos(0.3), std::sin(0.3)};
  ASSERT_TRUE(advance_crack(cracks, 0, dir, g, mesh(), GrowthOptions{}));
  const Crack& c = cracks[0];
  EXPECT_EQ(c.active, planned + 1);
  EXPECT_EQ(c.tip_end, CrackEnd::Open);
  const double h = local_spacing(mesh(), tip);
  EXPECT_NEAR(c.tip().x, tip.x + h * dir.x, 1e-12 * kSide);
  EXPECT_NEAR(c.tip().y, tip.y + h * dir.y, 1e-12 * kSide);
}

TEST(microCrackGrowth, AFreeTipStopsOnTheCellEdgeWithoutLeavingASliver) {
  const CellGeometry g = plain_cell();
  const double h = local_spacing(mesh(), {0.9e-3, 0.5e-3});
  const double x0 = kSide - 1.3 * h;  // the edge is within the 1.5-increment look-ahead
  std::vector<Crack> cracks{free_crack({x0 - h, 0.5e-3}, {x0, 0.5e-3})};
  ASSERT_TRUE(advance_crack(cracks, 0, {1.0, 0.0}, g, mesh(), GrowthOptions{}));
  EXPECT_EQ(cracks[0].tip_end, CrackEnd::Edge);
  EXPECT_DOUBLE_EQ(cracks[0].tip().x, kSide);
  EXPECT_TRUE(cracks[0].stopped());
  EXPECT_FALSE(advance_crack(cracks, 0, {1.0, 0.0}, g, mesh(), GrowthOptions{}));
  EXPECT_EQ(cracks[0].points.size(), 3u);
}

TEST(microCrackGrowth, AFreeTipStopsOnThePoreBoundaryItRunsInto) {
  CellGeometry g = plain_cell();
  const Vec2 center{0.6e-3, 0.5e-3};
  const double radius = 0.1e-3;
  g.pores.push_back({center, 2.0 * radius});
  const double h = local_spacing(mesh(), {0.45e-3, 0.5e-3});
  const double x0 = center.x - radius - 1.2 * h;
  std::vector<Crack> cracks{free_crack({x0 - h, 0.5e-3}, {x0, 0.5e-3})};
  ASSERT_TRUE(advance_crack(cracks, 0, {1.0, 0.0}, g, mesh(), GrowthOptions{}));
  EXPECT_EQ(cracks[0].tip_end, CrackEnd::Pore);
  EXPECT_NEAR(length(cracks[0].tip(), center), radius, 1e-12 * kSide);
}

TEST(microCrackGrowth, AFreeTipThatMeetsAnotherCrackJoinsItOnItsSide) {
  const CellGeometry g = plain_cell();
  const double h = local_spacing(mesh(), {0.5e-3, 0.5e-3});
  Crack wall;  // a vertical active crack at x = 0.5 mm
  wall.root = CrackEnd::Edge;
  wall.points = {{0.5e-3, 0.2e-3}, {0.5e-3, 0.5e-3}, {0.5e-3, 0.8e-3}};
  wall.active = 2;
  const double x0 = 0.5e-3 - 0.8 * h;
  std::vector<Crack> cracks{wall, free_crack({x0 - h, 0.55e-3}, {x0, 0.55e-3})};
  ASSERT_TRUE(advance_crack(cracks, 1, {1.0, 0.0}, g, mesh(), GrowthOptions{}));
  const Crack& c = cracks[1];
  EXPECT_EQ(c.tip_end, CrackEnd::Crack);
  EXPECT_EQ(c.junction, 0);
  EXPECT_NEAR(c.tip().x, 0.5e-3, 1e-12 * kSide);
  const double before[2] = {x0, 0.55e-3};
  EXPECT_EQ(c.junction_side, crack_side(cracks[0], before));
}

TEST(microCrackGrowth, WithCoalescenceATipPassingCloseToACrackJoinsItsNearestPoint) {
  const CellGeometry g = plain_cell();
  const double h = local_spacing(mesh(), {0.5e-3, 0.5e-3});
  Crack wall;  // a horizontal active crack 0.5 h above the line the tip runs on
  wall.root = CrackEnd::Edge;
  wall.points = {{0.45e-3, 0.5e-3 + 0.5 * h}, {0.8e-3, 0.5e-3 + 0.5 * h}};
  wall.active = 1;
  const Crack runner = free_crack({0.3e-3, 0.5e-3}, {0.4e-3, 0.5e-3});
  GrowthOptions off, on;
  on.coalescence_spacings = 1.0;
  std::vector<Crack> parallel{wall, runner};
  ASSERT_TRUE(advance_crack(parallel, 1, {1.0, 0.0}, g, mesh(), off));
  EXPECT_EQ(parallel[1].tip_end, CrackEnd::Open);  // off: it runs on beside the other crack
  std::vector<Crack> joined{wall, runner};
  ASSERT_TRUE(advance_crack(joined, 1, {1.0, 0.0}, g, mesh(), on));
  EXPECT_EQ(joined[1].tip_end, CrackEnd::Crack);
  EXPECT_EQ(joined[1].junction, 0);
  EXPECT_NEAR(joined[1].tip().y, 0.5e-3 + 0.5 * h, 1e-12 * kSide);
}

TEST(microCrackGrowth, ThePlannedCriterionIsTheNormalStressAcrossTheNextSegment) {
  CellGeometry g = plain_cell();
  g.seeds.push_back({-1, {0.0, 0.5e-3}, {0.3e-3, 0.5e-3}});
  const std::vector<Crack> cracks = cracks_from_seeds(g, mesh(), GrowthOptions{});
  const TipSamples s = tip_samples(g, mesh(), cracks, GrowthOptions{});
  const std::vector<std::array<double, 3>> stress(s.crack.size(), {1.0e6, 2.0e6, 0.5e6});
  const std::vector<TipCriterion> t = tip_criteria(cracks, s, stress);
  ASSERT_TRUE(t[0].valid);
  EXPECT_NEAR(t[0].stress_Pa, 2.0e6, 1e-6);  // the segment runs along x: its normal stress is sigma_yy
  EXPECT_NEAR(t[0].direction.x, 1.0, 1e-15);
}

TEST(microCrackGrowth, TheFreeCriterionIsTheLargestPrincipalStressAndTheCrackTurnsNormalToIt) {
  const CellGeometry g = plain_cell();
  const std::vector<Crack> cracks{free_crack({0.3e-3, 0.5e-3}, {0.4e-3, 0.5e-3})};
  const TipSamples s = tip_samples(g, mesh(), cracks, GrowthOptions{});
  // Uniaxial tension along y rotated by 30 degrees: sigma_1 = 3 MPa along (-sin 30, cos 30).
  const double a = M_PI / 6.0, s1 = 3e6;
  const std::array<double, 3> sig{s1 * std::sin(a) * std::sin(a), s1 * std::cos(a) * std::cos(a),
                                  -s1 * std::sin(a) * std::cos(a)};
  const std::vector<TipCriterion> t = tip_criteria(cracks, s, std::vector<std::array<double, 3>>(s.crack.size(), sig));
  ASSERT_TRUE(t[0].valid);
  EXPECT_NEAR(t[0].stress_Pa, s1, 1e-6);
  // Normal to sigma_1, i.e. along (cos 30, sin 30), and forward (the tip points along +x).
  EXPECT_NEAR(t[0].direction.x, std::cos(a), 1e-12);
  EXPECT_NEAR(t[0].direction.y, std::sin(a), 1e-12);
}

TEST(microCrackGrowth, TheStressIsSampledOnAHalfDiscAheadOfTheTipInTheMatrixOnly) {
  CellGeometry g = plain_cell();
  const Vec2 tip{0.4e-3, 0.5e-3};
  const double h = local_spacing(mesh(), tip);
  g.pores.push_back({{tip.x + 1.2 * h, tip.y + 1.2 * h}, 1.0 * h});  // covers part of the half disc
  Crack stopped = free_crack({0.1e-3, 0.2e-3}, {0.1e-3, 0.0});
  stopped.tip_end = CrackEnd::Edge;
  const std::vector<Crack> cracks{free_crack({0.3e-3, 0.5e-3}, tip), stopped};
  const GrowthOptions o;
  const TipSamples s = tip_samples(g, mesh(), cracks, o);
  ASSERT_GT(s.crack.size(), 20u);
  EXPECT_LT(s.crack.size(), 36u);  // 4 rings x 9 rays, less those in the pore
  for (std::size_t p = 0; p < s.crack.size(); ++p) {
    EXPECT_EQ(s.crack[p], 0);  // none for the stopped crack
    const double dx = s.x[2 * p] - tip.x, dy = s.x[2 * p + 1] - tip.y;
    EXPECT_GT(dx, 0.0);  // ahead of the tip
    EXPECT_LE(std::hypot(dx, dy), o.average_radius_spacings * h);
    EXPECT_GE(std::hypot(s.x[2 * p] - g.pores[0].center_m.x, s.x[2 * p + 1] - g.pores[0].center_m.y),
              g.pores[0].radius_m());
  }
}

}  // namespace
}  // namespace uhpc::micro
