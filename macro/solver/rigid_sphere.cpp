#include "solver/rigid_sphere.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Dense>

#include "solver/parallel.hpp"

namespace uhpc::macro {

double contact_reach(const SphereContactOptions& c, double spacing) {
  return (c.contact_radius_factor > 0.0 ? c.contact_radius_factor : 0.25) * spacing;
}

double contact_gap(const SphereContactOptions& c, double R, double r_I, const double* rel, double* normal) {
  const double d = std::sqrt(rel[0] * rel[0] + rel[1] * rel[1] + rel[2] * rel[2]);
  // A centre at the sphere's centre has no direction: it is pushed along the flight (+z for the offset
  // surface, as before the leading one).
  const bool leading = c.surface == ContactSurface::Leading;
  const Vec3 along = leading ? c.leading_direction : Vec3{0.0, 0.0, 1.0};
  double gap = d - (R + r_I);
  for (int k = 0; k < 3; ++k) normal[k] = d > 0.0 ? rel[k] / d : along[k];
  if (!leading) return gap;
  gap = d - R;
  // The advanced sphere: its centre r_I ahead along the flight direction.
  const double a[3] = {rel[0] - r_I * along[0], rel[1] - r_I * along[1], rel[2] - r_I * along[2]};
  const double da = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  if (da < d) {
    gap = da - R;
    for (int k = 0; k < 3; ++k) normal[k] = da > 0.0 ? a[k] / da : along[k];
  }
  return gap;
}

void RigidSphere::validate() const {
  if (!(mass_kg > 0) || !(radius_m > 0) || !std::isfinite(mass_kg) || !std::isfinite(radius_m))
    throw std::invalid_argument("RigidSphere: mass and radius must be finite and > 0");
  if (!(contact.penalty_scale > 0) || !(contact.contact_radius_factor >= 0) ||
      (contact.model == SphereContactModel::Penalty && !(contact.contact_radius_factor > 0)))
    throw std::invalid_argument("RigidSphere: penalty_scale must be > 0 and contact_radius_factor >= 0 (> 0 for the penalty)");
  if (contact.model == SphereContactModel::Penalty && contact.surface != ContactSurface::Offset)
    throw std::invalid_argument("RigidSphere: the leading contact surface needs the kinematic contact model");
  const Vec3& e = contact.leading_direction;
  if (contact.surface == ContactSurface::Leading && !(std::fabs(e[0] * e[0] + e[1] * e[1] + e[2] * e[2] - 1.0) < 1e-12))
    throw std::invalid_argument("RigidSphere: the leading direction must be a unit vector");
  if (!(contact.friction_coefficient >= 0) || !std::isfinite(contact.friction_coefficient))
    throw std::invalid_argument("RigidSphere: friction_coefficient must be finite and >= 0");
  for (int d = 0; d < 3; ++d)
    if (!std::isfinite(x[d]) || !std::isfinite(v[d]))
      throw std::invalid_argument("RigidSphere: position and velocity must be finite");
}

void SphereContact::initialize(const RigidSphere& sphere, const Particles& p, const double* wave_speed,
                               const RankShare* share) {
  k_.resize(p.n);
  min_travel_distance_ = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < p.n; ++i) {
    if (share && !share->owned[i]) continue;
    // rho0 c0^2 with rho0 = m / V0: the reference stiffness, whatever the current state.
    const double rho0 = p.mass[i] / p.volume0[i];
    k_[i] = sphere.contact.penalty_scale * rho0 * wave_speed[i] * wave_speed[i] * p.spacing[i];
    // The travel limit's distance: the contact radius; h_I / 4 for a zero radius (the particles' centres
    // on the sphere's surface), which would stop the clock.
    min_travel_distance_ = std::min(min_travel_distance_, contact_reach(sphere.contact, p.spacing[i]));
  }
  if (share) min_travel_distance_ = share->min(min_travel_distance_);
  flagged_.assign(p.n, 0);
  // Room for the particles a shell of one contact diameter around the sphere can hold, several times
  // over (debris piles up), so the candidate lists do not grow during a run.
  double r_max = 0.0, h_min = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < p.n; ++i) {
    r_max = std::max(r_max, contact_reach(sphere.contact, p.spacing[i]));
    h_min = std::min(h_min, p.spacing[i]);
  }
  const double outer = sphere.radius_m + 2.0 * r_max;
  const double shell = 4.0 * std::acos(-1.0) / 3.0 * outer * outer * outer;
  const std::size_t room = std::min(p.n, static_cast<std::size_t>(8.0 * shell / (h_min * h_min * h_min)) + 64);
  candidates_.reserve(room);
  gap_.reserve(room);
  normal_.reserve(3 * room);
  force_.reserve(room);
  mass_.reserve(room);
  velocity_.reserve(3 * room);
  local_.reserve(room);
  active_.reserve(room);
  if (share) mine_.reserve(9 * room);  // the records a rank sends (the kinematic contact's 9 doubles are the wider)
}

