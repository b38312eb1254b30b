#include "solver/particles.hpp"

#include <stdexcept>

namespace uhpc::macro {

Particles Particles::from_body(const ParticleBody& body, double density_kg_m3, double support_factor) {
  if (!(density_kg_m3 > 0) || !(support_factor > 0))
    throw std::invalid_argument("Particles::from_body: density and support factor must be > 0");
  Particles p;
  p.n = body.size();
  const std::size_t n = p.n;
  p.x = body.position;
  p.x_prev = p.x;
  p.x_mid = p.x;
  p.v.assign(3 * n, 0.0);
  p.a.assign(3 * n, 0.0);
  p.f_int.assign(3 * n, 0.0);
  p.f_ext.assign(3 * n, 0.0);
  p.f_contact.assign(3 * n, 0.0);
  p.volume = body.volume;
  p.volume0 = body.volume;
  p.spacing = body.spacing;
  p.mass.resize(n);
  p.density.assign(n, density_kg_m3);
  p.support.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    p.mass[i] = density_kg_m3 * body.volume[i];
    p.support[i] = support_factor * body.spacing[i];
  }
  p.stress.assign(9 * n, 0.0);
  p.bulk_q.assign(n, 0.0);
  p.vel_grad.assign(9 * n, 0.0);
  p.wave_speed.assign(n, 0.0);
  p.work.assign(n, 0.0);
  return p;
}

}  // namespace uhpc::macro
