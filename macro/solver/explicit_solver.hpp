#pragma once
// The 3D explicit semi-Lagrangian RKPM solver core: one body of particles, one material, walls and
// prescribed velocities. Each step (velocity Verlet, verlet.hpp):
//   1. v += dt/2 a, constraints, x += dt v                                  (integrator)
//   2. L_I = sum_J v_J (x) grad Psi_J(x_I) with v the half-step velocity and RK gradients with exact
//      neighbour lists (a cell-list search, or its Verlet-skin candidates filtered:
//      SolverOptions::neighbour_skin) rebuilt at the mid-step configuration (x_n + x_n+1)/2
//      (StrainConfiguration::Midpoint) or at x_n+1 (End); EndpointAverage: the mean of L with the
//      gradients still held from the last force evaluation (at x_n) and with those rebuilt at x_n+1
//   3. constitutive update per particle (stress_update.hpp): rotation, law, volume, bulk viscosity,
//      critical step
//   4. RK gradients at x_n+1 (Midpoint only: End and EndpointAverage reuse step 2's), nodal-integration
//      internal forces, wall and reaction forces, a = f / m
//   5. v += dt/2 a, constraints; energies and momentum; next dt = CFL * min critical step
// The rigid sphere (rigid_sphere.hpp), when there is one, gets the same kicks and drift in lockstep:
// its half kicks bracket the particles' Verlet step and it drifts where they drift (at the start of
// step 2), so both are advanced by one velocity Verlet with forces from one configuration.
// Every step first saves the state. After the step: (a) the robustness checks (step_health.hpp): on a
// failure the solver goes back to the saved (last good) state and reports the failed attempt;
// (b) the step-collapse guard (after Laghos): when the new stable step is below dt_collapse_fraction
// times the step just taken, the step is repeated from the saved state with the new stable step.
// Nothing allocates inside steps once the neighbour counts have settled.
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "solver/conditions.hpp"
#include "solver/energy.hpp"
#include "solver/internal_force.hpp"
#include "solver/material_set.hpp"
#include "solver/particles.hpp"
#include "solver/rank_share.hpp"
#include "solver/rigid_sphere.hpp"
#include "solver/step_health.hpp"
#include "solver/second_gradients.hpp"
#include "solver/shape_cache.hpp"
#include "solver/verlet.hpp"
#include "solver/bulk_viscosity.hpp"
#include "uhpc/rk_shape.hpp"

