#include "solver/rigid_sphere.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "solver/parallel.hpp"

namespace uhpc::macro {

void RigidSphere::validate() const {
  if (!(mass_kg > 0) || !(radius_m > 0) || !std::isfinite(mass_kg) || !std::isfinite(radius_m))
    throw std::invalid_argument("RigidSphere: mass and radius must be finite and > 0");
  if (!(contact.penalty_scale > 0) || !(contact.contact_radius_factor > 0))
    throw std::invalid_argument("RigidSphere: penalty_scale and contact_radius_factor must be > 0");
  if (!(contact.friction_coefficient >= 0) || !std::isfinite(contact.friction_coefficient))
    throw std::invalid_argument("RigidSphere: friction_coefficient must be finite and >= 0");
  for (int d = 0; d < 3; ++d)
    if (!std::isfinite(x[d]) || !std::isfinite(v[d]))
      throw std::invalid_argument("RigidSphere: position and velocity must be finite");
}

void sphere_contact_stiffness(const Particles& p, const SphereContactOptions& options, std::vector<double>& k) {
  k.resize(p.n);
  for (std::size_t i = 0; i < p.n; ++i) {
    // rho0 c0^2 with rho0 = m / V0: the reference stiffness, whatever the current state.
    const double rho0 = p.mass[i] / p.volume0[i];
    k[i] = options.penalty_scale * rho0 * p.wave_speed[i] * p.wave_speed[i] * p.spacing[i];
  }
}

SphereContactSums sphere_contact_forces(const RigidSphere& s, const Particles& p, const double* k,
                                        double min_contact_radius, double dt, double* f_contact) {
  const std::int64_t n = static_cast<std::int64_t>(p.n);
  double fx = 0.0, fy = 0.0, fz = 0.0, energy = 0.0, ksum = 0.0;
  const double mu = s.contact.friction_coefficient;
  double dt_min = std::numeric_limits<double>::infinity();
  std::int64_t count = 0;
  const double reach_factor = s.contact.contact_radius_factor;
#pragma omp parallel for schedule(static) reduction(+ : fx, fy, fz, energy, ksum, count) reduction(min : dt_min) if (n >= kParallelMinParticles)
  for (std::int64_t i = 0; i < n; ++i) {
    double* f = f_contact + 3 * i;
    f[0] = f[1] = f[2] = 0.0;
    const double* x = p.x.data() + 3 * i;
    const double r[3] = {x[0] - s.x[0], x[1] - s.x[1], x[2] - s.x[2]};
    const double reach = s.radius_m + reach_factor * p.spacing[i];
    const double d2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
    // d = 0 (a particle at the very centre) has no direction; it cannot happen before the particle has
    // crossed a whole radius against the penalty, long after the run has failed its checks.
    if (d2 >= reach * reach || d2 == 0.0) continue;
    const double d = std::sqrt(d2);
    const double delta = reach - d;
    const double magnitude = k[i] * delta;
    for (int c = 0; c < 3; ++c) f[c] = magnitude * r[c] / d;
    if (mu > 0.0) {
      const double* v = p.v.data() + 3 * i;
      double w[3], wn = 0.0;
      for (int c = 0; c < 3; ++c) {
        w[c] = v[c] - s.v[c];
        wn += w[c] * r[c] / d;
      }
      for (int c = 0; c < 3; ++c) w[c] -= wn * r[c] / d;  // tangential part
      const double wt = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
      if (wt > 0.0) {
        const double ft = std::min(mu * magnitude, p.mass[i] * wt / dt);
        for (int c = 0; c < 3; ++c) f[c] -= ft * w[c] / wt;
      }
    }
    fx -= f[0];
    fy -= f[1];
    fz -= f[2];
    energy += 0.5 * k[i] * delta * delta;
    ksum += k[i];
    ++count;
    dt_min = std::min(dt_min, 2.0 * std::sqrt(p.mass[i] / k[i]));
  }
  SphereContactSums sums;
  sums.force_on_sphere = {fx, fy, fz};
  sums.stored_energy = energy;
  sums.stiffness_sum = ksum;
  sums.particles_in_contact = count;
  sums.critical_step = count > 0 ? std::min(dt_min, 2.0 * std::sqrt(s.mass_kg / ksum)) : dt_min;
  const double speed = std::sqrt(s.v[0] * s.v[0] + s.v[1] * s.v[1] + s.v[2] * s.v[2]);
  if (speed > 0.0) sums.critical_step = std::min(sums.critical_step, min_contact_radius / speed);
  return sums;
}

}  // namespace uhpc::macro
