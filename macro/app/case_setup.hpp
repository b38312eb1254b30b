#pragma once
// Builds the solver of a case: the target's particles (centred on the z axis, entry face z = 0), the
// material, the rim support and the projectile.
#include <cstdint>
#include <string>
#include <vector>

#include "case_config.hpp"
#include "material_factory.hpp"
#include "solver/explicit_solver.hpp"

namespace uhpc::macro {

// The target's particle count before it is built (exact for a box, estimated for a disc).
double estimated_particle_count(const TargetSettings& target);
ParticleBody make_target_body(const TargetSettings& target);
// The inputs that count comes from, with their values, for messages: "target.size_m = [...] m, target.spacing_m
// = 0.004 m" (a box) or the disc's radius, thickness and spacings.
std::string particle_count_inputs(const TargetSettings& target);
// The spacing inputs alone: "target.spacing_m = 0.004 m", or the disc's "target.h_axis_m = ..., target.h_rim_m = ...".
std::string spacing_inputs(const TargetSettings& target);

// The rim band held by a fixed or framed rim: particles within rim_width of the lateral boundary (|x|
// or |y| near the box's sides; r near the disc's radius). Empty for a free rim.
std::vector<std::int32_t> rim_particles(const Particles& p, const CaseSettings& s);
std::vector<std::int32_t> rim_particles(const double* x, std::size_t n, const CaseSettings& s);  // x: 3n

// The frame (support.rim = frame): the impact-side lips and the exit-side plate, two rigid frictionless
// walls over the band, each touching the band's outermost particle surface at rest.
std::vector<Wall> frame_walls(const Particles& p, const std::vector<std::int32_t>& band);
std::vector<Wall> frame_walls(const double* x, const double* spacing, const std::vector<std::int32_t>& band);

// The projectile at rest position: on the axis, its surface initial_gap_m below the entry face.
RigidSphere make_projectile(const ProjectileSettings& s);

// The initialized solver (initialize() called).
ExplicitSolver make_solver(const CaseSettings& s, const ParticleBody& body, MaterialSet material);

// One rank's part of the case in a distributed run (distributed/distributed_run.hpp: its SolverFactory):
// the solver over the particles `ids` of `body` (ascending global ids), in their order, with fresh states
// of `law`'s law, the rim support and the projectile, NOT initialized. The conditions are judged on the
// whole body (the frame's walls touch the whole band), so each particle starts as in make_solver.
ExplicitSolver make_part_solver(const CaseSettings& s, const ParticleBody& body, const MaterialSet& law,
                                const std::vector<std::uint32_t>& ids);

}  // namespace uhpc::macro
