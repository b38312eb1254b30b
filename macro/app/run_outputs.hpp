#pragma once
// The files of a uhpc-macro run (docs/architecture.md section 2), kept apart from the time loop:
//   FieldOutput    fields.h5 + fields.xdmf (ParaView) through uhpc::ParticleFieldWriter: position,
//                  velocity, pressure, equivalent (von Mises) stress, volume, the energy dissipated
//                  per reference volume (dissipated_J_m3), and the law's own fields (Law::output_fields(),
//                  dimensionless)
//   History        history.csv, one row per step: time, projectile, contact, energies, momentum
//   ImpactTracker  the outcome (perforated, embedded, rebounded, undecided) and the residual velocity: the
//                  sphere's axial velocity at the first step at which it is past the exit face and no
//                  particle pushes it (docs/physics.md section 5)
//   BalanceTracker the worst energy and momentum balance errors over the run
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "panel_damage.hpp"
#include "solver/explicit_solver.hpp"
#include "uhpc/xdmf.hpp"

namespace uhpc::macro {

// What a checkpoint records of the field output: the steps each file holds so far.
struct FieldOutputState {
  std::vector<XdmfStep> particle_steps, sphere_steps;
  double last_time_s = -1.0;
};

// The fields of `full` (case_config.hpp FieldSet) beyond the standard ones: the particles' reference
// positions (3n), kept by the caller for the output's lifetime.
struct FullFields {
  const std::vector<double>* reference_position = nullptr;
};

// One particle's values of the field output as one record, its position first: x (3), v (3), pressure,
// von Mises stress, volume, the energy dissipated per reference volume, the law's fields (Law::
// output_fields()), and with the full set the stress (Tensor6: xx, xy, xz, yy, yz, zz). FieldOutput
// writes the body's records; a distributed run's ranks fill their own particles' and rank 0 gathers
// them (ShotStepper::field_records), so no rank needs the whole body's state.
class FieldRecords {
 public:
  struct Field {
    std::string name, units;
    int components;
  };
  FieldRecords(const MaterialSet& material, bool full);
  // The record's fields in its order ("position" first); width() doubles in all.
  const std::vector<Field>& fields() const { return fields_; }
  std::size_t width() const { return width_; }
  // Particle i of `s` into record (width() doubles).
  void fill(const ExplicitSolver& s, std::size_t i, double* record) const;

 private:
  std::vector<Field> fields_;
  std::size_t laws_ = 0, width_ = 0;  // the law's fields; the doubles of a record
  bool full_;
};

class FieldOutput {
 public:
  // Writes DIR/fields.{h5,xdmf} (the particles) and DIR/sphere.{h5,xdmf} (the projectile); with `full`,
  // also the stress tensor, the fragment flag, the particle id and the reference position each step.
  FieldOutput(const std::filesystem::path& dir, const MaterialSet& material, std::optional<FullFields> full = {});
  // Goes on with the files of an interrupted run from what its checkpoint recorded (steps written
  // after the checkpoint are dropped).
  FieldOutput(const std::filesystem::path& dir, const MaterialSet& material, const FieldOutputState& resumed,
              std::optional<FullFields> full = {});
  FieldOutputState state() const { return {writer_.steps(), sphere_writer_.steps(), last_time_}; }
  // Fills particle i's record (FieldRecords) into the buffer given.
  using RecordSource = std::function<void(std::size_t i, double* record)>;
  // Appends a state (skipped when a state of the same time was written last): the time and sphere from
  // `run`, the body's n particles from `record_of` (ShotStepper::field_records), and with the full set
  // their fragment flags (ShotStepper::fragment_flags).
  void write(const ExplicitSolver& run, std::size_t n, const RecordSource& record_of,
             const std::vector<std::uint8_t>& fragments);
  void write_provenance(const Provenance& provenance) {
    writer_.write_provenance(provenance);
    sphere_writer_.write_provenance(provenance);
  }
  std::size_t steps_written() const { return writer_.steps_written(); }

 private:
  static ParticleFieldWriter resumed_writer(const std::filesystem::path& dir, const std::string& basename,
                                            const std::vector<XdmfStep>& steps);
  ParticleFieldWriter writer_;
  // The projectile, one point per step with its radius and velocity (sphere.xdmf: in ParaView, a Glyph
  // of type Sphere scaled by "radius" with scale factor 2 draws it over fields.xdmf).
  ParticleFieldWriter sphere_writer_;
  FieldRecords records_;
  std::optional<FullFields> full_;
  std::vector<double> column_, fragment_, id_;
  double last_time_ = -1.0;
};

class History {
 public:
  History();
  History(std::string text, std::size_t rows) : text_(std::move(text)), rows_(rows) {}  // a checkpoint's
  void add(const ExplicitSolver& solver);
  const std::string& text() const { return text_; }
  void save(const std::filesystem::path& file) const;  // atomic
  std::size_t rows() const { return rows_; }

