#include "run_outputs.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "material_factory.hpp"
#include "uhpc/atomic_file.hpp"
#include "uhpc/errors.hpp"

namespace uhpc::macro {

FieldOutput::FieldOutput(const std::filesystem::path& dir, const MaterialSet& material, std::optional<FullFields> full)
    : writer_(dir, "fields"), sphere_writer_(dir, "sphere"), records_(material, full.has_value()), full_(full) {}

FieldOutput::FieldOutput(const std::filesystem::path& dir, const MaterialSet& material, const FieldOutputState& resumed,
                         std::optional<FullFields> full)
    : writer_(resumed_writer(dir, "fields", resumed.particle_steps)),
      sphere_writer_(resumed_writer(dir, "sphere", resumed.sphere_steps)),
      records_(material, full.has_value()),
      full_(full),
      last_time_(resumed.last_time_s) {}

// The outputs a restart appends to are inputs of the restart: one that is missing, lacks a step the
// checkpoint recorded or fails its checksums is bad input (exit 2), named by the writer's message.
ParticleFieldWriter FieldOutput::resumed_writer(const std::filesystem::path& dir, const std::string& basename,
                                                const std::vector<XdmfStep>& steps) {
  try {
    return ParticleFieldWriter(dir, basename, steps);
  } catch (const std::runtime_error& e) {
    throw InputError(std::string(e.what()) + " (an output of the run being restarted)");
  }
}

FieldRecords::FieldRecords(const MaterialSet& material, bool full) : full_(full) {
  fields_ = {{"position", "m", 3},         {"velocity", "m/s", 3}, {"pressure", "Pa", 1},
             {"equivalent_stress", "Pa", 1}, {"volume", "m^3", 1},  {"dissipated_J_m3", "J/m^3", 1}};
  // The law's fields, each its own scalar array.
  for (const std::string& name : law_output_fields(material)) fields_.push_back({name, "1", 1}), ++laws_;
  if (full_) fields_.push_back({"stress", "Pa", 6});
  for (const Field& f : fields_) width_ += static_cast<std::size_t>(f.components);
}

void FieldRecords::fill(const ExplicitSolver& s, std::size_t i, double* r) const {
  const Particles& p = s.particles();
  for (int d = 0; d < 3; ++d) r[d] = p.x[3 * i + d], r[3 + d] = p.v[3 * i + d];
  const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> stress(p.stress.data() + 9 * i);
  r[6] = pressure_of(stress);
  r[7] = von_mises(stress);
  r[8] = p.volume[i];
  r[9] = s.dissipated_density(i);
  constexpr std::size_t kLaw = 10;  // the law's fields follow the ten values above (fields_' order)
  law_output_values_at(s.material(), i, r + kLaw);
  if (full_) {  // the stored 3 x 3 (row-major) as XDMF's symmetric Tensor6
    constexpr int kTensor6[6] = {0, 1, 2, 4, 5, 8};
    double* t = r + kLaw + laws_;
    for (int c = 0; c < 6; ++c) t[c] = p.stress[9 * i + kTensor6[c]];
  }
}

void FieldOutput::write(const ExplicitSolver& run, std::size_t n, const RecordSource& record_of,
                        const std::vector<std::uint8_t>& fragments) {
  if (run.time() <= last_time_) return;
  // The records' columns, each field contiguous (components interleaved), in the body's order.
  const std::vector<FieldRecords::Field>& columns = records_.fields();
  std::vector<std::size_t> starts;  // where each column starts in column_
  std::size_t start = 0;
  for (const FieldRecords::Field& f : columns) {
    starts.push_back(start);
    start += n * static_cast<std::size_t>(f.components);
  }
  column_.resize(start);
  std::vector<double> record(records_.width());
  for (std::size_t i = 0; i < n; ++i) {
    record_of(i, record.data());
    const double* r = record.data();
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const auto w = static_cast<std::size_t>(columns[c].components);
      for (std::size_t k = 0; k < w; ++k) column_[starts[c] + w * i + k] = *r++;
    }
  }
  std::vector<ParticleField> fields;  // (the position is the writer's own, not a field)
  for (std::size_t c = 1; c < columns.size(); ++c)
    fields.push_back({columns[c].name, columns[c].units, columns[c].components, column_.data() + starts[c]});
  if (full_) {
    fragment_.resize(n);
    id_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      fragment_[i] = fragments[i] ? 1.0 : 0.0;
      id_[i] = static_cast<double>(i);  // the row: the same particle in every step
    }
    fields.push_back({"fragment", "1", 1, fragment_.data()});
    fields.push_back({"particle_id", "1", 1, id_.data()});
    fields.push_back({"reference_position", "m", 3, full_->reference_position->data()});
  }
  writer_.write_step(run.time(), n, 3, column_.data(), fields);
  const RigidSphere& sphere = run.sphere();
  sphere_writer_.write_step(run.time(), 1, 3, sphere.x.data(),
                            {{"radius", "m", 1, &sphere.radius_m}, {"velocity", "m/s", 3, sphere.v.data()}});
  last_time_ = run.time();
}

