#pragma once
// What can end a run numerically, and the checks made after every step (the robustness contract of
// docs/architecture.md section 2: the caller writes the last good state and a diagnostic, exit code 1).
//   NonFinite       a position or velocity (of a particle or the sphere) is NaN or infinite
//   InvertedVolume  a particle volume became non-positive or non-finite (stress_update.hpp)
//   OutOfDomain     a particle left the domain box (SolverOptions::domain)
//   StepCollapse    the stable step kept collapsing after max_step_repeats repeats
//   EnergyBalance   the energy balance error exceeds SolverOptions::energy_error_limit times the
//                   energy put in (an instability grows from round-off to 1e20 J in a few steps while
//                   positions stay finite: the last good state must be from before it)
#include <cmath>
#include <cstdint>

#include "solver/conditions.hpp"
#include "solver/energy.hpp"
#include "solver/particles.hpp"

namespace uhpc::macro {

enum class StepFailure : std::uint8_t { None, NonFinite, InvertedVolume, OutOfDomain, StepCollapse, EnergyBalance };

inline const char* to_string(StepFailure f) {
  switch (f) {
    case StepFailure::None: return "none";
    case StepFailure::NonFinite: return "non_finite_state";
    case StepFailure::InvertedVolume: return "inverted_volume";
    case StepFailure::OutOfDomain: return "particle_left_domain";
    case StepFailure::StepCollapse: return "stable_step_collapse";
    case StepFailure::EnergyBalance: return "energy_balance";
  }
  return "unknown";
}

// The failed attempt, recorded before the solver went back to the last good state.
struct FailureReport {
  StepFailure kind = StepFailure::None;
  std::int64_t particle = -1;  // -1: the sphere (NonFinite) or no particle (StepCollapse)
  double time_s = 0.0;         // time at the start of the failed step (the last good state's time)
  double dt_s = 0.0;           // the step that failed
  std::int64_t step = 0;       // index of the failed step (completed steps + 1)
  Vec3 x{}, v{};               // the particle's position and velocity in the failed state
  double volume_m3 = 0.0, volume0_m3 = 0.0;
  double energy_error = 0.0;   // the failed state's relative energy balance error (energy_error_ratio)
};

// |energy balance error| / energy put in (initial kinetic energy plus the magnitude of the external
// work); 0 while nothing has been put in.
inline double energy_error_ratio(const EnergyLedger& e) {
  const double put_in = e.kinetic_initial + std::fabs(e.external);
  return put_in > 0.0 ? std::fabs(e.balance_error()) / put_in : 0.0;
}

// counted (optional, one a particle): only the particles with a non-zero entry are looked at (a
// distributed run's owned particles, RankShare).

// The lowest index of a particle with a non-finite position or velocity, else -1.
inline std::int64_t first_non_finite(const Particles& p, const std::uint8_t* counted = nullptr) {
  for (std::size_t i = 0; i < 3 * p.n; ++i)
    if ((!std::isfinite(p.x[i]) || !std::isfinite(p.v[i])) && (!counted || counted[i / 3])) return static_cast<std::int64_t>(i / 3);
  return -1;
}

// The particle with the largest kinetic energy (-1 for none).
inline std::int64_t most_kinetic_particle(const Particles& p, const std::uint8_t* counted = nullptr) {
  std::int64_t best = -1;
  double most = -1.0;
  for (std::size_t i = 0; i < p.n; ++i) {
    if (counted && !counted[i]) continue;
    const double* v = p.v.data() + 3 * i;
    const double k = p.mass[i] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (k > most) most = k, best = static_cast<std::int64_t>(i);
  }
  return best;
}

// The lowest index of a particle outside `box`, else -1.
inline std::int64_t first_outside(const Particles& p, const Region& box, const std::uint8_t* counted = nullptr) {
  for (std::size_t i = 0; i < p.n; ++i)
    if ((!counted || counted[i]) && !box.contains(p.x.data() + 3 * i)) return static_cast<std::int64_t>(i);
  return -1;
}

}  // namespace uhpc::macro
