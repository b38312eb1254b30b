#pragma once
// The case file of uhpc-macro (data/macro_*.json), read and validated in one pass: every key is read by
// a typed getter with its range, and Config::finish() rejects any key nobody read. The material block
// is read by material_factory.hpp through the same Config, so a misspelt material key fails too.
// Geometry convention: the target's axis is z, its entry face is z = 0 and its exit face z = T; the
// projectile starts on the axis below the entry face and moves along +z.
#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "bodies/generators.hpp"
#include "solver/explicit_solver.hpp"
#include "uhpc/config.hpp"

namespace uhpc::macro {

struct TargetSettings {
  enum class Shape : std::uint8_t { Box, Disc } shape = Shape::Box;
  std::array<double, 3> box_size_m{};  // box: x, y (centred on the axis) and z (thickness)
  double box_spacing_m = 0.0;
  DiscSpec disc;                       // disc: z0 = 0
  double thickness_m() const { return shape == Shape::Box ? box_size_m[2] : disc.thickness_m; }
};

struct ProjectileSettings {
  double mass_kg = 0.0;
  double radius_m = 0.0;
  double initial_gap_m = 0.0;  // between the sphere and the entry face, along the axis
  double velocity_m_s = 0.0;   // speed along the flight direction
  // The impact geometry: the flight direction leans obliquity_deg from the target's normal (+z) towards
  // +x, and the sphere first touches the entry face offset_m from the axis along +x (0, 0: a normal
  // impact on the axis, the paper's shots).
  double obliquity_deg = 0.0;
  double offset_m = 0.0;
  SphereContactOptions contact;
};

// The unit flight direction (sin theta, 0, cos theta): exactly (0, 0, 1) for a normal impact.
Vec3 flight_direction(const ProjectileSettings& projectile);

// How the target's rim is held (support.rim):
//   free   nothing holds it;
//   fixed  the rim band's particles are held at zero velocity;
//   frame  the experiment's steel frame: the impact-side lips and the exit-side plate as two rigid,
//          frictionless walls over the rim band, at the band's outermost particle surfaces at rest, so
//          the band cannot move along the axis either way but slides freely in its plane.
// The rim band: particles within rim_width_m of the lateral boundary.
struct SupportSettings {
  enum class Rim : std::uint8_t { Free, Fixed, Frame } rim = Rim::Free;
  double rim_width_m = 0.0;
};

// What fields.h5 holds each step (run.fields, optional): `standard` position, velocity, pressure,
// equivalent stress, volume, dissipated energy and the law's fields; `full` adds the stress tensor, the
// fragment flag, the particle id and the reference position (about 80 % more per step).
enum class FieldSet : std::uint8_t { Standard, Full };

struct RunSettings {
  double end_time_s = 0.0;
  std::int64_t output_interval_steps = 0;  // fields every N steps (and the first and last state)
  FieldSet fields = FieldSet::Standard;
  // < 0: run to end_time_s; else stop this long after the outcome is decided (ImpactTracker: the sphere
  // perforated, stopped in the target or rebounded)
  double stop_after_outcome_s = -1.0;
  // The budget: a run whose first stable step would need more steps than this to reach end_time_s is
  // refused before it starts (exit 2, with the estimate).
  std::int64_t max_steps = 0;
  // The size budget: a target that would hold more particles than this is refused before it is built
  // (exit 2, with the estimated count and memory). At most 2^31 - 1: particle indices are 32-bit.
  std::int64_t max_particles = 0;
  // Every N steps DIR/checkpoint.h5 (checkpoint.hpp), from which --restart goes on bit for bit; 0: none.
  // Writing one drops the shape cache (its lazy rows are rebuilt at the next step), so a run with
  // checkpoints differs from one without by the rows' reuse tolerance, and a resumed run equals the run
  // it resumes exactly.
  std::int64_t checkpoint_interval_steps = 0;
};

struct CaseSettings {
  TargetSettings target;
  ProjectileSettings projectile;
  SupportSettings support;
  RunSettings run;
  SolverOptions solver;
};

// Reads everything but the "material" block (material_factory.hpp); call Config::finish() after both.
CaseSettings read_case(const Config& cfg);

}  // namespace uhpc::macro