double SphereContact::travel_limit(const RigidSphere& sphere) const {
  const double speed = std::sqrt(sphere.v[0] * sphere.v[0] + sphere.v[1] * sphere.v[1] + sphere.v[2] * sphere.v[2]);
  return speed > 0.0 ? min_travel_distance_ / speed : std::numeric_limits<double>::infinity();
}

SphereContactSums SphereContact::compute(const RigidSphere& sphere, const Particles& p, double dt, double dt_next,
                                         double* f_contact, const RankShare* share) {
  SphereContactSums sums = sphere.contact.model == SphereContactModel::Penalty
                               ? penalty(sphere, p, dt, f_contact, share)
                               : kinematic(sphere, p, dt, dt_next, f_contact, share);
  sums.critical_step = std::min(sums.critical_step, travel_limit(sphere));
  return sums;
}

void SphereContact::add_friction(const RigidSphere& s, const double* v, double m, const double* n, double normal_force,
                                 double dt, double* f) {
  double w[3], wn = 0.0;
  for (int c = 0; c < 3; ++c) {
    w[c] = v[c] - s.v[c];
    wn += w[c] * n[c];
  }
  for (int c = 0; c < 3; ++c) w[c] -= wn * n[c];  // tangential part
  const double wt = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  if (wt > 0.0) {
    const double ft = std::min(s.contact.friction_coefficient * normal_force, m * wt / dt);
    for (int c = 0; c < 3; ++c) f[c] -= ft * w[c] / wt;
  }
}

SphereContactSums SphereContact::penalty(const RigidSphere& s, const Particles& p, double dt, double* f_contact,
                                         const RankShare* share) {
  const std::int64_t n = static_cast<std::int64_t>(p.n);
  double fx = 0.0, fy = 0.0, fz = 0.0, energy = 0.0, ksum = 0.0;
  const bool friction = s.contact.friction_coefficient > 0.0;
  double dt_min = std::numeric_limits<double>::infinity();
  std::int64_t count = 0;
  const double reach_factor = s.contact.contact_radius_factor;
  if (share) mine_.clear();
#pragma omp parallel for schedule(static) reduction(+ : fx, fy, fz, energy, ksum, count) reduction(min : dt_min) if (n >= kParallelMinParticles && !share)
  for (std::int64_t i = 0; i < n; ++i) {
    double* f = f_contact + 3 * i;
    f[0] = f[1] = f[2] = 0.0;
    if (share && !share->owned[static_cast<std::size_t>(i)]) continue;  // a ghost: its owner's
    const double* x = p.x.data() + 3 * i;
    const double r[3] = {x[0] - s.x[0], x[1] - s.x[1], x[2] - s.x[2]};
    const double reach = s.radius_m + reach_factor * p.spacing[i];
    const double d2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
    // d = 0 (a particle at the very centre) has no direction; it cannot happen before the particle has
    // crossed a whole radius against the penalty, long after the run has failed its checks.
    if (d2 >= reach * reach || d2 == 0.0) continue;
    const double d = std::sqrt(d2);
    const double delta = reach - d;
    const double magnitude = k_[i] * delta;
    const double normal[3] = {r[0] / d, r[1] / d, r[2] / d};
    for (int c = 0; c < 3; ++c) f[c] = magnitude * normal[c];
    if (friction) add_friction(s, p.v.data() + 3 * i, p.mass[i], normal, magnitude, dt, f);
    if (share)  // summed below over every rank's pairs in the order of their ids
      mine_.insert(mine_.end(), {static_cast<double>(share->ids[static_cast<std::size_t>(i)]), f[0], f[1], f[2],
                                 0.5 * k_[i] * delta * delta, k_[i]});
    fx -= f[0];
    fy -= f[1];
    fz -= f[2];
    energy += 0.5 * k_[i] * delta * delta;
    ksum += k_[i];
    ++count;
    dt_min = std::min(dt_min, 2.0 * std::sqrt(p.mass[i] / k_[i]));
  }
  if (share) {
    // The sums one process makes, particle after particle: the pairs of every rank in the order of their
    // ids (ids below 2^53 are exact in a double), added from zero as the loop above adds them.
    constexpr std::size_t kWidth = 6;
    share->gather(mine_, all_);
    const std::size_t m = all_.size() / kWidth;
    order_.resize(m);
    for (std::size_t c = 0; c < m; ++c) order_[c] = c;
    std::sort(order_.begin(), order_.end(), [&](std::size_t a, std::size_t b) { return all_[kWidth * a] < all_[kWidth * b]; });
    fx = fy = fz = energy = ksum = 0.0;
    for (const std::size_t c : order_) {
      const double* r = all_.data() + kWidth * c;
      fx -= r[1];
      fy -= r[2];
      fz -= r[3];
      energy += r[4];
      ksum += r[5];
    }
    count = static_cast<std::int64_t>(m);
    dt_min = share->min(dt_min);
  }
  SphereContactSums sums;
  sums.force_on_sphere = {fx, fy, fz};
  sums.stored_energy = energy;
  sums.particles_in_contact = count;
  sums.critical_step = count > 0 ? std::min(dt_min, 2.0 * std::sqrt(s.mass_kg / ksum)) : dt_min;
  return sums;
}