 private:
  std::string text_;
  std::size_t rows_ = 0;
};

// How the shot ended (result.json "outcome").
enum class ImpactOutcome { Undecided, Perforated, Embedded, Rebounded };
const char* to_string(ImpactOutcome outcome);
// Why a sphere counts as embedded: at rest relative to the target's centre of mass, or its kinetic
// energy below the run's energy-balance error ("at_rest", "within_energy_resolution").
enum class EmbeddedBy : std::uint8_t { None, AtRest, WithinEnergyResolution };
const char* to_string(EmbeddedBy reason);

// Decides the outcome of the shot, step by step:
//   perforated  the sphere's centre is past the exit face, it moves on and no particle pushes it;
//   embedded    its centre is past the entry face and it has stopped: relative to the target (axial
//               velocity <= that of the target's centre of mass), or its kinetic energy has fallen below
//               the run's worst energy-balance error so far (what is left of its motion is below what the
//               run resolves: a sphere drifting at 0.27 % of its impact speed in its crater, or carried at
//               1.9 % by the shear cone that it pushes out of the rear face; a convention, docs/physics.md
//               section 5.8);
//   rebounded   it is back out of the entry face, moving back, and no particle pushes it (a sphere
//               that stops before its centre has passed the entry face is followed until then);
//   undecided   none of these by the end time (reported, never taken for a perforation).
// The residual velocity is the sphere's axial velocity when the outcome was decided.
struct ImpactTracker {
  double thickness_m = 0.0;
  double impact_velocity_m_s = 0.0;
  Vec3 flight_direction{0.0, 0.0, 1.0};  // unit, of the impact (case_config.hpp)
  double target_mass_kg = 0.0;
  ImpactOutcome outcome = ImpactOutcome::Undecided;
  double outcome_time_s = -1.0;
  // At the outcome: the velocity along the impact's flight direction (what the experiments' residual
  // velocity is for a normal impact), the speed, and the angle between the velocity and that direction.
  double residual_velocity_m_s = 0.0;
  double residual_speed_m_s = 0.0;
  double deflection_deg = 0.0;
  // What decided an embedded sphere (result.json's embedded_by; kept as plain data: checkpoints hold
  // this struct's bytes).
  EmbeddedBy embedded_by = EmbeddedBy::None;
  // `worst_energy_error`: the run's worst energy-balance error so far, a share of the impact energy
  // (BalanceTracker::worst_energy, updated before this).
  void update(const ExplicitSolver& solver, double worst_energy_error);
  // The same from the state it reads: the sphere, the energy books, how many particles touch the sphere.
  void decide(const RigidSphere& sphere, const EnergyLedger& ledger, std::int64_t particles_in_contact,
              double time_s, double worst_energy_error);
  bool decided() const { return outcome != ImpactOutcome::Undecided; }
  bool perforated() const { return outcome == ImpactOutcome::Perforated; }
  bool rebounded() const { return outcome == ImpactOutcome::Rebounded; }
};

struct BalanceTracker {
  double worst_energy = 0.0;    // max |balance error| / initial kinetic energy
  double worst_momentum = 0.0;  // max |p - p0 - external impulse| / |p0|
  void update(const ExplicitSolver& solver);
  static double energy_error(const ExplicitSolver& solver);
  static double momentum_error(const ExplicitSolver& solver);
};

// Where the sphere's lost kinetic energy went, in J and as shares of it (result.json "energy_partition"):
// the target's kinetic energy, the energy its material stores and dissipates (plastic, crushing,
// released), the NSNI stabilization (stored, dissipated), bulk viscosity, the contact, the supports
// (minus the external work) and the balance error; the parts add up to the loss exactly.
// The target starts at rest, so the initial kinetic energy is the sphere's.
nlohmann::json energy_partition_json(const EnergyLedger& ledger);

// The panel after the shot (result.json `panel`): crater and scab diameters, the debris of either face
// and the plug, with the thresholds they were measured with.
nlohmann::json panel_json(const PanelDamage& panel);

// The diagnostic of a failed run (diagnostic.json).
nlohmann::json diagnostic_json(const ExplicitSolver& solver, const FailureReport& failure);

}  // namespace uhpc::macro
