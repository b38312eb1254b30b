#include "solver/conditions.hpp"

#include <stdexcept>

namespace uhpc::macro {

PrescribedVelocity prescribe_velocity(const Particles& p, const Region& region, const Vec3& velocity) {
  PrescribedVelocity bc;
  bc.velocity = velocity;
  for (std::size_t i = 0; i < p.n; ++i)
    if (region.contains(p.x.data() + 3 * i)) bc.particles.push_back(static_cast<std::int32_t>(i));
  if (bc.particles.empty()) throw std::invalid_argument("prescribe_velocity: the region holds no particle");
  return bc;
}

void set_initial_velocity(Particles& p, const Region& region, const Vec3& velocity) {
  for (std::size_t i = 0; i < p.n; ++i)
    if (region.contains(p.x.data() + 3 * i))
      for (int d = 0; d < 3; ++d) p.v[3 * i + d] = velocity[d];
}

void set_initial_velocity(Particles& p, const std::function<Vec3(const double* x)>& velocity) {
  for (std::size_t i = 0; i < p.n; ++i) {
    const Vec3 v = velocity(p.x.data() + 3 * i);
    for (int d = 0; d < 3; ++d) p.v[3 * i + d] = v[d];
  }
}

}  // namespace uhpc::macro
