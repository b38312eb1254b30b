#pragma once
// Boundary and initial conditions of the particle bodies.
#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "solver/particles.hpp"

namespace uhpc::macro {

using Vec3 = std::array<double, 3>;

// An axis-aligned box region [lo, hi] (inclusive) selecting particles by their reference position.
struct Region {
  Vec3 lo{}, hi{};
  bool contains(const double* x) const {
    for (int d = 0; d < 3; ++d)
      if (x[d] < lo[d] || x[d] > hi[d]) return false;
    return true;
  }
};

// Particles whose velocity is held at `velocity` for the whole run ("fixed" is velocity zero). The
// solver books the reactions as external forces (their work and impulse enter the balances).
struct PrescribedVelocity {
  std::vector<std::int32_t> particles;
  Vec3 velocity{};
};
PrescribedVelocity prescribe_velocity(const Particles& p, const Region& region, const Vec3& velocity);

// A rigid, fixed, frictionless planar wall: the half-space (x - point) . normal < 0 is solid (normal,
// unit, points into the free side). A particle touches it when its centre is closer than h_I / 2 (its
// own half spacing: the body's surface, not its particle centres, meets the wall); the penalty force
//   f = k_I delta normal,  delta = h_I / 2 - (x - point) . normal > 0,  k_I = penalty_scale rho_I c_I^2 h_I
// is the stiffness of a cube of material of side h_I, so the contact is as stiff as the body and the
// contact frequency c/h stays within the stable step. The force is conservative: the energy stored
// during contact returns at release, and the wall's work is booked as external work. A wall with a
// list of particles acts on those only (a support over part of the body, e.g. the frame's lips over
// the rim band of a disc); an empty list means every particle.
struct Wall {
  Vec3 point{};
  Vec3 normal{1, 0, 0};
  double penalty_scale = 1.0;
  std::vector<std::int32_t> particles;
};

// Sets v_I = velocity(x_I) for the particles in `region` (all with an empty function is not allowed).
void set_initial_velocity(Particles& p, const Region& region, const Vec3& velocity);
void set_initial_velocity(Particles& p, const std::function<Vec3(const double* x)>& velocity);

}  // namespace uhpc::macro