namespace uhpc::macro {

enum class StrainConfiguration : std::uint8_t {
  Midpoint,  // strain rate at (x_n + x_n+1)/2: second order, objective, time-reversible; 2 RK builds/step
  End,       // strain rate at x_n+1: one RK build per step, first order in the configuration
  // L = (grad_x_n v + grad_x_n+1 v) / 2: the x_n gradients are the previous step's force evaluation's,
  // so one RK build and one extra gradient pass per step; time-symmetric, second order (the mean of
  // the end gradients is the midpoint one to O(dt^2)), a rigid rotation gives a skew L
  EndpointAverage,
};

enum class Stabilization : std::uint8_t {
  None,  // direct nodal integration
  Nsni,  // naturally stabilized nodal integration (Hillman and Chen 2016), see README.md
};

struct SolverOptions {
  rk::Options rk;              // linear basis, cubic B-spline, quasi-linear regularisation (common defaults)
  double support_factor = 2.0; // a_I = support_factor * h_I
  double cfl = 0.4;            // dt = cfl * min_I critical step (docs/physics.md: 0.3 - 0.5)
  double fixed_dt_s = 0.0;     // > 0: use this step instead (reversibility studies); must be <= stable
  StrainConfiguration strain_configuration = StrainConfiguration::EndpointAverage;
  BulkViscosity viscosity;     // {0, 0} switches it off
  Stabilization stabilization = Stabilization::Nsni;
  // [choice] c of the NSNI moments M_L = c V_L^(5/3) / 12 (nsni_moment.hpp): 1 is Hillman and Chen's
  // second moment of the particle's cell; a smaller c weakens the stabilization (and its dissipation).
  double nsni_coefficient = 1.0;
  SecondGradientOptions second_gradients;  // NSNI strain gradients (quadratic implicit second derivatives)
  // Verlet skin of the neighbour search, as a fraction of the smallest support radius (ShapeCache::skin):
  // candidate lists are searched with the radii grown by it and reused, filtered exactly, until some
  // particle has moved half the skin. Exact (the lists equal a fresh search); 0: search every rebuild.
  double neighbour_skin = 0.2;
  // Lazy RK rows (ShapeCache::reuse_tolerance; needs neighbour_skin > 0): a particle's shape functions
  // are rebuilt only once a neighbour has moved relative to it by more than this fraction of its
  // support radius since they were built, or a neighbour outside its support has come in by more;
  // otherwise they are kept (a new neighbour search does not force rebuilds). 0: every row is rebuilt at every configuration (the semi-Lagrangian method as such).
  double shape_reuse_tolerance = 0.0;
  // Fragments by the conditioning of their RK rows (ShapeCache::fragment_rcond; 0: by node count only).
  // [choice] 0.05, for stability: the step is set from the particle size at the CFL number, which is
  // stable for the rows of the intact body (the worst of the shipped disc, at an edge: rcond 0.345;
  // a lattice corner's gradient operator sum_J |grad Psi_J| h is 3.5, an interior row's 2.3). A row of
  // nodes nearly in a plane has a larger operator: 4.0 at rcond 0.05, 7.4 at 0.015 (1 / cfl = 2.5 times
  // the corner's, where the step stops being stable for it), 40 at 1.6e-4 (the ejecta row that stopped
  // the 300 m/s ballistic-limit run). 0.05 keeps a factor of two from that limit and touches no row
  // of the intact body (tests: MacroCaseSetup.TheShippedDiscHasNoFragmentRows, MacroRobustness.AFlatSheet*).
  double fragment_rcond = 0.05;
  // Step-collapse guard: repeat a step whose new stable step is below this fraction of the step taken
  // (0 switches the guard off; so does fixed_dt_s). With CFL 0.4 and 0.5 an accepted step was at most
  // 0.8 of the critical step of the configuration it produced.
  double dt_collapse_fraction = 0.5;
  int max_step_repeats = 10;  // repeats of one step before it fails with StepFailure::StepCollapse
  // A step whose energy balance error exceeds this fraction of the energy put in fails the run
  // (StepFailure::EnergyBalance; 0 switches the check off). Sound runs stay below 2e-3.
  double energy_error_limit = 0.05;
  // The domain box; unset: the bounding box of the particles and the sphere at initialize(), grown on
  // every side by domain_margin times its largest extent. While the energy balance is checked, a
  // particle beyond it is an ejecta in flight (far from the target, it carries its momentum and energy
  // unchanged, in the books; a blow-up shows in the balance first) and the run goes on. With the check
  // off (energy_error_limit = 0) the domain is the guard of last resort: a particle beyond it fails the
  // step (StepFailure::OutOfDomain).
  std::optional<Region> domain;
  double domain_margin = 1.0;
};

// What a step evolves besides the particle fields and the material states, listed once: a failed
// attempt restores it (ExplicitSolver::restore_state), a checkpoint carries it.
struct StepState {
  std::vector<double> f_ext_old, f_contact_old;  // the last step's forces (the trapezoid rule's start)
  std::optional<RigidSphere> sphere;
  Vec3 sphere_force_old{};
  SphereContactSums contact;  // the contact's last evaluation
  EnergyLedger ledger;
  double time_s = 0.0, dt_s = 0.0, wall_force_N = 0.0;  // dt_s: the stable step for the next step
};

// The run's counters: not undone by a repeated step (they count it).
struct StepCounters {
  double last_dt_s = 0.0;  // the step actually taken by the last step()
  std::int64_t steps = 0, repeats = 0;
};

// What a run needs to go on bit for bit after a successful step: the particle fields a step reads back,
// the material states, the step's state and the counters. Written and read by macro/app/checkpoint.hpp.
struct SolverCheckpoint {
  std::vector<std::pair<std::string, std::vector<double>>> particle_fields;  // name, values
  std::vector<std::uint8_t> material_states;  // the law's states, byte for byte
  StepState state;
  StepCounters counters;
};

class ExplicitSolver {
 public:
  // `particles` must come from Particles::from_body with the density of the material.
  ExplicitSolver(Particles particles, MaterialSet material, const SolverOptions& options);

