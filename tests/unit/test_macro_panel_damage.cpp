// The panel after a shot (macro/app/panel_damage.hpp) on a block of 7 x 7 x 4 particles (1 mm) whose
// positions and velocities are set by hand: the crater and scab diameters from the particles of each
// face layer that left their place, the debris of either face by mass and momentum, the plug, the hole
// left through the panel and the rear face's deflection.
#include <cmath>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "bodies/generators.hpp"
#include "panel_damage.hpp"
#include "solver/particles.hpp"

namespace uhpc::macro {
namespace {

constexpr double kH = 0.001, kT = 0.004;

struct Block {
  ParticleBody body;
  Particles p;
};

Block block() {
  ParticleBody body = box_body(0.007, 0.007, kT, kH);
  for (std::size_t i = 0; i < body.size(); ++i) {  // x, y centred on the axis, as the cases place a box
    body.position[3 * i] -= 0.0035;
    body.position[3 * i + 1] -= 0.0035;
  }
  Particles p = Particles::from_body(body, 2500.0, 2.5);
  return {body, p};
}

// The particle whose reference centre is nearest (x, y, z).
std::size_t at(const Block& b, double x, double y, double z) {
  std::size_t best = 0;
  double d_best = 1e9;
  for (std::size_t i = 0; i < b.p.n; ++i) {
    const double d = std::hypot(b.body.position[3 * i] - x, b.body.position[3 * i + 1] - y, b.body.position[3 * i + 2] - z);
    if (d < d_best) best = i, d_best = d;
  }
  return best;
}

// A normal shot through (impact_x, 0) of a 1.2 mm sphere moving on at sphere_vz at the end.
ShotOnPanel shot(double impact_x, double sphere_vz, bool perforated = false, double lean_dx_dz = 0.0) {
  return {kT, impact_x, lean_dx_dz, 0.0012, sphere_vz, perforated};
}

// Moves particle i by dz along the normal.
void move(Block& b, std::size_t i, double dz) { b.p.x[3 * i + 2] += dz; }

TEST(MacroPanelDamage, CraterAndScabAreWhereTheFaceLayersLeftTheirPlace) {
  Block b = block();
  PanelDamage none = panel_damage(b.p, b.body.position, shot(0.0, 100.0));
  EXPECT_EQ(none.front_crater_diameter_m, 0.0);
  EXPECT_EQ(none.rear_scab_diameter_m, 0.0);
  EXPECT_EQ(none.front_crater_depth_m, 0.0);
  EXPECT_EQ(none.rear_scab_depth_m, 0.0);
  // Entry layer (z = 0.5 mm): moved by 0.6 h at r = 0 and r = 2 mm; a particle of the second layer moved at
  // r = 3 mm does not count; one moved by 0.4 h (< kMovedShare) at r = 3 mm neither. Exit layer: r = 1 mm.
  move(b, at(b, 0, 0, 0.0005), 0.0006);
  move(b, at(b, 0.002, 0, 0.0005), -0.0006);
  move(b, at(b, 0.003, 0, 0.0015), 0.002);
  move(b, at(b, -0.003, 0, 0.0005), 0.0004);
  move(b, at(b, 0, 0.001, 0.0035), 0.0006);
  const PanelDamage d = panel_damage(b.p, b.body.position, shot(0.0, 100.0));
  EXPECT_NEAR(d.front_crater_diameter_m, 0.004, 1e-12);
  EXPECT_NEAR(d.rear_scab_diameter_m, 0.002, 1e-12);
  // Measured from the impact point: 1 mm off the axis along x, the entry layer's farthest is 2 mm away.
  EXPECT_NEAR(panel_damage(b.p, b.body.position, shot(-0.001, 100.0)).front_crater_diameter_m, 0.006, 1e-12);
}

TEST(MacroPanelDamage, DebrisIsWhatLeftEitherFaceAndThePlugWhatMovesWithTheSphere) {
  Block b = block();
  const std::size_t front = at(b, 0, 0, 0.0005), rear1 = at(b, 0, 0, 0.0035), rear2 = at(b, 0.001, 0, 0.0035),
                    back = at(b, 0.002, 0, 0.0035);
  b.p.x[3 * front + 2] = -0.001;  // thrown back out of the entry face
  b.p.v[3 * front + 2] = -30.0;
  b.p.x[3 * rear1 + 2] = b.p.x[3 * rear2 + 2] = 0.006;  // out of the exit face, moving on
  b.p.v[3 * rear1 + 2] = 80.0;
  b.p.v[3 * rear2 + 2] = 20.0;
  b.p.x[3 * back + 2] = 0.006;  // out of the exit face, but moving back towards it: not debris
  b.p.v[3 * back + 2] = -1.0;
  const double m = b.p.mass[front];
  const PanelDamage d = panel_damage(b.p, b.body.position, shot(0.0, 100.0));
  EXPECT_EQ(d.front_ejecta.particles, 1);
  EXPECT_NEAR(d.front_ejecta.mass_kg, m, 1e-15);
  EXPECT_NEAR(d.front_ejecta.velocity_m_s, -30.0, 1e-12);
  EXPECT_EQ(d.rear_ejecta.particles, 2);
  EXPECT_NEAR(d.rear_ejecta.mass_kg, b.p.mass[rear1] + b.p.mass[rear2], 1e-15);
  EXPECT_NEAR(d.rear_ejecta.velocity_m_s,
              (80.0 * b.p.mass[rear1] + 20.0 * b.p.mass[rear2]) / (b.p.mass[rear1] + b.p.mass[rear2]), 1e-9);
  // The sphere at 100 m/s: the plug is what moves at 50 m/s or faster.
  EXPECT_EQ(d.plug.particles, 1);
  EXPECT_NEAR(d.plug.velocity_m_s, 80.0, 1e-12);
  // Depths: the entry face lost a first-layer particle (centre 0.5 mm: 1 mm deep); the exit face lost two
  // of its last layer (centre 3.5 mm: from 3 mm, 1 mm deep); the one moving back also sits past the face.
  EXPECT_NEAR(d.front_crater_depth_m, 0.001, 1e-12);
  EXPECT_NEAR(d.rear_scab_depth_m, 0.001, 1e-12);
  b.p.x[3 * at(b, 0, 0, 0.0025) + 2] = 0.007;  // a third-layer particle pushed out: the scab 2 mm deep
  b.p.x[3 * at(b, 0, 0, 0.0015) + 2] = -0.002;  // a second-layer one thrown back: the crater 2 mm deep
  const PanelDamage deeper = panel_damage(b.p, b.body.position, shot(0.0, 100.0));
  EXPECT_NEAR(deeper.rear_scab_depth_m, 0.002, 1e-12);
  EXPECT_NEAR(deeper.front_crater_depth_m, 0.002, 1e-12);
  // A sphere that did not go on forward leaves no plug.
  EXPECT_EQ(panel_damage(b.p, b.body.position, shot(0.0, -5.0)).plug.particles, 0);
}

// Sends particle i out behind the exit face with the plug (the sphere at 100 m/s in these tests).
void into_plug(Block& b, std::size_t i) {
  b.p.x[3 * i + 2] = 0.008;
  b.p.v[3 * i + 2] = 90.0;
}

TEST(MacroPanelDamage, TheHoleIsTheNarrowestClearOpeningAlongTheShotLine) {
  Block b = block();
  EXPECT_EQ(panel_damage(b.p, b.body.position, shot(0.0, 100.0)).hole_diameter_m, 0.0);  // intact
  // The 3 x 3 columns around the axis leave with the plug: the nearest material is the column at 2 mm,
  // whose edge is 1.5 mm from the axis, in every slice.
  for (double x : {-0.001, 0.0, 0.001})
    for (double y : {-0.001, 0.0, 0.001})
      for (double z : {0.0005, 0.0015, 0.0025, 0.0035}) into_plug(b, at(b, x, y, z));
  EXPECT_NEAR(panel_damage(b.p, b.body.position, shot(0.0, 100.0)).hole_diameter_m, 0.003, 1e-12);
  // A shot line leaning by 0.25 along x per unit depth passes the column at x = 2 mm nearest at the last
  // layer's centre (z = 3.5 mm, the line at x = 0.875 mm): 1.125 - 0.5 mm clear.
  EXPECT_NEAR(panel_damage(b.p, b.body.position, shot(0.0, 100.0, true, 0.25)).hole_diameter_m, 0.00125, 1e-12);
  // One particle of the ring left at rest in the third layer narrows that slice alone: 1 - 0.5 mm clear.
  const std::size_t rubble = at(b, 0.001, 0, 0.0025);
  b.p.x[3 * rubble] = 0.001, b.p.x[3 * rubble + 1] = 0.0, b.p.x[3 * rubble + 2] = 0.0025, b.p.v[3 * rubble + 2] = 0.0;
  EXPECT_NEAR(panel_damage(b.p, b.body.position, shot(0.0, 100.0)).hole_diameter_m, 0.001, 1e-12);
  // Moved onto the shot line it closes the hole, as loose rubble would.
  b.p.x[3 * rubble] = 0.0;
  EXPECT_EQ(panel_damage(b.p, b.body.position, shot(0.0, 100.0)).hole_diameter_m, 0.0);
}

TEST(MacroPanelDamage, TheRearFaceDeflectionIsItsSignedMeanDisplacementAtTheShotLine) {
  Block b = block();
  EXPECT_EQ(*panel_damage(b.p, b.body.position, shot(0.0, 100.0)).rear_face_deflection_m, 0.0);
  // The exit layer within the sphere's 1.2 mm of the axis: the particle on it and its four neighbours at
  // 1 mm (equal masses). One farther off, at 2 mm, and one of the layer before do not count.
  const std::size_t centre = at(b, 0, 0, 0.0035);
  for (auto [x, y] : {std::pair{0.0, 0.0}, {0.001, 0.0}, {-0.001, 0.0}, {0.0, 0.001}, {0.0, -0.001}})
    move(b, at(b, x, y, 0.0035), 0.0003);
  move(b, centre, 0.0005);
  move(b, at(b, 0.002, 0, 0.0035), 0.005);
  move(b, at(b, 0, 0, 0.0025), 0.005);
  EXPECT_NEAR(*panel_damage(b.p, b.body.position, shot(0.0, 100.0)).rear_face_deflection_m, 0.0004, 1e-12);
  // Signed: a face pulled back towards the entry side is negative.
  for (auto [x, y] : {std::pair{0.0, 0.0}, {0.001, 0.0}, {-0.001, 0.0}, {0.0, 0.001}, {0.0, -0.001}})
    b.p.x[3 * at(b, x, y, 0.0035) + 2] = 0.0035 - 0.0002;
  EXPECT_NEAR(*panel_damage(b.p, b.body.position, shot(0.0, 100.0)).rear_face_deflection_m, -0.0002, 1e-12);
  // Measured where the shot line leaves: off the axis by 2 mm, the particle there and its neighbours.
  EXPECT_GT(*panel_damage(b.p, b.body.position, shot(0.002, 100.0)).rear_face_deflection_m, 0.0);
  // Not defined for a perforated panel: the face there left with the sphere.
  EXPECT_FALSE(panel_damage(b.p, b.body.position, shot(0.0, 100.0, true)).rear_face_deflection_m.has_value());
}

}  // namespace
}  // namespace uhpc::macro