SphereContactSums SphereContact::kinematic(const RigidSphere& s, const Particles& p, double dt, double dt_next,
                                           double* f_contact, const RankShare* share) {
  const std::int64_t n = static_cast<std::int64_t>(p.n);
  // The forces act over the second half kick of this step and the first of the next, so they move the
  // position after the next drift by dt2 = dt_next (dt + dt_next) / 2 per unit acceleration; the drift
  // itself is dt_next times the current (mid-step) velocity.
  const double dt2 = 0.5 * dt_next * (dt + dt_next);
  const double xs[3] = {s.x[0] + dt_next * s.v[0], s.x[1] + dt_next * s.v[1], s.x[2] + dt_next * s.v[2]};
  const double reach_factor = s.contact.contact_radius_factor;
  // 1. Candidates: the particles whose predicted centre comes within one contact radius of touching
  // (a margin for the sphere's own correction), in index order whatever the threads.
#pragma omp parallel for schedule(static) if (n >= kParallelMinParticles)
  for (std::int64_t i = 0; i < n; ++i) {
    double* f = f_contact + 3 * i;
    f[0] = f[1] = f[2] = 0.0;
    double d2 = 0.0;
    for (int c = 0; c < 3; ++c) {
      const double a = (p.f_int[3 * i + c] + p.f_ext[3 * i + c]) / p.mass[i];
      const double x = p.x[3 * i + c] + dt_next * p.v[3 * i + c] + dt2 * a;
      d2 += (x - xs[c]) * (x - xs[c]);
    }
    const double limit = s.radius_m + 2.0 * contact_reach(s.contact, p.spacing[i]);  // candidates' margin
    flagged_[i] = d2 < limit * limit;
  }
  candidates_.clear();
  for (std::int64_t i = 0; i < n; ++i)
    if (flagged_[i] && (!share || share->owned[static_cast<std::size_t>(i)])) candidates_.push_back(static_cast<std::int32_t>(i));
  std::size_t m = candidates_.size();
  gap_.resize(m);
  normal_.resize(3 * m);
  mass_.resize(m);
  velocity_.resize(3 * m);
  for (std::size_t c = 0; c < m; ++c) {
    const std::size_t i = static_cast<std::size_t>(candidates_[c]);
    double r[3], now[3], unused[3];
    for (int k = 0; k < 3; ++k) {
      const double a = (p.f_int[3 * i + k] + p.f_ext[3 * i + k]) / p.mass[i];
      r[k] = p.x[3 * i + k] + dt_next * p.v[3 * i + k] + dt2 * a - xs[k];
      now[k] = p.x[3 * i + k] - s.x[k];
    }
    const double r_I = reach_factor * p.spacing[i];
    // The gap to close: an overlap left by a change of the step (the prediction assumes the next step
    // equals this one) is held, not pushed out, so the contact never throws a particle off.
    gap_[c] = contact_gap(s.contact, s.radius_m, r_I, r, normal_.data() + 3 * c) -
              std::min(0.0, contact_gap(s.contact, s.radius_m, r_I, now, unused));
    mass_[c] = p.mass[i];
    for (int k = 0; k < 3; ++k) velocity_[3 * c + k] = p.v[3 * i + k];
  }
  local_.assign(candidates_.begin(), candidates_.end());
  if (share) gather_candidates(*share);
  m = gap_.size();
  force_.resize(m);
  active_.resize(m);
  for (std::size_t c = 0; c < m; ++c) active_[c] = gap_[c] < 0.0;
  // 2. The active set: the forces that close every predicted gap of the active particles, the sphere
  // recoiling under their sum S. Particles pulled (F < 0) leave; particles the recoil meets join.
  const double M = s.mass_kg;
  Eigen::Vector3d S = Eigen::Vector3d::Zero();
  for (int iteration = 0; iteration < 64; ++iteration) {
    Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
    Eigen::Vector3d b = Eigen::Vector3d::Zero();
    for (std::size_t c = 0; c < m; ++c) {
      if (!active_[c]) continue;
      const Eigen::Vector3d nc(normal_.data() + 3 * c);
      const double mass = mass_[c];
      A += (mass / M) * nc * nc.transpose();
      b += (-mass * gap_[c] / dt2) * nc;
    }
    S = A.ldlt().solve(b);
    bool changed = false;
    for (std::size_t c = 0; c < m; ++c) {
      const Eigen::Vector3d nc(normal_.data() + 3 * c);
      const double recoil = nc.dot(S) / M;  // the sphere's correction seen along n, per dt^2
      if (active_[c]) {
        force_[c] = mass_[c] * (-gap_[c] / dt2 - recoil);
        if (force_[c] < 0.0) active_[c] = 0, changed = true;
      } else if (gap_[c] + dt2 * recoil < 0.0) {
        active_[c] = 1, changed = true;
      }
    }
    if (!changed) break;
  }
  // 3. The pair forces (and friction), equal and opposite.
  SphereContactSums sums;
  sums.critical_step = std::numeric_limits<double>::infinity();
  const bool friction = s.contact.friction_coefficient > 0.0;
  double on_sphere[3] = {0.0, 0.0, 0.0};
  for (std::size_t c = 0; c < m; ++c) {
    if (!active_[c] || !(force_[c] > 0.0)) continue;
    double f[3];
    const double* nc = normal_.data() + 3 * c;
    for (int k = 0; k < 3; ++k) f[k] = force_[c] * nc[k];
    if (friction) add_friction(s, velocity_.data() + 3 * c, mass_[c], nc, force_[c], 0.5 * (dt + dt_next), f);  // the kicks' duration
    for (int k = 0; k < 3; ++k) on_sphere[k] -= f[k];
    if (local_[c] >= 0)
      for (int k = 0; k < 3; ++k) f_contact[3 * static_cast<std::size_t>(local_[c]) + k] = f[k];
    ++sums.particles_in_contact;
  }
  sums.force_on_sphere = {on_sphere[0], on_sphere[1], on_sphere[2]};
  return sums;
}