  void add_wall(const Wall& wall) { walls_.push_back(wall); }
  void add_prescribed_velocity(const PrescribedVelocity& bc) { prescribed_.push_back(bc); }
  // The free rigid projectile (at most one; validated). Set before initialize() (std::logic_error after).
  void set_sphere(const RigidSphere& sphere);
  // Makes the solver one rank's part (rank_share.hpp). Before initialize(). Not yet with the penalty
  // contact or the Midpoint configuration (std::invalid_argument).
  void set_rank_share(RankShare share);
  // In place of initialize(), for a distributed run's new rank solver (set_rank_share called, every
  // particle's state already in through read_particle): the run goes on from `run`, the run_state() of
  // the solver it replaces, which may be gone by then (the time, step, books, sphere and domain are the
  // run's, the same on every rank). The rows are built at the next step, or, lazy rows, installed next
  // (install_rows).
  struct RunState {
    StepState state;  // without the particles' last forces (f_ext_old, f_contact_old: read_particle's)
    StepCounters counters;
    Region domain;
  };
  RunState run_state() const;
  void continue_from(const RunState& run);
  // Lazy rows (shape_reuse_tolerance > 0) travel with their particles between a distributed run's
  // rank solvers: particle i's row as a record (ShapeCache::write_row, its nodes by global id), and, after
  // continue_from, every particle's row installed from the records of the solvers it came from, in
  // place of rows built afresh (which would differ: a kept row holds the configuration it was built in).
  std::size_t row_record_length(std::size_t i) const;
  double* write_row(std::size_t i, double* out) const;
  void install_rows(const std::vector<const double*>& records, const std::function<std::int32_t(std::uint32_t)>& local_of);
  bool lazy_rows() const { return options_.shape_reuse_tolerance > 0.0; }
  bool distributed() const { return share_.has_value(); }

  // Forces and accelerations at t = 0, initial energies and momentum, the first stable step. Call once
  // after the conditions are set (initial velocities in particles().v).
  void initialize();
  // One step of size dt() (or fixed_dt_s, which is not checked against the stable step), repeated with
  // a smaller step when the stable step collapses. Returns false when the step failed (step_health.hpp):
  // the solver is then back in the state before the step (the last good state) and failure() describes
  // the failed attempt.
  bool step();

  // Checkpoints. checkpoint() copies the state after the last step. resume() hands it to a solver built
  // and initialized from the same case, which then goes on exactly as the one that wrote it (throws
  // std::invalid_argument when the sizes or the law do not match). The shape cache is not part of a
  // checkpoint: a run drops it where it writes one (drop_shape_cache), and resume() starts without it,
  // so both rebuild every row from the same state at the next step.
  SolverCheckpoint checkpoint() const;
  // Particle i's evolving fields (the checkpoint's, in its order) and material state as
  // particle_record_width() doubles, and back: how a distributed run ships a particle to its ghosts.
  // read_particle also sets i's forces of the last step (f_ext_old, f_contact_old), as a step leaves them.
  std::size_t particle_record_width() const;
  void write_particle(std::size_t i, double* out) const;
  void read_particle(std::size_t i, const double* in);
  void resume(const SolverCheckpoint& checkpoint);
  void drop_shape_cache();
  // Checkpoints of a distributed run, which are those of one process (any rank count resumes them):
  // resume_part, on a rank solver after initialize(), takes its particles (by global id) and the run's
  // state from a checkpoint of the whole body; body_checkpoint, on a rank solver, is the whole body's
  // checkpoint from every particle's record (write_particle's, then stride - particle_record_width()
  // more doubles) in the order of their ids, with this rank's time, step, books and sphere: what
  // checkpoint() gives in one process.
  void resume_part(const SolverCheckpoint& checkpoint);
  SolverCheckpoint body_checkpoint(std::size_t total, const double* records, std::size_t stride) const;

  double time() const { return st_.time_s; }
  double dt() const { return options_.fixed_dt_s > 0 ? options_.fixed_dt_s : st_.dt_s; }
  double stable_dt() const { return st_.dt_s; }
  std::int64_t steps() const { return counters_.steps; }
  const EnergyLedger& ledger() const { return st_.ledger; }
  const Particles& particles() const { return p_; }
  Particles& particles() { return p_; }
  const MaterialSet& material() const { return material_; }
  // At the current configuration after a successful step (after a failed one: at the failed attempt's).
  const ShapeCache& shapes() const { return shapes_; }
  const SolverOptions& options() const { return options_; }
  double wall_force_magnitude() const { return st_.wall_force_N; }  // total normal wall force, last step
  std::int64_t failure_particle() const { return failure_.particle; }
  const FailureReport& failure() const { return failure_; }
  std::int64_t step_repeats() const { return counters_.repeats; }  // repeats by the step-collapse guard, whole run
  double last_dt() const { return counters_.last_dt_s; }          // the step actually taken by the last step()
  const Region& domain() const { return domain_; }
  // Whether a particle beyond the domain fails the step (SolverOptions::domain).
  bool domain_is_guard() const { return options_.energy_error_limit <= 0.0; }
  bool has_sphere() const { return st_.sphere.has_value(); }
  const RigidSphere& sphere() const { return *st_.sphere; }  // requires has_sphere()
  const SphereContactSums& contact() const { return st_.contact; }  // last force evaluation
  // Energy particle i has dissipated so far per unit reference volume (J/m^3): its stress work minus
  // the energy its law holds (EnergyLedger::material_dissipated per particle).
  double dissipated_density(std::size_t i) const;

