// Particle generators of the 3D code: exact volumes, particles inside their body, spacing following
// the grading, no near-coincident particles, counts as the spacing field predicts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "bodies/generators.hpp"
#include "uhpc/neighbour_search.hpp"

namespace m = uhpc::macro;

namespace {

const double kPi = std::acos(-1.0);

// The paper's target: 406.4 mm x 31.75 mm, spacing 3.0 mm at the axis growing to 4.5 mm at the rim.
m::DiscSpec paper_disc(double core_radius) {
  return {0.2032, 0.03175, -0.03175, 0.003, 0.0045, core_radius};
}

double smallest_neighbour_distance(const m::ParticleBody& body, double search) {
  const auto list = uhpc::neighbours_within<3>(body.position.data(), body.size(), body.position.data(), body.size(),
                                               search);
  double d_min = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < body.size(); ++i)
    for (std::int64_t e = list.begin(i); e < list.end(i); ++e) {
      const std::size_t j = static_cast<std::size_t>(list.indices[e]);
      if (j == i) continue;
      double d2 = 0;
      for (int d = 0; d < 3; ++d) d2 += std::pow(body.position[3 * i + d] - body.position[3 * j + d], 2);
      d_min = std::min(d_min, std::sqrt(d2));
    }
  return d_min;
}

TEST(Bodies, BoxIsACellCentredLatticeWithExactVolume) {
  const auto box = m::box_body(0.1, 0.02, 0.03, 0.0049);
  EXPECT_EQ(box.size(), 20u * 4u * 6u);
  EXPECT_NEAR(box.total_volume(), 0.1 * 0.02 * 0.03, 1e-15);
  for (std::size_t i = 0; i < box.size(); ++i) {
    EXPECT_GT(box.position[3 * i], 0.0);
    EXPECT_LT(box.position[3 * i], 0.1);
    EXPECT_NEAR(box.spacing[i], std::cbrt(0.1 / 20 * 0.02 / 4 * 0.03 / 6), 1e-15);
  }
}

TEST(Bodies, PaperDiscHasExactVolumeAndStaysInside) {
  const m::DiscSpec s = paper_disc(0.0);
  const auto disc = m::disc_body(s);
  EXPECT_NEAR(disc.total_volume() / (kPi * s.radius_m * s.radius_m * s.thickness_m), 1.0, 1e-12);
  for (std::size_t i = 0; i < disc.size(); ++i) {
    EXPECT_LT(std::hypot(disc.position[3 * i], disc.position[3 * i + 1]), s.radius_m);
    EXPECT_GT(disc.position[3 * i + 2], -s.thickness_m);
    EXPECT_LT(disc.position[3 * i + 2], 0.0);
  }
  const double expected = m::disc_particle_estimate(s);
  std::printf("  paper disc, linear grading from the axis: %zu particles (spacing field predicts %.0f)\n",
              disc.size(), expected);
  EXPECT_NEAR(disc.size() / expected, 1.0, 0.05);
}

TEST(Bodies, DiscSpacingFollowsTheGrading) {
  const m::DiscSpec s = paper_disc(0.0);
  const auto disc = m::disc_body(s);
  double near_axis = 0, near_rim = 0;
  int n_axis = 0, n_rim = 0;
  for (std::size_t i = 0; i < disc.size(); ++i) {
    const double r = std::hypot(disc.position[3 * i], disc.position[3 * i + 1]);
    if (r < 0.02) near_axis += disc.spacing[i], ++n_axis;
    if (r > 0.19) near_rim += disc.spacing[i], ++n_rim;
  }
  EXPECT_NEAR(near_axis / n_axis, m::disc_spacing_at(s, 0.01), 0.1 * s.h_axis_m);
  EXPECT_NEAR(near_rim / n_rim, m::disc_spacing_at(s, 0.197), 0.1 * s.h_rim_m);
}

TEST(Bodies, DiscParticlesAreNeverNearlyCoincident) {
  // A thin slice of the paper's disc keeps the check quick.
  m::DiscSpec s = paper_disc(0.05);
  s.radius_m = 0.06;
  const auto disc = m::disc_body(s);
  EXPECT_GT(smallest_neighbour_distance(disc, 0.006), 0.5 * s.h_axis_m);
}

TEST(Bodies, UniformDiscMatchesTheLatticeCount) {
  // With no grading the count is that of a 3 mm cubic lattice of the same volume, which is what the
  // paper's "about 150 000 particles" corresponds to (see the issue note).
  const m::DiscSpec s{0.2032, 0.03175, -0.03175, 0.003, 0.003, 0.0};
  const auto disc = m::disc_body(s);
  // In-plane lattice count times the whole number of layers (11 layers of 2.89 mm through 31.75 mm).
  const double lattice = kPi * s.radius_m * s.radius_m / (0.003 * 0.003) * std::lround(s.thickness_m / 0.003);
  std::printf("  uniform 3 mm disc: %zu particles (square lattice in plane x 11 layers: %.0f)\n", disc.size(),
              lattice);
  EXPECT_NEAR(disc.size() / lattice, 1.0, 0.01);
}

// The counts a run's size budget is checked against before the body is built: exact for the box, within
// a few per cent of disc_body's rounded rings and layers for graded, cored and uniform discs.
TEST(Bodies, TheCountsKnownBeforeABodyIsBuiltMatchTheBuiltBodies) {
  EXPECT_EQ(m::box_particle_count(0.048, 0.048, 0.016, 0.004), m::box_body(0.048, 0.048, 0.016, 0.004).size());
  EXPECT_EQ(m::box_particle_count(0.01, 0.02, 0.001, 0.004), m::box_body(0.01, 0.02, 0.001, 0.004).size());
  EXPECT_EQ(m::box_particle_count(0.048, 0.048, 0.016, 1e-9), 48e6 * 48e6 * 16e6);
  for (const m::DiscSpec& s : {paper_disc(0.0), paper_disc(0.05), m::DiscSpec{0.2032, 0.03175, 0, 0.003, 0.003, 0},
                               m::DiscSpec{0.2032, 0.03175, 0, 0.006, 0.009, 0.05}}) {
    const double built = static_cast<double>(m::disc_body(s).size());
    EXPECT_NEAR(m::disc_particle_estimate(s) / built, 1.0, 0.05) << s.h_axis_m << " " << s.core_radius_m;
  }
}

TEST(Bodies, RejectsDegenerateSpecs) {
  EXPECT_THROW(m::box_body(0.1, 0.0, 0.1, 0.01), std::invalid_argument);
  m::DiscSpec s = paper_disc(0.0);
  s.core_radius_m = s.radius_m;
  EXPECT_THROW(m::disc_body(s), std::invalid_argument);
}

}  // namespace