History::History() {
  text_ =
      "time_s,step,dt_s,sphere_x_m,sphere_y_m,sphere_z_m,sphere_vx_m_s,sphere_vy_m_s,sphere_vz_m_s,"
      "contact_force_x_N,contact_force_y_N,contact_force_z_N,contact_particles,kinetic_J,kinetic_sphere_J,"
      "internal_J,dissipated_material_J,dissipated_viscous_J,contact_J,contact_stored_J,external_work_J,"
      "energy_balance_error_J,momentum_x_N_s,momentum_y_N_s,momentum_z_N_s,elastic_stored_J,plastic_J,crushing_J,"
      "released_J,stabilization_J,stabilization_stored_J,opening_J\n";
}

void History::add(const ExplicitSolver& s) {
  const EnergyLedger& e = s.ledger();
  const RigidSphere& sp = s.sphere();
  text_ += fmt::format("{:.17g},{},{:.6e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.6e},{:.6e},{:.6e},{},{:.9e},{:.9e},"
                       "{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.6e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},"
                       "{:.9e},{:.9e},{:.9e},{:.9e}\n",
                       s.time(), s.steps(), s.last_dt(), sp.x[0], sp.x[1], sp.x[2], sp.v[0], sp.v[1], sp.v[2],
                       sp.force[0], sp.force[1], sp.force[2], s.contact().particles_in_contact, e.kinetic,
                       e.kinetic_sphere, e.internal, e.material_dissipated, e.viscous, e.contact, e.contact_stored,
                       e.external, e.balance_error(), e.momentum[0], e.momentum[1], e.momentum[2], e.material_stored,
                       e.plastic, e.crushing, e.released(), e.stabilization, e.stabilization_stored, e.opening);
  ++rows_;
}

void History::save(const std::filesystem::path& file) const { write_text_atomic(file, text_); }

const char* to_string(ImpactOutcome outcome) {
  switch (outcome) {
    case ImpactOutcome::Perforated: return "perforated";
    case ImpactOutcome::Embedded: return "embedded";
    case ImpactOutcome::Rebounded: return "rebounded";
    case ImpactOutcome::Undecided: break;
  }
  return "undecided";
}

const char* to_string(EmbeddedBy reason) {
  switch (reason) {
    case EmbeddedBy::AtRest: return "at_rest";
    case EmbeddedBy::WithinEnergyResolution: return "within_energy_resolution";
    case EmbeddedBy::None: break;
  }
  return "";
}

void ImpactTracker::update(const ExplicitSolver& s, double worst_energy_error) {
  decide(s.sphere(), s.ledger(), s.contact().particles_in_contact, s.time(), worst_energy_error);
}

void ImpactTracker::decide(const RigidSphere& sp, const EnergyLedger& e, std::int64_t particles_in_contact,
                           double time_s, double worst_energy_error) {
  if (decided()) return;
  const bool free = particles_in_contact == 0;
  const double target_vz = (e.momentum[2] - e.momentum_sphere[2]) / target_mass_kg;
  // Perforated once the sphere's centre has crossed the exit face and no particle pushes it: from
  // there on it flies free (its rear needs another radius of travel, up to 25 us at the lowest
  // residual speeds, in which nothing changes its velocity).
  if (free && sp.x[2] > thickness_m && sp.v[2] > 0) {
    outcome = ImpactOutcome::Perforated;
  } else if (free && sp.x[2] + sp.radius_m < 0.0 && sp.v[2] < 0) {
    outcome = ImpactOutcome::Rebounded;
  } else if (sp.x[2] > 0.0 && sp.v[2] <= target_vz) {
    outcome = ImpactOutcome::Embedded;
    embedded_by = EmbeddedBy::AtRest;
  } else if (sp.x[2] > 0.0 && e.kinetic_sphere <= worst_energy_error * e.kinetic_initial) {
    outcome = ImpactOutcome::Embedded;
    embedded_by = EmbeddedBy::WithinEnergyResolution;
  } else {
    return;
  }
  outcome_time_s = time_s;
  const Vec3& d = flight_direction;
  residual_velocity_m_s = sp.v[0] * d[0] + sp.v[1] * d[1] + sp.v[2] * d[2];
  residual_speed_m_s = std::sqrt(sp.v[0] * sp.v[0] + sp.v[1] * sp.v[1] + sp.v[2] * sp.v[2]);
  deflection_deg = residual_speed_m_s > 0.0
                       ? std::acos(std::clamp(residual_velocity_m_s / residual_speed_m_s, -1.0, 1.0)) * 180.0 /
                             std::acos(-1.0)
                       : 0.0;
}

