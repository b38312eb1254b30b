#include "case_setup.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

namespace uhpc::macro {

double estimated_particle_count(const TargetSettings& t) {
  if (t.shape == TargetSettings::Shape::Disc) return disc_particle_estimate(t.disc);
  return box_particle_count(t.box_size_m[0], t.box_size_m[1], t.box_size_m[2], t.box_spacing_m);
}

std::string spacing_inputs(const TargetSettings& t) {
  if (t.shape == TargetSettings::Shape::Disc)
    return fmt::format("target.h_axis_m = {:g} m, target.h_rim_m = {:g} m", t.disc.h_axis_m, t.disc.h_rim_m);
  return fmt::format("target.spacing_m = {:g} m", t.box_spacing_m);
}

std::string particle_count_inputs(const TargetSettings& t) {
  if (t.shape == TargetSettings::Shape::Disc)
    return fmt::format("target.radius_m = {:g} m, target.thickness_m = {:g} m, {}", t.disc.radius_m, t.disc.thickness_m,
                       spacing_inputs(t));
  return fmt::format("target.size_m = [{:g}, {:g}, {:g}] m, {}", t.box_size_m[0], t.box_size_m[1], t.box_size_m[2],
                     spacing_inputs(t));
}

ParticleBody make_target_body(const TargetSettings& t) {
  if (t.shape == TargetSettings::Shape::Disc) return disc_body(t.disc);
  ParticleBody body = box_body(t.box_size_m[0], t.box_size_m[1], t.box_size_m[2], t.box_spacing_m);
  for (std::size_t i = 0; i < body.size(); ++i) {  // centre x and y on the axis; z in [0, thickness]
    body.position[3 * i] -= 0.5 * t.box_size_m[0];
    body.position[3 * i + 1] -= 0.5 * t.box_size_m[1];
  }
  return body;
}

std::vector<std::int32_t> rim_particles(const Particles& p, const CaseSettings& s) { return rim_particles(p.x.data(), p.n, s); }

std::vector<std::int32_t> rim_particles(const double* xs, std::size_t n, const CaseSettings& s) {
  std::vector<std::int32_t> out;
  if (s.support.rim == SupportSettings::Rim::Free) return out;
  const double w = s.support.rim_width_m;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = xs[3 * i], y = xs[3 * i + 1];
    bool rim;
    if (s.target.shape == TargetSettings::Shape::Disc) {
      rim = std::hypot(x, y) > s.target.disc.radius_m - w;
    } else {
      rim = std::fabs(x) > 0.5 * s.target.box_size_m[0] - w || std::fabs(y) > 0.5 * s.target.box_size_m[1] - w;
    }
    if (rim) out.push_back(static_cast<std::int32_t>(i));
  }
  return out;
}

std::vector<Wall> frame_walls(const Particles& p, const std::vector<std::int32_t>& band) {
  return frame_walls(p.x.data(), p.spacing.data(), band);
}

std::vector<Wall> frame_walls(const double* x, const double* spacing, const std::vector<std::int32_t>& band) {
  // The lips (impact side: the solid is below them) and the plate (exit side: the solid is above it)
  // touch the band's outermost particle surfaces, z -+ h/2, so nothing is pressed at rest.
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (const std::int32_t j : band) {
    const std::size_t i = static_cast<std::size_t>(j);
    lo = std::min(lo, x[3 * i + 2] - 0.5 * spacing[i]);
    hi = std::max(hi, x[3 * i + 2] + 0.5 * spacing[i]);
  }
  Wall lips, plate;
  lips.point = {0.0, 0.0, lo};
  lips.normal = {0.0, 0.0, 1.0};
  lips.particles = band;
  plate.point = {0.0, 0.0, hi};
  plate.normal = {0.0, 0.0, -1.0};
  plate.particles = band;
  return {lips, plate};
}

RigidSphere make_projectile(const ProjectileSettings& s) {
  RigidSphere sphere;
  sphere.mass_kg = s.mass_kg;
  sphere.radius_m = s.radius_m;
  // The centre starts initial_gap_m from the entry face along its normal, on the flight line through the
  // centre at first touch, (offset, 0, -R). A normal impact on the axis is (0, 0, -(R + gap)) exactly.
  const Vec3 d = flight_direction(s);
  const double travel = s.initial_gap_m / d[2];
  sphere.x = {s.offset_m - travel * d[0], 0.0, -s.radius_m - travel * d[2]};
  sphere.v = {s.velocity_m_s * d[0], s.velocity_m_s * d[1], s.velocity_m_s * d[2]};
  sphere.contact = s.contact;
  sphere.contact.leading_direction = d;  // the leading surface's front: the flight direction at impact
  return sphere;
}

namespace {
// The rim support and the projectile of solver, whose particles are some of `whole`'s (all of them for
// one process): the band is the solver's own particles in it; the frame's walls touch the whole band.
void set_conditions(ExplicitSolver& solver, const CaseSettings& s, const ParticleBody& whole, bool is_whole) {
  const std::vector<std::int32_t> band = rim_particles(solver.particles(), s);
  if (s.support.rim == SupportSettings::Rim::Fixed) {
    PrescribedVelocity rim;
    rim.particles = band;
    solver.add_prescribed_velocity(rim);
  } else if (s.support.rim == SupportSettings::Rim::Frame) {
    const std::vector<std::int32_t> whole_band = is_whole ? band : rim_particles(whole.position.data(), whole.size(), s);
    for (Wall w : frame_walls(whole.position.data(), whole.spacing.data(), whole_band)) {
      w.particles = band;
      solver.add_wall(w);
    }
  }
  solver.set_sphere(make_projectile(s.projectile));
}
}  // namespace

ExplicitSolver make_solver(const CaseSettings& s, const ParticleBody& body, MaterialSet material) {
  const double rho = reference_density(material);
  ExplicitSolver solver(Particles::from_body(body, rho, s.solver.support_factor), std::move(material), s.solver);
  set_conditions(solver, s, body, true);
  solver.initialize();
  return solver;
}

ExplicitSolver make_part_solver(const CaseSettings& s, const ParticleBody& body, const MaterialSet& law,
                                const std::vector<std::uint32_t>& ids) {
  ParticleBody part;
  part.position.reserve(3 * ids.size());
  part.volume.reserve(ids.size());
  part.spacing.reserve(ids.size());
  for (const std::uint32_t id : ids) {
    if (id >= body.size()) throw std::invalid_argument("make_part_solver: a particle id beyond the body");
    part.position.insert(part.position.end(), body.position.begin() + 3 * id, body.position.begin() + 3 * id + 3);
    part.volume.push_back(body.volume[id]);
    part.spacing.push_back(body.spacing[id]);
  }
  ExplicitSolver solver(Particles::from_body(part, reference_density(law), s.solver.support_factor),
                        same_law(law, ids.size()), s.solver);
  set_conditions(solver, s, body, false);
  return solver;
}

}  // namespace uhpc::macro
