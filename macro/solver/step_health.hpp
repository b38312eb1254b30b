#pragma once
// What can end a run numerically, and the checks made after every step (the robustness contract of
// ARCHITECTURE.md section 2: the caller writes the last good state and a diagnostic, exit code 1).
//   NonFinite       a position or velocity (of a particle or the sphere) is NaN or infinite
//   InvertedVolume  a particle volume became non-positive or non-finite (stress_update.hpp)
//   OutOfDomain     a particle left the domain box (SolverOptions::domain)
//   StepCollapse    the stable step kept collapsing after max_step_repeats repeats
#include <cmath>
#include <cstdint>

#include "solver/conditions.hpp"
#include "solver/particles.hpp"

namespace uhpc::macro {

enum class StepFailure : std::uint8_t { None, NonFinite, InvertedVolume, OutOfDomain, StepCollapse };

inline const char* to_string(StepFailure f) {
  switch (f) {
    case StepFailure::None: return "none";
    case StepFailure::NonFinite: return "non_finite_state";
    case StepFailure::InvertedVolume: return "inverted_volume";
    case StepFailure::OutOfDomain: return "particle_left_domain";
    case StepFailure::StepCollapse: return "stable_step_collapse";
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
};

// The lowest index of a particle with a non-finite position or velocity, else -1.
inline std::int64_t first_non_finite(const Particles& p) {
  for (std::size_t i = 0; i < 3 * p.n; ++i)
    if (!std::isfinite(p.x[i]) || !std::isfinite(p.v[i])) return static_cast<std::int64_t>(i / 3);
  return -1;
}

// The lowest index of a particle outside `box`, else -1.
inline std::int64_t first_outside(const Particles& p, const Region& box) {
  for (std::size_t i = 0; i < p.n; ++i)
    if (!box.contains(p.x.data() + 3 * i)) return static_cast<std::int64_t>(i);
  return -1;
}

}  // namespace uhpc::macro
