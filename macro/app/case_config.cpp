#include "case_config.hpp"

#include <cmath>

#include <fmt/format.h>

#include "uhpc/errors.hpp"

namespace uhpc::macro {

namespace {

TargetSettings read_target(const Config& t) {
  TargetSettings s;
  const std::string shape = t.choice("shape", {"box", "disc"});
  if (shape == "box") {
    s.shape = TargetSettings::Shape::Box;
    const std::vector<double> size = t.numbers("size_m", Range::positive(), 3);
    if (size.size() != 3) t.fail("size_m", fmt::format("expected 3 numbers (x, y, thickness along z), got {}", size.size()));
    s.box_size_m = {size[0], size[1], size[2]};
    s.box_spacing_m = t.number("spacing_m", Range::positive());
    for (int d = 0; d < 3; ++d)
      if (s.box_spacing_m > size[static_cast<std::size_t>(d)])
        t.fail("spacing_m", fmt::format("value {} exceeds the box size", s.box_spacing_m));
  } else {
    s.shape = TargetSettings::Shape::Disc;
    s.disc.radius_m = t.number("radius_m", Range::positive());
    s.disc.thickness_m = t.number("thickness_m", Range::positive());
    s.disc.h_axis_m = t.number("h_axis_m", Range::positive());
    s.disc.h_rim_m = t.number("h_rim_m", Range::positive());
    s.disc.core_radius_m = t.number("core_radius_m", Range::closed(0.0, s.disc.radius_m));
    s.disc.z0_m = 0.0;
    if (s.disc.h_axis_m > s.disc.thickness_m)
      t.fail("h_axis_m", "spacing larger than the thickness leaves no particle layer");
  }
  return s;
}

ProjectileSettings read_projectile(const Config& p) {
  ProjectileSettings s;
  s.mass_kg = p.number("mass_kg", Range::positive());
  s.radius_m = p.number("radius_m", Range::positive());
  s.initial_gap_m = p.number("initial_gap_m", Range::non_negative());
  s.velocity_m_s = p.number("velocity_m_s", Range::positive());
  s.obliquity_deg = p.number("obliquity_deg", Range::closed(0.0, 80.0));
  s.offset_m = p.number("offset_m", Range::non_negative());
  const Config c = p.section("contact");
  s.contact.model = c.choice("model", {"kinematic", "penalty"}) == "penalty" ? SphereContactModel::Penalty
                                                                            : SphereContactModel::Kinematic;
  s.contact.penalty_scale = c.number("penalty_scale", Range::positive());
  // 0: the particles' centres meet the sphere's surface (the kinematic contact only: a penalty needs a reach).
  s.contact.contact_radius_factor = c.number("contact_radius_factor", Range{0.0, 2.0, false, true});
  if (s.contact.model == SphereContactModel::Penalty && s.contact.contact_radius_factor == 0.0)
    c.fail("contact_radius_factor", "value 0 needs model 'kinematic' (the penalty acts over the contact radius)");
  s.contact.friction_coefficient = c.number("friction_coefficient", Range::closed(0.0, 2.0));
  // [choice] optional, "offset" when absent (the contact every case was run with before the option).
  if (c.has("surface"))
    s.contact.surface = c.choice("surface", {"offset", "leading"}) == "leading" ? ContactSurface::Leading
                                                                               : ContactSurface::Offset;
  if (s.contact.model == SphereContactModel::Penalty && s.contact.surface == ContactSurface::Leading)
    c.fail("surface", "value 'leading' needs model 'kinematic' (the penalty's force is the gradient of its offset overlap)");
  return s;
}

SupportSettings read_support(const Config& s) {
  SupportSettings out;
  const std::string rim = s.choice("rim", {"free", "fixed", "frame"});
  out.rim = rim == "fixed" ? SupportSettings::Rim::Fixed : rim == "frame" ? SupportSettings::Rim::Frame : SupportSettings::Rim::Free;
  out.rim_width_m = s.number("rim_width_m", Range::positive());
  return out;
}

RunSettings read_run(const Config& r) {
  RunSettings s;
  s.end_time_s = r.number("end_time_s", Range::positive());
  s.output_interval_steps = r.integer("output_interval_steps", Range::at_least(1));
  // Optional, an output choice only: a case written before it keeps its hash and its files.
  if (r.has("fields")) s.fields = r.choice("fields", {"standard", "full"}) == "full" ? FieldSet::Full : FieldSet::Standard;
  s.stop_after_outcome_s = r.number("stop_after_outcome_s", Range::any());
  s.max_steps = r.integer("max_steps", Range::at_least(1));
  s.max_particles = r.integer("max_particles", Range::closed(1, 2147483647.0));
  s.checkpoint_interval_steps = r.integer("checkpoint_interval_steps", Range::non_negative());
  return s;
}

SolverOptions read_solver(const Config& c) {
  SolverOptions o;
  o.support_factor = c.number("support_factor", Range::closed(1.2, 3.0));
  o.cfl = c.number("cfl", Range{0.0, 1.0, true, false});
  o.stabilization = c.flag("nsni") ? Stabilization::Nsni : Stabilization::None;
  o.nsni_coefficient = c.number("nsni_coefficient", Range{0.0, 4.0, true, false});
  const std::string strain = c.choice("strain_configuration", {"midpoint", "end", "endpoint_average"});
  o.strain_configuration = strain == "midpoint" ? StrainConfiguration::Midpoint
                           : strain == "end"    ? StrainConfiguration::End
                                                : StrainConfiguration::EndpointAverage;
  const Config v = c.section("bulk_viscosity");
  o.viscosity.c_linear = v.number("linear", Range::non_negative());
  o.viscosity.c_quadratic = v.number("quadratic", Range::non_negative());
  o.viscosity.damp_stress_free_points = v.choice("stress_free_points", {"damped", "undamped"}) == "damped";
  o.dt_collapse_fraction = c.number("dt_collapse_fraction", Range{0.0, 1.0, false, true});
  o.max_step_repeats = static_cast<int>(c.integer("max_step_repeats", Range::closed(0, 100)));
  o.energy_error_limit = c.number("energy_error_limit", Range::non_negative());
  o.domain_margin = c.number("domain_margin", Range::positive());
  // The skin of the neighbour search stays at its default; the lazy rows need tolerance < skin / 2.
  o.shape_reuse_tolerance = c.number("shape_reuse_tolerance", Range{0.0, 0.5 * o.neighbour_skin, false, true});
  o.fragment_rcond = c.number("fragment_rcond", Range{0.0, 1.0, false, true});
  return o;
}

}  // namespace

CaseSettings read_case(const Config& cfg) {
  CaseSettings s;
  cfg.accept_any("notes");
  s.target = read_target(cfg.section("target"));
  s.projectile = read_projectile(cfg.section("projectile"));
  s.support = read_support(cfg.section("support"));
  s.run = read_run(cfg.section("run"));
  s.solver = read_solver(cfg.section("solver"));
  const double lateral = s.target.shape == TargetSettings::Shape::Box
                             ? 0.5 * std::fmin(s.target.box_size_m[0], s.target.box_size_m[1])
                             : s.target.disc.radius_m;
  if (s.projectile.radius_m >= lateral)
    cfg.section("projectile").fail("radius_m", "the sphere must be smaller than the target's half width");
  if (s.support.rim != SupportSettings::Rim::Free && s.support.rim_width_m >= lateral)
    cfg.section("support").fail("rim_width_m", "the rim band would cover the whole target");
  // The sphere's first touch must lie inside the target and clear of the held rim band.
  const double clear = lateral - (s.support.rim == SupportSettings::Rim::Free ? 0.0 : s.support.rim_width_m);
  if (s.projectile.offset_m + s.projectile.radius_m >= clear)
    cfg.section("projectile").fail("offset_m", fmt::format("the sphere would first touch the target beyond {:.4g} m from "
                                                           "the axis (offset + radius must be < {:.4g} m: the {})",
                                                           s.projectile.offset_m + s.projectile.radius_m, clear,
                                                           s.support.rim == SupportSettings::Rim::Free ? "target's half width"
                                                                                                      : "inner edge of the rim band"));
  return s;
}

Vec3 flight_direction(const ProjectileSettings& p) {
  if (p.obliquity_deg == 0.0) return {0.0, 0.0, 1.0};
  const double theta = p.obliquity_deg * std::acos(-1.0) / 180.0;
  return {std::sin(theta), 0.0, std::cos(theta)};
}

}  // namespace uhpc::macro
