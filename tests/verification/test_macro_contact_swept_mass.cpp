// The mass the sphere's contact sweeps (rigid_sphere.hpp, ContactSurface), against geometry: a sphere of
// radius R moving straight through a simple cubic lattice of free particles (no internal forces) touches
// the particles whose centres lie within the contact surface's section across the motion, per unit of
// travel a number pi R_s^2 / h^3, R_s = R + r_I for the offset surface and R for the leading one. The
// lattice count of a disc averaged over the disc's offsets in the lattice's cell is exactly its area
// over h^2, so the test averages the path over an 8 x 8 grid of offsets and counts the particles ever
// touched in a slab four layers deep. The sphere is heavy (it keeps its speed) and the particles
// are free, so the count is the contact's geometry as its step (prediction, active set) applies it.
// Measured: the offset surface sweeps 1.532 / 1.381 / 1.251 times the sphere's own section at 3.0 / 2.25 /
// 1.5 mm (geometry (1 + h / 2R)^2: 1.528 / 1.386 / 1.250), the leading surface 1.004 / 0.994 / 1.001.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "solver/rigid_sphere.hpp"

namespace uhpc::macro {
namespace {

constexpr double kRadius = 0.00635, kSpeed = 100.0, kRho = 2555.7;

// Free particles of spacing h at the positions p.x: at rest, no internal or external force, the mass of a
// cube of side h (what the contact reads).
void make_free(Particles& p, double h) {
  p.n = p.x.size() / 3;
  p.v.assign(3 * p.n, 0.0);
  p.f_int.assign(3 * p.n, 0.0);
  p.f_ext.assign(3 * p.n, 0.0);
  p.mass.assign(p.n, kRho * h * h * h);
  p.volume0.assign(p.n, h * h * h);
  p.spacing.assign(p.n, h);
  p.wave_speed.assign(p.n, 4000.0);
}

// The particles of a slab of a lattice (spacing h, `depth` thick from z = 0) touched by the sphere whose
// path is the z line through (ox, oy); the sphere starts clear of the slab and stops once its rear has
// passed it by 2 h (its section then has passed every particle of the slab). The particles do not act on
// each other and the sphere does not slow down, so the lattice beyond the slab would change nothing.
int touched_in_slab(double h, ContactSurface surface, double ox, double oy, double depth) {
  const int across = static_cast<int>(std::ceil((kRadius + h) / h)) + 2;  // half-width in columns
  const int layers = static_cast<int>(std::lround(depth / h));
  Particles p;
  for (int k = 0; k < layers; ++k)
    for (int j = -across; j <= across; ++j)
      for (int i = -across; i <= across; ++i) p.x.insert(p.x.end(), {i * h, j * h, k * h});
  make_free(p, h);

  RigidSphere s;
  s.mass_kg = 1e9;  // keeps its speed
  s.radius_m = kRadius;
  s.contact.surface = surface;
  s.x = {ox, oy, -kRadius - h};
  s.v = {0.0, 0.0, kSpeed};
  SphereContact contact;
  contact.initialize(s, p, p.wave_speed.data());
  std::vector<double> f(3 * p.n, 0.0);
  std::vector<unsigned char> touched(p.n, 0);
  const double dt = 0.1 * h / kSpeed;  // a tenth of a spacing a step, inside the travel limit (h / 2)
  while (s.x[2] - kRadius < depth + 2.0 * h) {
    contact.compute(s, p, dt, dt, f.data());
    // The solver's kicks at a constant step: the two half kicks of these forces, then the drift.
    for (std::size_t i = 0; i < p.n; ++i) {
      if (f[3 * i] != 0.0 || f[3 * i + 1] != 0.0 || f[3 * i + 2] != 0.0) touched[i] = 1;
      for (int c = 0; c < 3; ++c) {
        p.v[3 * i + c] += f[3 * i + c] / p.mass[i] * dt;
        p.x[3 * i + c] += p.v[3 * i + c] * dt;
      }
    }
    for (int c = 0; c < 3; ++c) s.x[c] += s.v[c] * dt;
  }
  return static_cast<int>(std::count(touched.begin(), touched.end(), 1));
}

// The mean count over an n x n grid of path offsets in the lattice's cell, per layer, over the sphere's
// own section in columns (pi R^2 / h^2).
double swept_over_own_section(double h, ContactSurface surface) {
  constexpr int kOffsets = 8, kLayers = 4;
  double sum = 0.0;
  for (int a = 0; a < kOffsets; ++a)
    for (int b = 0; b < kOffsets; ++b)
      sum += touched_in_slab(h, surface, (a + 0.5) / kOffsets * h, (b + 0.5) / kOffsets * h, kLayers * h);
  const double per_layer = sum / (kOffsets * kOffsets) / kLayers;
  return per_layer / (std::acos(-1.0) * kRadius * kRadius / (h * h));
}

TEST(MacroContactSweptMass, TheLeadingSurfaceSweepsTheSpheresOwnSectionAtEverySpacing) {
  for (const double h : {0.003, 0.00225, 0.0015}) {
    const double offset = swept_over_own_section(h, ContactSurface::Offset);
    const double leading = swept_over_own_section(h, ContactSurface::Leading);
    const double expected_offset = std::pow(1.0 + 0.5 * h / kRadius, 2);
    std::printf("spacing %.2f mm: swept section / pi R^2: offset %.4f (geometry %.4f), leading %.4f\n", 1e3 * h, offset,
                expected_offset, leading);
    EXPECT_NEAR(offset, expected_offset, 0.02 * expected_offset) << "spacing " << h;
    EXPECT_NEAR(leading, 1.0, 0.02) << "spacing " << h;
  }
}

// The gap and normal of both surfaces (contact_gap), with an oblique flight direction e (30 degrees).
TEST(MacroContactSweptMass, TheLeadingSurfaceIsTheSphereAndTheSphereAdvancedAlongTheFlight) {
  const double R = kRadius, r = 0.0015, t = std::acos(-1.0) / 6.0;
  SphereContactOptions offset, leading;
  leading.surface = ContactSurface::Leading;
  leading.leading_direction = {std::sin(t), 0.0, std::cos(t)};
  const Vec3 e = leading.leading_direction, side = {std::cos(t), 0.0, -std::sin(t)};  // side is normal to e
  double n[3];
  const auto at = [](const Vec3& u, double d) { return Vec3{d * u[0], d * u[1], d * u[2]}; };
  // The offset surface: R + r all around, central.
  const Vec3 q = at(side, R + r + 1e-4);
  EXPECT_NEAR(contact_gap(offset, R, r, q.data(), n), 1e-4, 1e-15);
  EXPECT_NEAR(n[0], side[0], 1e-15);
  // The leading surface: R + r ahead on the flight line, R across it and behind; the normals there.
  const Vec3 front = at(e, R + r), across = at(side, R), behind = at(e, -R);
  EXPECT_NEAR(contact_gap(leading, R, r, front.data(), n), 0.0, 1e-15);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(n[k], e[k], 1e-15);
  EXPECT_NEAR(contact_gap(leading, R, r, across.data(), n), 0.0, 1e-15);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(n[k], side[k], 1e-15);
  EXPECT_NEAR(contact_gap(leading, R, r, behind.data(), n), 0.0, 1e-15);
  // Anywhere: the gap is the distance to the nearer sphere less R, the normal its gradient.
  unsigned state = 12345u;
  const auto uniform = [&state] {
    state = state * 1664525u + 1013904223u;
    return (state >> 8) / 16777216.0 - 0.5;
  };
  for (int trial = 0; trial < 200; ++trial) {
    const double x[3] = {0.03 * uniform(), 0.03 * uniform(), 0.03 * uniform()};
    const double d0 = std::hypot(x[0], x[1], x[2]);
    const double d1 = std::hypot(x[0] - r * e[0], x[1] - r * e[1], x[2] - r * e[2]);
    const double g = contact_gap(leading, R, r, x, n);
    EXPECT_NEAR(g, std::min(d0, d1) - R, 1e-15);
    if (std::fabs(d0 - d1) < 1e-6) continue;  // the crease: no gradient
    for (int k = 0; k < 3; ++k) {
      double xp[3] = {x[0], x[1], x[2]}, xm[3] = {x[0], x[1], x[2]}, unused[3];
      xp[k] += 1e-7;
      xm[k] -= 1e-7;
      EXPECT_NEAR((contact_gap(leading, R, r, xp, unused) - contact_gap(leading, R, r, xm, unused)) / 2e-7, n[k], 1e-6);
    }
  }
}

// In the contact's step: a particle on the flight line ends its first contact step on the surface, R + r_I
// from the sphere's centre, moving on with the sphere (restitution 0), for both surfaces; one r_I / 2
// outside the sphere's section is struck by the offset surface and never by the leading one.
TEST(MacroContactSweptMass, TheFlightLineIsStruckAtRPlusRAndTheSectionsEdgeOnlyByTheOffsetSurface) {
  const double h = 0.003, r_I = 0.5 * h, t = std::acos(-1.0) / 6.0;
  const Vec3 e = {std::sin(t), 0.0, std::cos(t)}, side = {std::cos(t), 0.0, -std::sin(t)};
  for (const ContactSurface surface : {ContactSurface::Offset, ContactSurface::Leading}) {
    for (const double lateral : {0.0, kRadius + 0.5 * r_I}) {
      Particles p;
      p.x = {lateral * side[0], lateral * side[1], lateral * side[2]};
      make_free(p, h);
      RigidSphere s;
      s.mass_kg = 1e9;
      s.radius_m = kRadius;
      s.contact.surface = surface;
      s.contact.leading_direction = e;
      const double start = kRadius + 2.0 * h;
      s.x = {-start * e[0], -start * e[1], -start * e[2]};
      s.v = {kSpeed * e[0], kSpeed * e[1], kSpeed * e[2]};
      SphereContact contact;
      contact.initialize(s, p, p.wave_speed.data());
      double f[3];
      const double dt = 0.1 * h / kSpeed;
      bool struck = false;
      for (int step = 0; step < 400 && !struck; ++step) {
        contact.compute(s, p, dt, dt, f);
        struck = f[0] != 0.0 || f[1] != 0.0 || f[2] != 0.0;
        for (int c = 0; c < 3; ++c) {
          p.v[c] += f[c] / p.mass[0] * dt;
          p.x[c] += p.v[c] * dt;
          s.x[c] += s.v[c] * dt;
        }
      }
      const char* name = surface == ContactSurface::Leading ? "leading" : "offset";
      if (lateral > 0.0) {
        EXPECT_EQ(struck, surface == ContactSurface::Offset) << name << ": a particle r_I / 2 outside the section";
        continue;
      }
      ASSERT_TRUE(struck) << name;
      const double d = std::hypot(p.x[0] - s.x[0], p.x[1] - s.x[1], p.x[2] - s.x[2]);
      EXPECT_NEAR(d, kRadius + r_I, 1e-9 * kRadius) << name;
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(p.v[c], s.v[c], 1e-9 * kSpeed) << name;
    }
  }
}

}  // namespace
}  // namespace uhpc::macro