  // The physics interface of velocity_verlet_step.
  VerletArrays verlet_arrays() { return {p_.x.data(), p_.x_prev.data(), p_.v.data(), p_.a.data(), 3 * p_.n}; }
  void constrain_velocities();
  void compute_accelerations(double dt);

 private:
  const SecondGradientOptions* second_options() const;  // null without NSNI
  // Whether particle i counts in the books, checks and the stable step (every particle but a ghost).
  bool counted(std::size_t i) const { return !share_ || share_->owned[i] != 0; }
  const std::uint8_t* owned_flags() const { return share_ ? share_->owned.data() : nullptr; }
  // The ranks' minimum and sums (RankShare); the value itself in one process.
  double ranks_min(double value) const { return share_ ? share_->min(value) : value; }
  // Each of the values replaced by its sum over the ranks (one exchange; nothing in one process).
  void ranks_sum(std::initializer_list<double*> values) const;
  bool ranks_any(bool flag) const { return ranks_min(flag ? 0.0 : 1.0) == 0.0; }
  // The stable step, the one place solver.cfl applies: cfl times the smallest of the critical steps
  // given (the particles' from their wave speed and bulk viscosity over the stable length; the sphere
  // contact's from its stiffness and travel; the sphere's travel limit), each known at a different
  // point of the step.
  double stable_step(std::initializer_list<double> critical_steps) const;
  double travel_limit() const;  // the sphere's travel limit (infinity without a sphere)
  // f_int, f_ext and a at the current configuration (shapes_ up to date); dt: the step that produced
  // it (friction's cap; 0 at the start), dt_next: the next step (the kinematic contact's prediction).
  // internal false: f_int is already there (computed with the stress update, compute_accelerations).
  void compute_forces(double dt, double dt_next, bool internal = true);
  void update_momentum_and_kinetic();
  void update_material_books();  // the material and stabilization parts of the ledger
  void book_contact_work(double h);  // the contact's share of the step's kicks (after the second one)
  double stabilization_energy(const Moduli& mod, std::int64_t i) const;  // held by particle i's gradients
  StepFailure attempt(double h);  // one velocity Verlet step of size h and the checks
  void save_state();
  Region default_domain() const;
  void restore_state();
  // shapes_ at the n points x (the particles' supports); with L non-null also L (9n) and, with G
  // non-null (NSNI), dL/dx (27n) of the current velocities with the new shapes.
  void rebuild_shapes(const double* x, double* L = nullptr, double* G = nullptr);
  // L (9n) and, with G non-null (NSNI), dL/dx (27n) of the current velocities with shapes_.
  void velocity_gradients(double* L, double* G) const;

  Particles p_;
  MaterialSet material_;
  SolverOptions options_;
  std::vector<Wall> walls_;
  std::vector<PrescribedVelocity> prescribed_;
  ShapeCache shapes_;
  void take_run_state(const StepState& state, const StepCounters& counters);  // keeps the particles' last forces
  ShapeCache empty_shape_cache() const;  // configured from options_, no rows
  // shapes_ were built at the current x (false after restore_state: they are the failed attempt's).
  bool shapes_at_x_ = false;
  // EndpointAverage: L and (NSNI) dL/dx with the start-of-step gradients; sized once in the constructor.
  std::vector<double> vel_grad_start_, vel_grad_grad_start_;
  InternalForce force_;
  SphereContact sphere_contact_;  // the contact model and its scratch, set up at initialize()
  Region domain_;
  StepState st_;
  StepCounters counters_;
  std::int64_t inverted_ = -1;
  bool initialized_ = false;
  std::optional<RankShare> share_;
  std::vector<double> reference_wave_speed_;  // a rank's solver: its particles' at the reference state (set_rank_share)
  FailureReport failure_;
  // The last good state, saved at the start of every step (same-size copies: no allocation). Of the
  // particles only the fields a step changes and reads back are kept (kEvolvingFields in
  // explicit_solver.cpp, in its order): the rest is not worth its memory.
  struct Saved {
    std::vector<std::vector<double>> particle_fields;
    std::optional<MaterialSet> material;
    StepState state;
  } saved_;
};

}  // namespace uhpc::macro
