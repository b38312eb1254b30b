#include "bodies/generators.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace uhpc::macro {

namespace {

const double kPi = std::acos(-1.0);

int divisions(double length, double spacing) { return std::max(1, static_cast<int>(std::lround(length / spacing))); }

}  // namespace

ParticleBody box_body(double lx, double ly, double lz, double spacing) {
  if (!(lx > 0 && ly > 0 && lz > 0 && spacing > 0)) throw std::invalid_argument("box_body: sizes must be > 0");
  const int nx = divisions(lx, spacing), ny = divisions(ly, spacing), nz = divisions(lz, spacing);
  const double dx = lx / nx, dy = ly / ny, dz = lz / nz;
  ParticleBody body;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) body.add((i + 0.5) * dx, (j + 0.5) * dy, (k + 0.5) * dz, dx * dy * dz);
  return body;
}

double disc_spacing_at(const DiscSpec& s, double r) {
  if (r <= s.core_radius_m) return s.h_axis_m;
  const double t = std::clamp((r - s.core_radius_m) / (s.radius_m - s.core_radius_m), 0.0, 1.0);
  return s.h_axis_m + (s.h_rim_m - s.h_axis_m) * t;
}

double box_particle_count(double lx, double ly, double lz, double spacing) {
  const auto cells = [spacing](double l) { return std::max(1.0, std::round(l / spacing)); };
  return cells(lx) * cells(ly) * cells(lz);
}

double disc_particle_estimate(const DiscSpec& s) {
  constexpr int kSamples = 4096;  // midpoint rule; h(r) is piecewise linear, so this is converged
  const double dr = s.radius_m / kSamples;
  double n = s.thickness_m / s.h_axis_m;  // the central column
  for (int i = 0; i < kSamples; ++i) {
    const double r = (i + 0.5) * dr, h = disc_spacing_at(s, r);
    n += 2 * kPi * r * s.thickness_m / (h * h * h) * dr;
  }
  return n;
}

ParticleBody disc_body(const DiscSpec& s) {
  if (!(s.radius_m > 0 && s.thickness_m > 0 && s.h_axis_m > 0 && s.h_rim_m > 0) ||
      !(s.core_radius_m >= 0 && s.core_radius_m < s.radius_m))
    throw std::invalid_argument("disc_body: radius, thickness and spacings must be > 0, 0 <= core radius < radius");

  // Ring boundaries: a central column of cross-section h_axis^2, then rings as wide as the spacing at
  // their middle (one fixed-point pass), rescaled to end exactly at R.
  std::vector<double> b{0.0, s.h_axis_m / std::sqrt(kPi)};
  while (b.back() < s.radius_m) {
    const double w0 = disc_spacing_at(s, b.back());
    b.push_back(b.back() + disc_spacing_at(s, b.back() + 0.5 * w0));
  }
  // Keep whichever of the last two boundaries is closer to R, then stretch to R.
  if (b.size() > 2 && (b.back() - s.radius_m) > (s.radius_m - b[b.size() - 2])) b.pop_back();
  const double stretch = s.radius_m / b.back();
  for (double& v : b) v *= stretch;

  ParticleBody body;
  for (std::size_t k = 0; k + 1 < b.size(); ++k) {
    const double r_in = b[k], r_out = b[k + 1], r_mid = 0.5 * (r_in + r_out);
    const double h = disc_spacing_at(s, r_mid);
    const int n_ring = k == 0 ? 1 : std::max(1, static_cast<int>(std::lround(2 * kPi * r_mid / h)));
    const int n_z = divisions(s.thickness_m, h);
    const double v = kPi * (r_out * r_out - r_in * r_in) * s.thickness_m / (n_ring * n_z);
    // Particles sit at the radius that splits the ring's area in two (its centroid radius in area).
    const double r = k == 0 ? 0.0 : std::sqrt(0.5 * (r_in * r_in + r_out * r_out));
    const double phase = (k % 2) * kPi / n_ring;
    for (int j = 0; j < n_z; ++j) {
      const double z = s.z0_m + (j + 0.5) * s.thickness_m / n_z;
      for (int i = 0; i < n_ring; ++i) {
        const double theta = phase + 2 * kPi * i / n_ring;
        body.add(r * std::cos(theta), r * std::sin(theta), z, v);
      }
    }
  }
  return body;
}

}  // namespace uhpc::macro
