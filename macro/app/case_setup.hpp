#pragma once
// Builds the solver of a case: the target's particles (centred on the z axis, entry face z = 0), the
// material, the rim support and the projectile.
#include "case_config.hpp"
#include "material_factory.hpp"
#include "solver/explicit_solver.hpp"

namespace uhpc::macro {

ParticleBody make_target_body(const TargetSettings& target);

// Particles of `body` held fixed by a fixed rim: within rim_width of the lateral boundary (|x| or |y|
// near the box's sides; r near the disc's radius). Empty for a free rim.
std::vector<std::int32_t> rim_particles(const Particles& p, const CaseSettings& s);

// The projectile at rest position: on the axis, its surface initial_gap_m below the entry face.
RigidSphere make_projectile(const ProjectileSettings& s);

// The initialized solver (initialize() called).
ExplicitSolver make_solver(const CaseSettings& s, const ParticleBody& body, MaterialSet material);

}  // namespace uhpc::macro