void SphereContact::gather_candidates(const RankShare& share) {
  // A record a candidate: its id, gap, normal, mass and velocity (9 doubles; ids below 2^53 are exact).
  constexpr std::size_t kWidth = 9;
  const std::size_t mine = gap_.size();
  mine_.resize(kWidth * mine);
  for (std::size_t c = 0; c < mine; ++c) {
    double* r = mine_.data() + kWidth * c;
    r[0] = static_cast<double>(share.ids[static_cast<std::size_t>(candidates_[c])]);
    r[1] = gap_[c];
    for (int k = 0; k < 3; ++k) r[2 + k] = normal_[3 * c + k], r[6 + k] = velocity_[3 * c + k];
    r[5] = mass_[c];
  }
  share.gather(mine_, all_);
  const std::size_t m = all_.size() / kWidth;
  order_.resize(m);
  for (std::size_t c = 0; c < m; ++c) order_[c] = c;
  std::sort(order_.begin(), order_.end(), [&](std::size_t a, std::size_t b) { return all_[kWidth * a] < all_[kWidth * b]; });
  gap_.resize(m);
  normal_.resize(3 * m);
  mass_.resize(m);
  velocity_.resize(3 * m);
  local_.assign(m, -1);
  std::size_t own = 0;  // this rank's candidates, ascending ids as the gathered order meets them
  for (std::size_t c = 0; c < m; ++c) {
    const double* r = all_.data() + kWidth * order_[c];
    gap_[c] = r[1];
    for (int k = 0; k < 3; ++k) normal_[3 * c + k] = r[2 + k], velocity_[3 * c + k] = r[6 + k];
    mass_[c] = r[5];
    if (own < mine && static_cast<double>(share.ids[static_cast<std::size_t>(candidates_[own])]) == r[0])
      local_[c] = candidates_[own++];
  }
}

}  // namespace uhpc::macro
