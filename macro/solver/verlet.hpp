#pragma once
// Velocity Verlet (central difference) in two half kicks around a drift. The integrator knows nothing
// of the physics: the physics offers its arrays, computes accelerations in the new configuration
// (given the step, for rate-dependent and incremental laws) and imposes its velocity constraints.
//   v += dt/2 a;  constrain;  x += dt v;  a = physics(x, v, dt);  v += dt/2 a;  constrain.
// With a constant dt and position-only (or exactly reversible incremental) physics the scheme is
// time-reversible: negating v and stepping again retraces the trajectory.
#include <cstddef>
#include <cstdint>

#include "solver/parallel.hpp"

namespace uhpc::macro {

struct VerletArrays {
  double* x;
  double* x_prev;
  double* v;
  const double* a;
  std::size_t size;  // number of scalars (3 per particle)
};

template <class Physics>
void velocity_verlet_step(Physics& physics, double dt) {
  const VerletArrays s = physics.verlet_arrays();
  const std::int64_t n = static_cast<std::int64_t>(s.size);
  const double half = 0.5 * dt;
#pragma omp parallel for schedule(static) if (n >= 3 * kParallelMinParticles)
  for (std::int64_t i = 0; i < n; ++i) {
    s.v[i] += half * s.a[i];
  }
  physics.constrain_velocities();
#pragma omp parallel for schedule(static) if (n >= 3 * kParallelMinParticles)
  for (std::int64_t i = 0; i < n; ++i) {
    s.x_prev[i] = s.x[i];
    s.x[i] += dt * s.v[i];
  }
  physics.compute_accelerations(dt);
#pragma omp parallel for schedule(static) if (n >= 3 * kParallelMinParticles)
  for (std::int64_t i = 0; i < n; ++i) s.v[i] += half * s.a[i];
  physics.constrain_velocities();
}

}  // namespace uhpc::macro
