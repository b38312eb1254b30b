#include "bodies/particle_body.hpp"

#include <cmath>
#include <numeric>

namespace uhpc::macro {

void ParticleBody::add(double x, double y, double z, double v) {
  position.insert(position.end(), {x, y, z});
  volume.push_back(v);
  spacing.push_back(std::cbrt(v));
}

double ParticleBody::total_volume() const { return std::accumulate(volume.begin(), volume.end(), 0.0); }

}  // namespace uhpc::macro
