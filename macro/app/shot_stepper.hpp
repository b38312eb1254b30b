#pragma once
// What uhpc-macro's run loop (macro_run.cpp) steps: the case's solver in one process (OneProcessShot),
// or the ranks' parts of it under mpirun or srun (distributed_shot.hpp). The run's time, step, sphere,
// contact and books are the same on every rank and come from solver(); the particles' own fields, for
// the outputs, from field_records() and body_particles() on the rank that writes. The calls marked
// collective are made by every rank in the same order.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "run_outputs.hpp"
#include "solver/explicit_solver.hpp"

namespace uhpc::macro {

inline double kept_fraction(double built, double kept) { return built + kept > 0.0 ? kept / (built + kept) : 0.0; }

class ShotStepper {
 public:
  virtual ~ShotStepper() = default;
  // One step (collective); false when it failed (the run is back at its last good state).
  virtual bool step() = 0;
  // The run's state. A distributed run replaces its rank's solver when it rebuilds its halo: do not keep
  // the reference across a step.
  virtual const ExplicitSolver& solver() const = 0;
  // Whether this rank writes the run's files (one rank does).
  virtual bool writes() const = 0;
  // Every particle's field record as it is now (FieldRecords), by its index in the body (collective): on
  // the rank that writes, the source FieldOutput::write reads them from; an empty function on the
  // others. What a source holds is freed with it.
  virtual FieldOutput::RecordSource field_records(const FieldRecords& records) = 0;
  // The body's particles as they are now (collective), for the results: on the rank that writes, their
  // positions, velocities, masses and spacings (other fields may be empty); nullptr on the others.
  virtual const Particles* body_particles() = 0;
  // The last failed step, named as one process names it (collective).
  virtual FailureReport failure() = 0;
  // The particles moving as rigid fragments (ShapeCache::fragment) and the whole target's mass, summed
  // in the body's order (collective).
  virtual std::size_t fragment_particles() = 0;
  virtual double target_mass_kg() = 0;
  // Whether each particle moves as a rigid fragment now, in the body's order (collective): on the rank
  // that writes; empty on the others.
  virtual std::vector<std::uint8_t> fragment_flags() = 0;
  // Lazy RK rows: the fraction of the rows built over the run that were kept (0 without; over the
  // ranks, their ghosts' rows included). Collective.
  virtual double rows_kept_fraction() = 0;
  // Checkpoints, in one process's format whatever the ranks (collective): the run's state, on the rank
  // that writes (empty on the others); going on from one (std::invalid_argument for one of another
  // body); the RK rows dropped where a checkpoint that must be resumed bit for bit is written.
  virtual SolverCheckpoint checkpoint() = 0;
  virtual void resume(const SolverCheckpoint& checkpoint) = 0;
  virtual void drop_rows() = 0;
  // A decision every rank must take alike, from what the rank that writes decided (its wall clock).
  virtual bool agree(bool decided) = 0;
};

class OneProcessShot final : public ShotStepper {
 public:
  explicit OneProcessShot(ExplicitSolver& solver) : solver_(solver) {}
  bool step() override { return solver_.step(); }
  const ExplicitSolver& solver() const override { return solver_; }
  bool writes() const override { return true; }
  FieldOutput::RecordSource field_records(const FieldRecords& records) override {
    return [this, &records](std::size_t i, double* record) { records.fill(solver_, i, record); };
  }
  const Particles* body_particles() override { return &solver_.particles(); }
  FailureReport failure() override { return solver_.failure(); }
  std::size_t fragment_particles() override { return solver_.shapes().fragments(); }
  std::vector<std::uint8_t> fragment_flags() override {
    std::vector<std::uint8_t> flags(solver_.particles().n);
    for (std::size_t i = 0; i < flags.size(); ++i) flags[i] = solver_.shapes().fragment(i) ? 1 : 0;
    return flags;
  }
  double target_mass_kg() override {
    double mass = 0.0;
    for (const double m : solver_.particles().mass) mass += m;
    return mass;
  }
  double rows_kept_fraction() override { return kept_fraction(solver_.shapes().rows_built, solver_.shapes().rows_kept); }
  SolverCheckpoint checkpoint() override { return solver_.checkpoint(); }
  void resume(const SolverCheckpoint& checkpoint) override { solver_.resume(checkpoint); }
  void drop_rows() override { solver_.drop_shape_cache(); }
  bool agree(bool decided) override { return decided; }

 private:
  ExplicitSolver& solver_;
};

}  // namespace uhpc::macro