double BalanceTracker::energy_error(const ExplicitSolver& s) {
  return std::fabs(s.ledger().balance_error()) / s.ledger().kinetic_initial;
}

double BalanceTracker::momentum_error(const ExplicitSolver& s) {
  const EnergyLedger& e = s.ledger();
  double err = 0.0, ref = 0.0;
  for (int d = 0; d < 3; ++d) {
    const double r = e.momentum[d] - e.momentum_initial[d] - e.external_impulse[d];
    err += r * r;
    ref += e.momentum_initial[d] * e.momentum_initial[d];
  }
  return std::sqrt(err / ref);
}

void BalanceTracker::update(const ExplicitSolver& s) {
  worst_energy = std::fmax(worst_energy, energy_error(s));
  worst_momentum = std::fmax(worst_momentum, momentum_error(s));
}

nlohmann::json energy_partition_json(const EnergyLedger& e) {
  const double lost = e.kinetic_initial - e.kinetic_sphere;
  // kinetic + internal + viscous + contact - external - initial = balance error, and the target starts
  // at rest, so the sphere's loss is the sum of these parts minus the balance error.
  const std::vector<std::pair<const char*, double>> parts = {
      {"target_kinetic_J", e.kinetic - e.kinetic_sphere},
      {"elastic_stored_J", e.material_stored},
      {"plastic_J", e.plastic},
      {"crushing_J", e.crushing},
      {"opening_J", e.opening},
      {"released_J", e.released()},
      {"stabilization_stored_J", e.stabilization_stored},
      {"stabilization_dissipated_J", e.stabilization_dissipated()},
      {"bulk_viscosity_J", e.viscous},
      {"contact_J", e.contact},
      {"supports_J", -e.external},
      {"balance_error_J", -e.balance_error()}};
  nlohmann::json j = {{"sphere_lost_kinetic_J", lost}};
  nlohmann::json shares = nlohmann::json::object();
  for (const auto& [name, value] : parts) {
    j[name] = value;
    shares[name] = lost != 0.0 ? value / lost : 0.0;
  }
  j["shares"] = shares;
  return j;
}

nlohmann::json panel_json(const PanelDamage& panel) {
  const auto debris = [](const Debris& d) {
    return nlohmann::json{{"mass_kg", d.mass_kg}, {"velocity_m_s", d.velocity_m_s}, {"particles", d.particles}};
  };
  return {{"moved_share", kMovedShare},
          {"front_crater_diameter_m", panel.front_crater_diameter_m},
          {"rear_scab_diameter_m", panel.rear_scab_diameter_m},
          {"front_crater_depth_m", panel.front_crater_depth_m},
          {"rear_scab_depth_m", panel.rear_scab_depth_m},
          {"hole_diameter_m", panel.hole_diameter_m},
          {"rear_face_deflection_m", panel.rear_face_deflection_m ? nlohmann::json(*panel.rear_face_deflection_m)
                                                                  : nlohmann::json(nullptr)},
          {"front_ejecta", debris(panel.front_ejecta)},
          {"rear_ejecta", debris(panel.rear_ejecta)},
          {"plug_speed_share", kPlugSpeedShare},
          {"plug", debris(panel.plug)}};
}

nlohmann::json diagnostic_json(const ExplicitSolver& s, const FailureReport& f) {
  nlohmann::json failed = {{"particle", f.particle},
                           {"position_m", f.x},
                           {"velocity_m_s", f.v},
                           {"volume_m3", f.volume_m3},
                           {"reference_volume_m3", f.volume0_m3}};
  if (f.particle < 0) failed["particle"] = nullptr;
  if (f.kind == StepFailure::EnergyBalance) failed["energy_balance_error"] = f.energy_error;  // relative
  return {{"status", "numerical_failure"},
          {"reason", to_string(f.kind)},
          {"failed_step", f.step},
          {"failed_step_dt_s", f.dt_s},
          {"failed_state", failed},
          {"last_good_state", {{"time_s", s.time()}, {"steps", s.steps()}, {"written_to", "fields.h5 (last step)"}}},
          {"domain_m", {{"lo", s.domain().lo}, {"hi", s.domain().hi}}},
          {"step_repeats", s.step_repeats()},
          {"sphere", {{"position_m", s.sphere().x}, {"velocity_m_s", s.sphere().v}}}};
}

}  // namespace uhpc::macro
