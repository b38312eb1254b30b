#include "macro_run.hpp"


#include <chrono>
#include <fstream>
#include <cmath>
#include <iostream>
#include <memory>
#include <optional>
#include <ostream>

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "case_config.hpp"
#include "case_setup.hpp"
#include "checkpoint.hpp"
#include "distributed_shot.hpp"
#include "material_factory.hpp"
#include "run_inputs.hpp"
#include "run_outputs.hpp"
#include "run_warnings.hpp"
#include "shot_stepper.hpp"
#include "uhpc/atomic_file.hpp"
#include "uhpc/config.hpp"
#include "uhpc/errors.hpp"
#include "uhpc/output_lock.hpp"
#include "uhpc/parallel.hpp"
#include "uhpc/progress.hpp"
#include "uhpc/provenance.hpp"
#include "uhpc/resources.hpp"
#include "uhpc/sdel_handoff.hpp"

namespace fs = std::filesystem;

namespace uhpc::macro {

namespace {

nlohmann::json beyond_domain_json(const Particles& p, const Region& domain) {
  std::int64_t count = 0;
  double mass = 0.0, kinetic = 0.0;
  for (std::size_t i = 0; i < p.n; ++i) {
    if (domain.contains(p.x.data() + 3 * i)) continue;
    const double* v = p.v.data() + 3 * i;
    ++count;
    mass += p.mass[i];
    kinetic += 0.5 * p.mass[i] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  }
  return {{"particles", count}, {"mass_kg", mass}, {"kinetic_J", kinetic}};
}

// s: the run's state (time, sphere, books); body: the whole body's particles (ShotStepper::body_particles).
nlohmann::json result_json(const ExplicitSolver& s, const Particles& body, std::size_t fragment_particles,
                           double rows_kept_fraction, const ImpactTracker& impact, const BalanceTracker& balance, const std::string& model,
                           double wall_s, const Provenance& provenance, std::size_t field_steps) {
  const double vi = impact.impact_velocity_m_s, vf = s.sphere().v[2];
  nlohmann::json r = {
      {"impact_velocity_m_s", vi},
      {"outcome", to_string(impact.outcome)},
      {"perforated", impact.perforated()},
      {"rebounded", impact.rebounded()},
      {"residual_velocity_m_s", nullptr},
      {"residual_speed_m_s", nullptr},
      {"deflection_deg", nullptr},
      {"outcome_time_s", nullptr},
      {"exit_time_s", nullptr},
      {"velocity_reduction", nullptr},
      {"kinetic_energy_reduction", nullptr},
      {"final_velocity_m_s", vf},
      {"final_sphere_position_m", s.sphere().x},
      {"end_time_s", s.time()},
      {"material_model", model},
      {"particle_count", body.n},
      {"steps", s.steps()},
      {"step_repeats", s.step_repeats()},
      {"field_outputs", field_steps},
      {"wall_time_s", wall_s},
      {"peak_memory_MB", peak_memory_MiB()},  // (MiB; the key predates the unit)
      {"particle_steps_per_s",
       wall_s > 0 ? static_cast<double>(body.n) * static_cast<double>(s.steps()) / wall_s : 0.0},
      // Lazy RK rows (solver.shape_reuse_tolerance): the fraction of rows kept over the run (0 without).
      {"shape_rows_kept_fraction", rows_kept_fraction},
      // Particles moving as rigid fragments at the end (ShapeCache::fragment, solver.fragment_rcond).
      {"fragment_particles", fragment_particles},
      // Ejecta in flight beyond the domain box at the end (SolverOptions::domain).
      {"beyond_domain", beyond_domain_json(body, s.domain())},
      {"energy",
       {{"initial_kinetic_J", s.ledger().kinetic_initial},
        {"final_kinetic_J", s.ledger().kinetic},
        {"final_sphere_kinetic_J", s.ledger().kinetic_sphere},
        {"internal_J", s.ledger().internal},
        {"elastic_stored_J", s.ledger().material_stored},
        {"dissipated_material_J", s.ledger().material_dissipated},
        {"plastic_J", s.ledger().plastic},
        {"crushing_J", s.ledger().crushing},
        {"opening_J", s.ledger().opening},
        {"released_J", s.ledger().released()},
        {"stabilization_J", s.ledger().stabilization},
        {"stabilization_stored_J", s.ledger().stabilization_stored},
        {"dissipated_viscous_J", s.ledger().viscous},
        {"contact_J", s.ledger().contact},
        {"external_work_J", s.ledger().external},
        {"balance_error", BalanceTracker::energy_error(s)},
        {"worst_balance_error", balance.worst_energy}}},
      {"momentum",
       {{"initial_N_s", s.ledger().momentum_initial},
        {"final_N_s", s.ledger().momentum},
        {"external_impulse_N_s", s.ledger().external_impulse},
        {"balance_error", BalanceTracker::momentum_error(s)},
        {"worst_balance_error", balance.worst_momentum}}},
      {"energy_partition", energy_partition_json(s.ledger())},
      {"provenance", provenance.to_json()}};
  if (impact.decided()) {
    const double vr = impact.residual_velocity_m_s;
    r["residual_velocity_m_s"] = vr;
    r["residual_speed_m_s"] = impact.residual_speed_m_s;
    r["deflection_deg"] = impact.deflection_deg;
    r["outcome_time_s"] = impact.outcome_time_s;
    if (impact.outcome == ImpactOutcome::Embedded) r["embedded_by"] = to_string(impact.embedded_by);
    if (impact.perforated() || impact.rebounded()) r["exit_time_s"] = impact.outcome_time_s;
    r["velocity_reduction"] = (vi - vr) / vi;
    r["kinetic_energy_reduction"] = (vi * vi - vr * vr) / (vi * vi);
  }
  return r;
}

// A run is refused before it starts when its first stable step would need more than run.max_steps
// steps to reach the end time (a density of 1e-300 gave a step of exactly 0 and a run that never
// advanced; a bulk modulus of 1e300 or a speed of 1e9 m/s, runs of days). The message names the inputs
// the step comes from (the material's wave speed, the spacing, the sphere's speed, the CFL number) beside
// the guard's key, since those, not the guard, are what a user mistyped.
void refuse_beyond_budget(const Config& cfg, const CaseSettings& settings, double first_step,
                          const std::string& wave_speed_inputs) {
  const Config r = cfg.section("run");
  const RunSettings& run = settings.run;
  const std::string inputs =
      fmt::format("the step comes from the wave speed ({}), the spacing ({}), the sphere's speed "
                  "(projectile.velocity_m_s = {:g} m/s) and solver.cfl = {:g}",
                  wave_speed_inputs, spacing_inputs(settings.target), settings.projectile.velocity_m_s, settings.solver.cfl);
  if (!(first_step > 0.0) || !std::isfinite(first_step))
    r.fail("end_time_s", fmt::format("the first stable step is {:.3e} s: the run cannot advance ({})", first_step,
                                     inputs));
  const double steps = run.end_time_s / first_step;
  if (steps > static_cast<double>(run.max_steps))
    r.fail("max_steps", fmt::format("the run would take about {:.3g} steps of {:.3e} s to reach end_time_s = {:.3e} s, "
                                    "more than max_steps = {} (raise max_steps or check the inputs: {})",
                                    steps, first_step, run.end_time_s, run.max_steps, inputs));
}

// A target of more than run.max_particles particles is refused before it is built (a 1 nm spacing
// asked for 1e23 particles). The memory figure is the shipped disc's measured peak, about 12 kB a particle
// at support 2.5 h (80 000 and 158 000 particles: 0.93 and 1.9 GB), scaled by the count. The message
// names the target's inputs the count comes from.
void refuse_beyond_size_budget(const Config& cfg, const CaseSettings& settings) {
  constexpr double kBytesPerParticle = 12e3;
  const double n = estimated_particle_count(settings.target);
  if (n > static_cast<double>(settings.run.max_particles))
    cfg.section("run").fail(
        "max_particles", fmt::format("the target would hold about {:.3g} particles (about {:.3g} GiB of memory) with {}, "
                                     "more than max_particles = {} (check the target's size and spacing, or raise "
                                     "max_particles)",
                                     n, n * kBytesPerParticle / (1u << 30), particle_count_inputs(settings.target),
                                     settings.run.max_particles));
}

// --reuse: true when `result` holds a finished run of these inputs (their hash, or their hash in the former
// scheme that hashed the case's notes too, for a run recorded before 2026-12-06); false when there is
// none (the run goes ahead); an InputError when it holds a run of other inputs (a make rule would
// otherwise take an answer made with another end time, SDEL or --set for this one).
bool reuse_finished_run(const fs::path& result, const RunInputs& inputs) {
  const std::string& hash = inputs.hash;
  if (!fs::exists(result)) return false;
  std::ifstream in(result, std::ios::binary);
  std::string recorded;
  try {
    recorded = nlohmann::json::parse(in).at("provenance").at("config_hash").get<std::string>();
  } catch (const nlohmann::json::exception& e) {
    throw InputError(result.string() + ": not a run's result (provenance.config_hash unreadable: " + e.what() +
                     "): delete its directory to run it again");
  }
  if (recorded == inputs.former_hash) {
    spdlog::info("{}: a finished run of these inputs (hashed with the case's notes, as before 2026-12-06), kept",
                 result.string());
    return true;
  }
  if (recorded != hash)
    throw InputError(fmt::format("{}: made from other inputs (config_hash {}, these inputs {}): delete its directory "
                                 "or use another output directory (an undecided run given only a later "
                                 "run.end_time_s goes on with --restart)",
                                 result.string(), recorded, hash));
  spdlog::info("{}: a finished run of these inputs, kept", result.string());
  return true;
}

// The case's solver in one process or its parts over the ranks, resumed from `resumed` when given. One
// process takes `law` over (its states are the solver's); the ranks' parts keep reading it.
std::unique_ptr<ShotStepper> make_shot(const CaseSettings& settings, const ParticleBody& body, MaterialSet& law,
                                       int ranks, std::optional<ExplicitSolver>& one_process,
                                       const std::optional<RunCheckpoint>& resumed, const fs::path& checkpoint_file) {
  std::unique_ptr<ShotStepper> shot;
#ifdef UHPC_WITH_MPI
  if (ranks > 1) {
    try {
      shot = make_distributed_shot(settings, body, law);
    } catch (const std::invalid_argument& e) {  // what the rank solvers refuse (ExplicitSolver::set_rank_share)
      throw InputError(fmt::format("{} (run on one rank, not {})", e.what(), ranks));
    }
  }
#endif
  (void)ranks;
  if (!shot) {
    one_process.emplace(make_solver(settings, body, std::move(law)));
    shot = std::make_unique<OneProcessShot>(*one_process);
  }
  if (resumed) {
    try {
      shot->resume(resumed->solver);
    } catch (const std::invalid_argument& e) {
      throw InputError(checkpoint_file.string() + ": does not fit this case: " + e.what());
    }
  }
  return shot;
}

}  // namespace

void run_macro(const MacroRunArgs& args) {
  const Config cfg = Config::load(args.config_path, args.overrides);
  const CaseSettings settings = read_case(cfg);
  // The handoff is validated whenever it is given, whether or not the law uses it.
  std::optional<SdelHandoff> sdel;
  if (!args.sdel_path.empty()) sdel = read_sdel_handoff(args.sdel_path);
  refuse_beyond_size_budget(cfg, settings);
  const ParticleBody body = make_target_body(settings.target);
  MaterialChoice material = make_material(cfg.section("material"), body.size(), sdel);
  cfg.finish();
  const int ranks = world_ranks();  // every rank reads the inputs and decides alike
  const bool writer = world_rank() == 0;
  if (!writer) spdlog::set_level(spdlog::level::err);  // the warnings once, from the rank that writes
  if (sdel && !material.uses_sdel)
    spdlog::info("the '{}' law does not use the SDEL: {} was validated and is ignored", material.model, args.sdel_path);

  const RunInputs inputs = run_inputs(cfg, args.config_path, args.overrides, args.sdel_path, material.inputs);
  if (args.inputs_hash) {
    if (writer) std::cout << inputs.hash << '\n' << inputs.former_hash << std::endl;
    return;
  }
  if (args.reuse_check) {
    const bool kept = reuse_finished_run(args.out / "result.json", inputs);
    if (writer) std::cout << (kept ? "kept" : "run") << std::endl;
    return;
  }
  const fs::path checkpoint_file = args.out / "checkpoint.h5";
  if (args.restart_check) {
    const bool resumable = fs::exists(checkpoint_file) && written_by_this_build(checkpoint_file);
    if (resumable) check_checkpoint_values(read_checkpoint(checkpoint_file, inputs.restart_hash), settings.run, checkpoint_file);
    if (writer) std::cout << (resumable ? "restart" : "start") << std::endl;
    return;
  }
  if (args.reuse && reuse_finished_run(args.out / "result.json", inputs)) return;
  std::optional<RunCheckpoint> resumed;
  if (args.restart) {
    resumed = read_checkpoint(checkpoint_file, inputs.restart_hash);
    check_checkpoint_values(*resumed, settings.run, checkpoint_file);
  }
  std::optional<ExplicitSolver> one_process;  // the solver, when the run is on one rank
  const std::unique_ptr<ShotStepper> shot =
      make_shot(settings, body, material.set, ranks, one_process, resumed, checkpoint_file);
  // (A distributed run replaces its rank's solver at a halo rebuild: shot->solver() is asked afresh.)
  refuse_beyond_budget(cfg, settings, shot->solver().dt(), material.wave_speed_inputs);
  // Every check has passed: only now are the previous run's outputs replaced, by this run alone (a second
  // run given the same --out stops here with exit 2 naming this one).
  std::optional<OutputLock> lock;
  if (writer) {
    lock.emplace(lock_output_directory(args.out, "uhpc-macro"));
    for (const char* name : {"result.json", "diagnostic.json", "history.csv", "config.json", "checkpoint.h5", "fields.h5",
                             "fields.xdmf", "sphere.h5", "sphere.xdmf"})
      require_file_path(args.out / name);
    for (const char* stale : {"result.json", "diagnostic.json"}) fs::remove(args.out / stale);
    if (!resumed) {
      for (const char* stale : {"history.csv", "config.json", "checkpoint.h5"}) fs::remove(args.out / stale);
    }
    write_text_atomic(args.out / "config.json", inputs.record.dump(2) + "\n");
  }
  const Provenance provenance = Provenance::make("uhpc-macro", inputs.hash);
  if (resumed)
    spdlog::info("restarting from {} at step {}, t = {:.6e} s", checkpoint_file.string(), shot->solver().steps(),
                 shot->solver().time());
  spdlog::info("{} particles{}, material '{}', sphere {} kg at {} m/s, first step {:.3e} s, end time {:.3e} s",
               body.size(), ranks > 1 ? fmt::format(" on {} ranks", ranks) : "", material.model,
               settings.projectile.mass_kg, settings.projectile.velocity_m_s, shot->solver().dt(), settings.run.end_time_s);
  std::vector<RunWarning> warnings = warnings_before_run(settings);
  for (RunWarning& w : warnings_for_material(shot->solver().material(), settings))
    warnings.push_back(std::move(w));
  const WallTimeEstimate estimate =
      estimate_wall_time(body.size(), settings.run.end_time_s - shot->solver().time(), shot->solver().dt(),
                         ranks * max_threads());
  spdlog::info("{}", estimate.message);
  if (estimate.seconds > kLongRunSeconds) warnings.push_back({"long_run", estimate.message});
  for (const RunWarning& w : warnings) spdlog::warn("{}", w.message);

  // The files are the writing rank's; every rank calls write_fields, which gathers the particles there.
  std::optional<FieldOutput> fields;
  std::optional<FullFields> full;
  if (settings.run.fields == FieldSet::Full) full = FullFields{&body.position};
  if (writer && resumed) fields.emplace(args.out, shot->solver().material(), resumed->fields, full);
  else if (writer) fields.emplace(args.out, shot->solver().material(), full);
  if (fields) fields->write_provenance(provenance);
  const FieldRecords field_records(shot->solver().material(), full.has_value());  // every rank fills its own
  const auto write_fields = [&] {
    const std::vector<std::uint8_t> fragments = full ? shot->fragment_flags() : std::vector<std::uint8_t>{};
    const FieldOutput::RecordSource records = shot->field_records(field_records);
    if (fields) fields->write(shot->solver(), body.size(), records, fragments);
  };
  History history = resumed ? History(resumed->history_text, resumed->history_rows) : History();
  const auto save_history = [&] {
    if (writer) history.save(args.out / "history.csv");
  };
  ImpactTracker impact;
  impact.thickness_m = settings.target.thickness_m();
  impact.impact_velocity_m_s = settings.projectile.velocity_m_s;
  impact.flight_direction = flight_direction(settings.projectile);
  impact.target_mass_kg = shot->target_mass_kg();
  BalanceTracker balance;
  if (resumed) {
    impact = resumed->impact;
    balance = resumed->balance;
  } else {
    write_fields();
    history.add(shot->solver());
  }
  // The checkpoints of run.checkpoint_interval_steps and of the end drop the shape cache where they are
  // written, so the run that writes them and a run resumed from one rebuild every row from the same state
  // (ExplicitSolver::resume). The wall clock's (--checkpoint-every-min) keep it: when they fire depends on
  // the machine, and the run's numbers must not. Over several ranks, rank 0 writes the whole body's
  // (collective), and rank 0's clock decides when.
  enum class ShapeRows : bool { Keep, Drop };
  const auto write_checkpoint_now = [&](ShapeRows rows) {
    if (rows == ShapeRows::Drop) shot->drop_rows();
    SolverCheckpoint state = shot->checkpoint();
    if (!writer) return;
    history.save(args.out / "history.csv");
    write_checkpoint(checkpoint_file, {std::move(state), history.text(), history.rows(), impact, balance,
                                       fields->state(), inputs.restart_hash, checkpoint_build()});
  };
  const auto finished = [&] {
    const ExplicitSolver& solver = shot->solver();
    const bool stop_after_outcome = impact.decided() && settings.run.stop_after_outcome_s >= 0 &&
                                    solver.time() >= impact.outcome_time_s + settings.run.stop_after_outcome_s;
    return solver.time() >= settings.run.end_time_s || stop_after_outcome;
  };

  // Progress over simulated time, counted in nanoseconds; the step rate goes into the log lines.
  const auto total_ns = static_cast<std::uint64_t>(std::llround(settings.run.end_time_s * 1e9));
  std::ostream quiet_sink(nullptr);  // -q (and the ranks that do not write): no progress line either
  Progress progress("uhpc-macro simulated", total_ns,
                    ProgressOptions{args.quiet || !writer ? &quiet_sink : nullptr, -1, 10, 0.1, "ns"});
  std::uint64_t done_ns = 0;
  if (resumed) {
    done_ns = static_cast<std::uint64_t>(std::llround(std::fmin(shot->solver().time(), settings.run.end_time_s) * 1e9));
    progress.advance(done_ns);
  }
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  double last_checkpoint_s = 0.0;  // wall time of the last checkpoint (the run's start before the first)

  while (!finished()) {
    if (!shot->step()) {
      // The solver is back in the last good state: keep it, say what failed, and stop.
      progress.finish();
      write_fields();
      save_history();
      const FailureReport f = shot->failure();
      const ExplicitSolver& solver = shot->solver();
      if (writer) write_text_atomic(args.out / "diagnostic.json", diagnostic_json(solver, f).dump(2) + "\n");
      throw NumericalError(fmt::format("{} at step {} (t = {:.6e} s, particle {}); last good state at t = {:.6e} s "
                                       "written to {}, diagnostic in {}",
                                       to_string(f.kind), f.step, f.time_s + f.dt_s, f.particle, solver.time(),
                                       (args.out / "fields.h5").string(), (args.out / "diagnostic.json").string()));
    }
    const ExplicitSolver& solver = shot->solver();
    history.add(solver);
    balance.update(solver);
    impact.update(solver, balance.worst_energy);
    if (solver.steps() % settings.run.output_interval_steps == 0) {
      write_fields();
      save_history();  // a killed run keeps its history up to here
      spdlog::info("step {}, t = {:.3f} us, {:.1f} steps/s, sphere z = {:.3f} mm, v_z = {:.2f} m/s, {} in contact",
                   solver.steps(), solver.time() * 1e6, solver.steps() / elapsed(), solver.sphere().x[2] * 1e3,
                   solver.sphere().v[2], solver.contact().particles_in_contact);
    }
    // None on the last step: the run ends there, and removes its checkpoint or writes its own.
    const bool last_step = finished();
    if (!last_step && settings.run.checkpoint_interval_steps > 0 &&
        solver.steps() % settings.run.checkpoint_interval_steps == 0) {
      write_checkpoint_now(ShapeRows::Drop);
      last_checkpoint_s = elapsed();
    } else if (!last_step && args.checkpoint_every_s > 0.0 &&
               shot->agree(elapsed() - last_checkpoint_s >= args.checkpoint_every_s)) {
      write_checkpoint_now(ShapeRows::Keep);
      last_checkpoint_s = elapsed();
    }
    const auto now_ns = static_cast<std::uint64_t>(std::llround(std::fmin(solver.time(), settings.run.end_time_s) * 1e9));
    if (now_ns > done_ns) {
      progress.advance(now_ns - done_ns);
      done_ns = now_ns;
    }
  }
  progress.finish();
  const ExplicitSolver& solver = shot->solver();
  if (!impact.decided())
    spdlog::warn("outcome undecided: the sphere is still moving in the target at the end time ({:.1f} us, v_z = {:.2f} "
                 "m/s); run.end_time_s is too short to decide this shot",
                 solver.time() * 1e6, solver.sphere().v[2]);
  const double wall = elapsed();
  write_fields();
  const Particles* body_now = shot->body_particles();
  const std::size_t fragments = shot->fragment_particles();
  const double rows_kept = shot->rows_kept_fraction();
  // An undecided run keeps its last state as a checkpoint, so that --restart with a later run.end_time_s
  // carries it on instead of starting again; it is written before result.json, so that a result.json on
  // disk always means a finished run. A decided run's results replace the checkpoint.
  if (!impact.decided()) write_checkpoint_now(ShapeRows::Drop);
  if (!writer) return;
  save_history();
  nlohmann::json result =
      result_json(solver, *body_now, fragments, rows_kept, impact, balance, material.model, wall, provenance, fields->steps_written());
  result["ranks"] = ranks;
  result["inputs"] = inputs_summary(inputs);
  const Vec3 flight = flight_direction(settings.projectile);
  const ShotOnPanel shot_on_panel{settings.target.thickness_m(), settings.projectile.offset_m, flight[0] / flight[2],
                                  settings.projectile.radius_m, solver.sphere().v[2], impact.perforated()};
  result["panel"] = panel_json(panel_damage(*body_now, body.position, shot_on_panel));
  for (RunWarning& w : warnings_after_run(solver.ledger())) {
    spdlog::warn("{}", w.message);
    warnings.push_back(std::move(w));
  }
  result["warnings"] = warnings_json(warnings);
  write_text_atomic(args.out / "result.json", result.dump(2) + "\n");
  if (impact.decided()) fs::remove(checkpoint_file);
  spdlog::info("{} steps ({} repeated) in {:.2f} s, {:.3g} particle-steps/s; sphere v_z {:.2f} m/s ({}); energy "
               "balance {:.2e}, momentum balance {:.2e}",
               solver.steps(), solver.step_repeats(), wall, result["particle_steps_per_s"].get<double>(),
               solver.sphere().v[2],
               impact.decided() ? to_string(impact.outcome) : "undecided: still moving in the target at the end time",
               BalanceTracker::energy_error(solver), balance.worst_momentum);
}

}  // namespace uhpc::macro
