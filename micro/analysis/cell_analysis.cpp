#include "cell_analysis.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <Eigen/UmfPackSupport>
#include <fmt/format.h>

#include "bordered_tangent_solver.hpp"
#include "cohesive_assembly.hpp"
#include "crack_stage.hpp"
#include "energy_books.hpp"
#include "path_modes.hpp"
#include "path_steps.hpp"
#include "uniaxial_cell.hpp"

namespace uhpc::micro {

namespace {

CohesiveLaw cohesive_law(const CellMaterial& material, const CellAnalysisOptions& o) {
  CohesiveLaw law;
  law.tensile_strength_Pa = material.tensile_strength_Pa;
  law.fracture_energy_J_m2 = material.fracture_energy_J_m2;
  law.activation_ratio = o.activation_ratio;
  law.contact_penalty_ratio = o.contact_penalty_ratio;
  law.residual_stiffness_ratio = o.residual_stiffness_ratio;
  law.mode = o.mode;
  return law;
}

std::vector<std::array<double, 2>> constraint_points(const ElasticProblem& unit) {
  std::vector<std::array<double, 2>> x;
  for (const PointConstraint& c : unit.points) x.push_back(c.x_m);
  return x;
}

struct NewtonResult {
  bool ok = false;
  int iterations = 0;
  std::string why;
};

class Analysis {
 public:
  Analysis(const CellGeometry& cell, const CellDiscretization& mesh, const CellMaterial& material,
           const CellAnalysisOptions& o)
      : cell_(cell),
        mesh_(mesh),
        o_(o),
        law_(cohesive_law(material, o)),
        elastic_(material.elastic),
        axis_(cell.load == LoadAxis::X ? 0 : 1),
        far_(axis_ == 0 ? BoundaryPart::Right : BoundaryPart::Top),
        unit_(uniaxial_problem(cell.side_m, cell.load, 1.0 / cell.side_m, elastic_, o.nitsche_factor)),
        base_(build_rk_galerkin_model(mesh, o.rk)),
        stage_(base_, mesh, unit_, far_, axis_, constraint_points(unit_), o.enrichment, o.field_transfer,
               law_.activation_opening(), cracks_from_seeds(cell, mesh, o.growth)),
        tangent_(o.krylov_iterations),
        books_(o.energy_tolerance),
        steps_({o.opening_increment, o.min_opening_increment, o.max_opening_increment},
               {o.strain_increment, o.min_strain_increment, o.max_strain_increment}, o.step_growth),
        opening_mode_(o.verification.zone_at_every_step) {}

  CellResponse run(const FractureObserver& observer);
  const std::vector<Crack>& cracks() const { return stage_.cracks(); }

 private:
  const CellGeometry& cell_;
  const CellDiscretization& mesh_;
  const CellAnalysisOptions& o_;
  CohesiveLaw law_;
  PlaneStrain elastic_;
  int axis_ = 0;
  BoundaryPart far_ = BoundaryPart::Right;
  ElasticProblem unit_;
  RkGalerkinModel base_;
  CrackStage stage_;
  BorderedTangentSolver tangent_;
  Eigen::VectorXd d_;
  double lambda_ = 0.0;
  double scale_ = 1.0;  // residual scale
  CohesiveEvaluation eval_;
  EnergyBooks books_;
  double excess_energy(const CellState& s) const { return books_.excess(EnergyBooks::imbalance(s)); }
  // stored + dissipated - work at the current state, leaving the books as they were.
  double current_imbalance() {
    const EnergyBooks::Work w = books_.work_books();
    const double v = EnergyBooks::imbalance(state(0));
    books_.restore(w);
    return v;
  }
  double excess_energy() { return books_.excess(current_imbalance()); }
  double peak_ = 0.0;  // the largest sigma_bar so far
  void note_peak(const CellState& s) { peak_ = std::max(peak_, s.sigma_bar_Pa); }
  // GrowthFallback::UnloadAndRegrow's way back onto the loading path (path_modes.hpp). Its first
  // reload step is linear under displacement control (halved until no point dissipates in it, so the
  // trapezoid work of that step is exact).
  ReloadPath reload_;
  // Process-zone control (CellAnalysisOptions::zone_control): the cohesive points on their softening
  // envelope (flat_history() order), their length, and a counter that keys the LU's pattern.
  std::vector<char> zone_;
  double zone_length_ = 0.0;
  long zone_id_ = 0;
  // Selects the zone at the current state; false when no point is on its softening envelope.
  bool select_zone();
  // Selects the cohesive points of the segments active in `before` (growth re-equilibration).
  bool select_old_segments(const std::vector<Crack>& before);

  // The enriched model and system of the current cracks; with `keep_field`, d is transferred so the
  // displacement field stays what it was (field_transfer.hpp), else it is zero.
  void build_stage(bool keep_field = true) { d_ = stage_.rebuild(d_, keep_field); }
  std::vector<CohesiveHistory> flat_history() const { return stage_.flat_history(); }
  void commit(const std::vector<CohesiveHistory>& trial) { stage_.commit(trial); }
  double active_length() const { return stage_.active_length(); }

  // Energy dissipated per unit thickness by the cohesive points in `flat` (flat_history() order).
  double dissipated(const std::vector<CohesiveHistory>& flat) const {
    double sum = 0.0;
    for (std::size_t p = 0; p < flat.size(); ++p)
      sum += stage_.model().cohesive[p].weight * (law_.dissipated(flat[p].kappa) + flat[p].shear_dissipated);
    return sum;
  }

  // Dissipation below this is round-off (a point at its kappa to the last digit), not loading.
  double dissipation_round_off() const { return 1e-9 * law_.fracture_energy_J_m2 * active_length(); }


  // Newton at the constraint `hold` = target; with `viscosity`, the relaxation's pseudo-time step.
  NewtonResult newton(Hold hold, double target, std::vector<CohesiveHistory>& trial,
                      const OpeningViscosity* viscosity = nullptr);
  // JumpFallback::Relax: from the last accepted state, the far face one strain_increment further and
  // the pseudo-time relaxation there (see cell_analysis.hpp). Returns "" or a diagnostic.
  std::string relax(double dlambda, int& iterations);
  // Its parts: the largest motion of a cohesive point's opening (eval_) since `reference`, points
  // beyond w_c not counted; the norm of the viscous forces at the current state (r: the residual
  // without them, eval_ its evaluation).
  double opening_motion(const std::vector<std::array<double, 2>>& reference,
                        const std::vector<CohesiveHistory>& history) const;
  double viscous_force(const OpeningViscosity& viscosity, const std::vector<CohesiveHistory>& history,
                       Eigen::VectorXd& r);
  struct Snapshot {
    CrackStage::Saved cracks;  // the geometry and the cohesive history
    Eigen::VectorXd d;
    double lambda;
  };
  Snapshot snapshot() const { return {stage_.save(), d_, lambda_}; }
  // Back to a snapshot; `rebuild` when the crack geometry may have changed since.
  void restore(const Snapshot& s, bool rebuild) {
    stage_.restore(s.cracks);
    if (rebuild) build_stage(false);
    d_ = s.d;
    lambda_ = s.lambda;
  }
  // The path: what a step holds and targets, and how it ends.
  struct StepPlan {
    bool jump = false;     // relax() at the next strain (no continuation at the smallest step before)
    bool reload = false;   // the first, linear reload step after an unloading
    bool opening = false;  // a crack-opening hold (PathControl::CrackOpening, once there are cracks)
    bool zone = false;     // on the process zone's opening (after a fold of the global one)
    Hold hold = Hold::Lambda;
    double target = 0.0;
    double opening_before = 0.0;  // the opening integral at the start of the step
  };
  enum class StepEnd { Accepted, Retry, Stop };
  bool elastic_branch();  // 1.; false when the run ends there
  bool first_cracking();  // 2.; false when the run ends there
  StepPlan plan_step();
  StepEnd path_step(int step);  // 3.
  StepEnd after_accepted(const StepPlan& p, int iterations);
  // Back to the step's start with a smaller step; false when there is none (or the step was a jump).
  bool cut(const StepPlan& p, const Snapshot& start);
  StepEnd jump_or_fail(const StepPlan& p, const std::string& diagnostic);
  StepEnd retry(const StepPlan& p, const Snapshot& start, const std::string& diagnostic);
  bool in_compression() const;
  void record(const CellState& s);  // a state of the response (and to the observer)
  void accept(const CellState& s);  // an accepted path state: recorded, the books' reference, the peak
  CellResponse out_;
  const FractureObserver* observer_ = nullptr;
  PathSteps steps_;
  OpeningMode opening_mode_;  // ZoneControl::Fallback: the global opening or the process zone's (path_modes.hpp)
  std::string jump_reason_;      // set where the path has no continuation: the next step is a jump

  std::vector<TipCriterion> criteria();
  double max_ratio(const std::vector<TipCriterion>& t) const {
    double r = -std::numeric_limits<double>::infinity();
    for (const TipCriterion& c : t)
      if (c.valid) r = std::max(r, c.stress_Pa / law_.tensile_strength_Pa);
    return r;
  }
  // Grows every tip at f_t and re-equilibrates, repeatedly, until no tip is at f_t: Settled; Unloaded
  // when it passed a growth event by unloading (then there is no state to emit, the path reloads);
  // Failed with the diagnostic `why`.
  struct Growth {
    enum class Outcome { Settled, Unloaded, Failed } outcome = Outcome::Settled;
    std::string why;
  };
  static Growth failed(std::string why) { return {Growth::Outcome::Failed, std::move(why)}; }
  Growth grow(int& iterations);
  // Its parts. The tips at f_t, most stressed first:
  std::vector<std::size_t> tips_at_strength(const std::vector<TipCriterion>& t) const;
  // One growth round: the tips `ready` advance and the cell re-equilibrates (all of them, else only the
  // most stressed). NoGrowth: no tip could advance; NoEquilibrium: `why` none was found (restore!).
  struct GrowthRound {
    enum Outcome { NoGrowth, Equilibrium, NoEquilibrium } outcome;
    std::string why;
  };
  GrowthRound advance_and_equilibrate(const std::vector<std::size_t>& ready, const std::vector<TipCriterion>& t,
                                      const Snapshot& before, int& iterations);
  // Newton on the grown geometry under the growth hold; false (with why) when it fails or creates energy.
  bool equilibrate_grown(const Snapshot& before, int& iterations, std::string& why);
  // GrowthFallback::Relax: the tips advance and the crack runs (relax()); "" or a diagnostic.
  std::string run_through(const std::vector<std::size_t>& ready, const std::vector<TipCriterion>& t,
                          const Snapshot& before, const std::string& why, int& iterations);
  // GrowthFallback::UnloadAndRegrow (and the verification hook): unload, then advance.
  Growth unload_at_growth(const std::vector<std::size_t>& ready, const std::vector<TipCriterion>& t);
  std::string unreachable(double created) const;  // the diagnostic of a growth that creates energy
  // GrowthFallback::UnloadAndRegrow at the converged state before growth: unloads to zero along the
  // secants (the work is booked), then advances the crack tips `ready` in their `directions`.
  void unload_and_advance(const std::vector<std::size_t>& ready, const std::vector<TipCriterion>& t);
  // After the linear reload step: scales the state along its secant to where the first cohesive
  // point reaches its history opening or the first tip reaches f_t.
  void scale_to_envelope();
  CellState state(int iterations);
};

NewtonResult Analysis::newton(Hold hold, double target, std::vector<CohesiveHistory>& trial,
                              const OpeningViscosity* viscosity) {
  NewtonResult res;
  const std::vector<CohesiveHistory> committed = flat_history();
  FractureSystem& sys = stage_.system();
  const Eigen::VectorXd g = hold == Hold::Zone ? sys.opening_gradient(zone_) : sys.opening_gradient();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(g.size());
  const auto N = static_cast<Eigen::Index>(sys.dofs());
  Eigen::VectorXd r;
  // Backtracking: a full step that raises |r| is halved (up to line_search_halvings times). A point
  // switching branch of the piecewise-linear law (softening/unloading, open/contact) makes Newton
  // cycle between two or four iterates; a shorter step breaks the cycle.
  Eigen::VectorXd d_prev, x_prev;
  double lambda_prev = 0.0, r_prev = std::numeric_limits<double>::infinity(), alpha = 1.0;
  int halvings = 0;
  const double tolerance = o_.tolerance * scale_;
  for (int it = 0; it <= o_.max_iterations; ++it) {
    sys.evaluate(d_, lambda_, law_, committed, true, r, eval_, viscosity);
    const double cres = hold == Hold::Lambda ? lambda_ - target : g.dot(d_) - target;
    if (!r.allFinite()) {
      res.why = "the residual is not finite";
      return res;
    }
    // (Not once |r| meets the tolerance: then only the constraint may be unmet.)
    if (it > 0 && r.norm() >= r_prev && r.norm() > tolerance && halvings < o_.line_search_halvings &&
        it < o_.max_iterations) {
      alpha *= 0.5;
      ++halvings;
      d_ = d_prev + alpha * x_prev.head(N);
      lambda_ = lambda_prev + alpha * x_prev[N];
      continue;
    }
    const double cscale = hold == Hold::Lambda ? 1e-12 * std::max(std::abs(target), 1e-12)
                          : hold == Hold::Zone ? 1e-10 * law_.critical_opening() * zone_length_
                                               : 1e-10 * law_.critical_opening() * std::max(active_length(), 1e-12);
    if (it > 0 && r.norm() <= tolerance && std::abs(cres) <= cscale) {
      res.ok = true;
      res.iterations = it;
      trial = eval_.trial;
      return res;
    }
    if (it == o_.max_iterations) break;
    // The pattern is fixed per stage and constraint: the ordering and symbolic analysis are reused.
    // (A zone's row has its own pattern: a new analysis per zone.)
    const long key = viscosity          ? -(1L << 40) - stage_.id()
                     : hold == Hold::Zone ? -2 - zone_id_
                                          : 2 * stage_.id() + (hold == Hold::Lambda ? 0 : 1);
    // The constraint row is scaled so that its tolerance is the residual's (GMRES minimizes one norm
    // over both).
    const auto assemble = [&](double row_scale) {
      return hold == Hold::Lambda ? sys.bordered(zero, row_scale) : sys.bordered(g * row_scale, 0.0);
    };
    BorderedTangentSolver::Correction c = tangent_.solve(key, it == 0, tolerance / cscale, assemble, r, cres, tolerance);
    if (!c.ok) {
      res.why = c.why;
      return res;
    }
    const Eigen::VectorXd& x = c.x;
    d_prev = d_;
    lambda_prev = lambda_;
    x_prev = x;
    // |r| is the merit only once the (linear) constraint holds: the first step of a path increment
    // starts in equilibrium off the new constraint, so its |r| must rise.
    r_prev = std::abs(cres) <= cscale ? r.norm() : std::numeric_limits<double>::infinity();
    alpha = 1.0;
    halvings = 0;
    d_ += x.head(N);
    lambda_ += x[N];
  }
  res.why = fmt::format("no convergence in {} iterations (|r| = {:.3e}, tolerance {:.3e})", o_.max_iterations, r.norm(),
                        tolerance);
  return res;
}

std::vector<TipCriterion> Analysis::criteria() {
  const TipSamples s = tip_samples(cell_, mesh_, stage_.cracks(), o_.growth);
  std::vector<std::array<double, 3>> stress(s.crack.size());
  if (!s.crack.empty()) {
    const GeneralTable t = enriched_table_at(base_, stage_.model(), stage_.cracks(), s.x);
    const std::array<double, 9> D = elastic_.D();
    for (std::size_t p = 0; p < t.size(); ++p) stress[p] = apply_D(D, t.strain(p, d_));
  }
  return tip_criteria(stage_.cracks(), s, stress);
}

Analysis::Growth Analysis::grow(int& iterations) {
  for (int round = 0; round < o_.max_growth_per_step; ++round) {
    const std::vector<TipCriterion> t = criteria();
    const std::vector<std::size_t> ready = tips_at_strength(t);
    if (ready.empty()) return {};
    if (o_.verification.unload_at_every_growth) return unload_at_growth(ready, t);
    const Snapshot before = snapshot();
    const GrowthRound g = advance_and_equilibrate(ready, t, before, iterations);
    if (g.outcome == GrowthRound::NoGrowth) return {};
    if (g.outcome == GrowthRound::Equilibrium) continue;
    restore(before, true);
    switch (o_.growth_fallback) {
      case GrowthFallback::Fail: return failed("re-equilibration after crack growth failed: " + g.why);
      case GrowthFallback::Relax:
        if (std::string why = run_through(ready, t, before, g.why, iterations); !why.empty()) return failed(why);
        continue;
      case GrowthFallback::UnloadAndRegrow: return unload_at_growth(ready, t);  // at zero load no tip is at f_t
    }
  }
  return {};
}

std::vector<std::size_t> Analysis::tips_at_strength(const std::vector<TipCriterion>& t) const {
  std::vector<std::size_t> ready;
  for (std::size_t c = 0; c < t.size(); ++c)
    if (t[c].valid && t[c].stress_Pa >= law_.tensile_strength_Pa * (1.0 - 1e-9)) ready.push_back(c);
  std::stable_sort(ready.begin(), ready.end(), [&](std::size_t a, std::size_t b) { return t[a].stress_Pa > t[b].stress_Pa; });
  return ready;
}

std::string Analysis::unreachable(double created) const {
  return fmt::format("re-equilibration after crack growth creates energy ({:.3g} of the largest work)",
                     created / books_.largest_work());
}

Analysis::Growth Analysis::unload_at_growth(const std::vector<std::size_t>& ready, const std::vector<TipCriterion>& t) {
  // An unload books the state as it is: growth rounds before it that created energy (a re-equilibration
  // into an unreachable equilibrium) would pass unseen, so they fail the load step instead.
  if (const double created = excess_energy(); created > 0.0) return failed(unreachable(created));
  unload_and_advance(ready, t);
  return {Growth::Outcome::Unloaded, ""};
}

Analysis::GrowthRound Analysis::advance_and_equilibrate(const std::vector<std::size_t>& ready,
                                                        const std::vector<TipCriterion>& t, const Snapshot& before,
                                                        int& iterations) {
  std::string why;
  // Every tip at f_t advances; if the new geometry does not re-equilibrate, only the most stressed.
  for (int attempt = 0; attempt < 2; ++attempt) {
    if (attempt == 1) {
      if (ready.size() == 1) break;
      restore(before, true);
    }
    bool grew = false;
    for (std::size_t k = 0; k < (attempt == 0 ? ready.size() : 1); ++k)
      grew = advance_crack(stage_.cracks(), ready[k], t[ready[k]].direction, cell_, mesh_, o_.growth) || grew;
    if (!grew) {
      if (attempt == 0) return {GrowthRound::NoGrowth, ""};
      break;
    }
    build_stage();
    if (equilibrate_grown(before, iterations, why)) return {GrowthRound::Equilibrium, ""};
  }
  return {GrowthRound::NoEquilibrium, why};
}

bool Analysis::equilibrate_grown(const Snapshot& before, int& iterations, std::string& why) {
  // Re-equilibrate the new geometry: at the same far-face displacement while nothing softens (the
  // new segments sit on their stiff activation branch), at the same crack opening afterwards (on
  // the softening branch a fixed displacement may have no nearby equilibrium): by default that of
  // the segments there were before, as a Hold::Zone of them (GrowthHold, cell_analysis.hpp).
  const bool opening = o_.control == PathControl::CrackOpening && stage_.softening();
  const bool old_only = opening && o_.growth_hold == GrowthHold::OldSegments && select_old_segments(before.cracks.cracks);
  const Hold hold = old_only ? Hold::Zone : opening ? Hold::Opening : Hold::Lambda;
  const double target = old_only  ? stage_.system().opening_gradient(zone_).dot(d_)
                        : opening ? stage_.system().opening_integral(d_)
                                  : lambda_;
  const Eigen::VectorXd d0 = d_;
  const double l0 = lambda_;
  std::vector<CohesiveHistory> trial;
  NewtonResult n = newton(hold, target, trial);
  if (!n.ok && hold != Hold::Lambda) {
    d_ = d0;
    lambda_ = l0;
    n = newton(Hold::Lambda, l0, trial);
  }
  if (!n.ok) {
    why = n.why;
    return false;
  }
  iterations += n.iterations;
  commit(trial);
  // An equilibrium out of reach (one that creates energy: the held opening or displacement found
  // a far branch) counts as none, whatever the fallback. It was common while build_stage carried
  // the enriched coefficients by crack and node (field_transfer.hpp: at a junction Newton then
  // started from another field, with spurious strain energy); the field transfer made it rare.
  // Unloading first makes any change of functions free (d = 0); the relaxation lets the crack run.
  if (const double created = excess_energy(); created > 0.0) {
    why = unreachable(created);
    return false;
  }
  return true;
}

std::string Analysis::run_through(const std::vector<std::size_t>& ready, const std::vector<TipCriterion>& t,
                                  const Snapshot& before, const std::string& why, int& iterations) {
  // The grown crack has no equilibrium near this one: it runs (a jump at this strain).
  const double start = current_imbalance();
  for (const std::size_t c : ready) advance_crack(stage_.cracks(), c, t[c].direction, cell_, mesh_, o_.growth);
  build_stage();
  if (const std::string r = relax(0.0, iterations); !r.empty()) {
    restore(before, true);
    return "re-equilibration after crack growth failed (" + why + "), and so did the relaxation: " + r;
  }
  const double released = start - current_imbalance();
  if (released < -o_.energy_tolerance * books_.largest_work()) {
    restore(before, true);
    return "the relaxation after crack growth creates energy (" + unreachable(-released) + ")";
  }
  books_.book_jump(released);
  return "";
}

void Analysis::scale_to_envelope() {
  // With the history fixed every point keeps its branch (secant, or contact: the sign of w_n is
  // kept) when d and lambda are scaled, so the scaled state is an equilibrium until some point
  // reaches its kappa or some tip reaches f_t; all of those are linear in the scale.
  Eigen::VectorXd r;
  const std::vector<CohesiveHistory> h = flat_history();
  stage_.system().evaluate(d_, lambda_, law_, h, false, r, eval_);
  double ratio = max_ratio(criteria());
  for (std::size_t p = 0; p < h.size(); ++p) {
    const double wn = std::max(eval_.opening[p][0], 0.0), wt = eval_.opening[p][1];
    const double weff = law_.mode == CohesiveMode::ModeI ? wn : std::hypot(wn, wt);
    ratio = std::max(ratio, weff / h[p].kappa);
  }
  if (!(ratio > 0.0) || ratio >= 1.0) return;
  const double scale = (1.0 - 1e-9) / ratio;
  d_ *= scale;
  lambda_ *= scale;
}

// A pseudo-step whose viscous forces are below this fraction of the residual tolerance moved by noise.
constexpr double kViscousFraction = 0.1;

std::string Analysis::relax(double dlambda, int& iterations) {
  // A viscous stiffness above the softening slope makes every cohesive point monotone within a
  // pseudo-step (plus the positive definite bulk), so Newton converges where the quasi-static path has
  // no continuation. The pseudo-time step grows (k_v falls) after easy steps, since an unstable mode
  // grows slowly at first, and shrinks (k_v x 4) when one does not converge. The jump ends when the
  // openings stop moving and the law alone is in equilibrium.
  const double softening = law_.tensile_strength_Pa / (law_.critical_opening() - law_.activation_opening());
  const double settled = 1e-6 * law_.critical_opening();
  const double target = lambda_ + dlambda;
  double kv = o_.relaxation_ratio * softening;
  Eigen::VectorXd r;
  stage_.system().evaluate(d_, lambda_, law_, flat_history(), false, r, eval_);
  std::vector<std::array<double, 2>> reference = eval_.opening;
  for (int k = 0; k < o_.max_relaxation_steps; ++k) {
    const OpeningViscosity viscosity{kv, &reference};
    const Eigen::VectorXd d0 = d_;
    const double l0 = lambda_;
    std::vector<CohesiveHistory> trial;
    const NewtonResult n = newton(Hold::Lambda, target, trial, &viscosity);
    if (!n.ok) {
      d_ = d0;
      lambda_ = l0;
      kv *= 4.0;
      if (kv > 1e3 * o_.relaxation_ratio * softening) return fmt::format("relaxation step {}: {}", k, n.why);
      continue;
    }
    iterations += n.iterations;
    commit(trial);
    const std::vector<CohesiveHistory> history = flat_history();
    const double moved = opening_motion(reference, history);
    // Motion the tolerance cannot resolve does not count either: Newton stops anywhere within
    // |r| <= tolerance, which on a nearly free point (a secant of 1e-4 K0 at kappa = 0.94 w_c) leaves
    // its opening uncertain by far more than `settled`, and at a contact kink the pseudo-steps then
    // chatter around the equilibrium forever (6.5 mm #3 of the 20-cell study: 1e-10 m to and fro for
    // 2000 steps). So the viscous forces of the step, k_v (w - w_previous) assembled, are also
    // compared with the tolerance: below kViscousFraction of it, the step moved by noise.
    const double viscous = viscous_force(viscosity, history, r);
    reference = eval_.opening;
    if (n.iterations <= o_.easy_iterations) kv = std::max(kv / o_.step_growth, 1e-2 * softening);
    if (moved > settled && viscous > kViscousFraction * o_.tolerance * scale_) continue;
    if (r.norm() <= o_.tolerance * scale_) return "";
  }
  return fmt::format("relaxation did not settle in {} pseudo-time steps", o_.max_relaxation_steps);
}

double Analysis::opening_motion(const std::vector<std::array<double, 2>>& reference,
                                const std::vector<CohesiveHistory>& history) const {
  // A point opened past w_c keeps only the residual spring and, when its faces touch, slides
  // frictionless: a fragment held only by such points creeps on under forces below the tolerance
  // and would never settle. Components without cohesive stiffness do not count as moving.
  double moved = 0.0;
  for (std::size_t p = 0; p < reference.size(); ++p) {
    const bool free = history[p].kappa >= law_.critical_opening();
    const double dn = free && eval_.opening[p][0] >= 0.0 ? 0.0 : eval_.opening[p][0] - reference[p][0];
    const double dt = free ? 0.0 : eval_.opening[p][1] - reference[p][1];
    moved = std::max(moved, std::hypot(dn, dt));
  }
  return moved;
}

double Analysis::viscous_force(const OpeningViscosity& viscosity, const std::vector<CohesiveHistory>& history,
                               Eigen::VectorXd& r) {
  Eigen::VectorXd rv;
  stage_.system().evaluate(d_, lambda_, law_, history, false, rv, eval_, &viscosity);
  stage_.system().evaluate(d_, lambda_, law_, history, false, r, eval_);
  return (rv - r).norm();
}

void Analysis::unload_and_advance(const std::vector<std::size_t>& ready, const std::vector<TipCriterion>& t) {
  // Secant unloading is linear and path independent (every point's traction is S(kappa) [[u]], or
  // the contact penalty), so d = 0 at lambda = 0 is the exact unloaded state and the work of the
  // unloading is -1/2 F lambda; the trapezoid to here books the step that reached this state.
  const double F = stage_.system().reaction(d_, lambda_);
  const double unload_strain = lambda_ / cell_.side_m;
  books_.book_unload(lambda_, F, dissipated(flat_history()));
  d_.setZero();
  lambda_ = 0.0;
  for (const std::size_t c : ready) advance_crack(stage_.cracks(), c, t[c].direction, cell_, mesh_, o_.growth);
  build_stage();  // the new segments start at zero opening: equilibrium holds exactly
  reload_.unloaded(unload_strain, cell_.side_m, dissipated(flat_history()));
}

bool Analysis::select_old_segments(const std::vector<Crack>& before) {
  zone_.assign(stage_.model().cohesive.size(), 0);
  zone_length_ = 0.0;
  for (std::size_t p = 0; p < zone_.size(); ++p) {
    const CohesivePoint& q = stage_.model().cohesive[p];
    if (static_cast<std::size_t>(q.segment) < before[static_cast<std::size_t>(q.crack)].active) {
      zone_[p] = 1;
      zone_length_ += q.weight;
    }
  }
  ++zone_id_;
  return zone_length_ > 0.0;
}

bool Analysis::select_zone() {
  // On the envelope: the effective opening at the point's history maximum, short of w_c (beyond it
  // the point is traction-free and opens freely; holding it would hold nothing).
  Eigen::VectorXd r;
  const std::vector<CohesiveHistory> h = flat_history();
  stage_.system().evaluate(d_, lambda_, law_, h, false, r, eval_);
  zone_.assign(h.size(), 0);
  zone_length_ = 0.0;
  for (std::size_t p = 0; p < h.size(); ++p) {
    const double wn = std::max(eval_.opening[p][0], 0.0), wt = eval_.opening[p][1];
    const double weff = law_.mode == CohesiveMode::ModeI ? wn : std::hypot(wn, wt);
    if (weff >= (1.0 - 1e-6) * h[p].kappa && h[p].kappa < law_.critical_opening()) {
      zone_[p] = 1;
      zone_length_ += stage_.model().cohesive[p].weight;
    }
  }
  ++zone_id_;
  return zone_length_ > 0.0;
}

CellState Analysis::state(int iterations) {
  CellState s;
  FractureSystem& sys = stage_.system();
  const std::vector<CohesiveHistory> h = flat_history();
  Eigen::VectorXd r;
  sys.evaluate(d_, lambda_, law_, h, false, r, eval_);
  const double F = sys.reaction(d_, lambda_);
  s.strain = lambda_ / cell_.side_m;
  s.sigma_bar_Pa = F / cell_.side_m;
  s.bulk_energy_J_m = sys.bulk_energy(d_);
  const double stored = s.bulk_energy_J_m + sys.boundary_energy(d_, lambda_);
  double coh = 0.0, wmax = 0.0;
  for (std::size_t p = 0; p < h.size(); ++p) {
    const double w = stage_.model().cohesive[p].weight;
    coh += 0.5 * w * (eval_.traction[p][0] * eval_.opening[p][0] + eval_.traction[p][1] * eval_.opening[p][1]);
    wmax = std::max(wmax, eval_.opening[p][0]);
  }
  s.cohesive_energy_J_m = coh;
  s.dissipated_J_m = dissipated(h);
  s.jump_dissipated_J_m = books_.jump_dissipated();
  s.external_work_J_m = books_.book_work(lambda_, F);
  if (books_.largest_work() > 0.0) books_.note_operator_mismatch(std::abs(sys.operator_energy(d_, lambda_) - stored));
  s.max_opening_m = wmax;
  for (const Crack& c : stage_.cracks()) s.crack_segments += c.active;
  s.open_segments = stage_.open_segments();
  s.newton_iterations = iterations;
  return s;
}

CellResponse Analysis::run(const FractureObserver& observer) {
  observer_ = &observer;
  out_.side_m = cell_.side_m;
  out_.porosity = cell_.porosity();
  record(CellState{});
  build_stage();
  out_.nodes = base_.node_count();
  if (elastic_branch() && first_cracking()) {
    out_.status = CellStatus::ReachedEnd;
    for (int step = 0; step < o_.max_steps; ++step)
      if (path_step(step) == StepEnd::Stop) break;
    if (out_.status == CellStatus::ReachedEnd && out_.diagnostic.empty()) out_.diagnostic = "reached max_steps";
  }
  out_.dofs = stage_.model().dof_count();
  out_.enriched_nodes = stage_.model().enriched_node.size();
  out_.growth_unloads = reload_.unloads();
  out_.jumps = books_.jumps();
  out_.factorizations = tangent_.factorizations();
  out_.crack_geometries = static_cast<std::size_t>(stage_.id());
  out_.krylov_corrections = tangent_.krylov_corrections();
  out_.krylov_products = tangent_.krylov_products();
  out_.operator_energy_mismatch = books_.operator_mismatch();
  return std::move(out_);
}

void Analysis::record(const CellState& s) {
  out_.states.push_back(s);
  if (*observer_) (*observer_)(out_.states.size() - 1, s);
}

void Analysis::accept(const CellState& s) {
  books_.accept(EnergyBooks::imbalance(s));
  record(s);
  note_peak(s);
}

bool Analysis::elastic_branch() {
  // The response is linear until the first tip reaches f_t: one solve, K d1 = f_unit at lambda = 1,
  // and the states there are its multiples.
  FractureSystem& sys = stage_.system();
  const auto N = static_cast<Eigen::Index>(sys.dofs());
  Eigen::VectorXd r;
  sys.evaluate(Eigen::VectorXd::Zero(N), 0.0, law_, {}, true, r, eval_);
  const Eigen::SparseMatrix<double> J = sys.bordered(Eigen::VectorXd::Zero(N), 1.0);  // the LU keeps a reference
  Eigen::UmfPackLU<Eigen::SparseMatrix<double>> lu(J);
  if (lu.info() != Eigen::Success) {
    out_.status = CellStatus::Failed;
    out_.diagnostic = "UMFPACK: the elastic stiffness is singular";
    return false;
  }
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(N + 1);
  rhs[N] = 1.0;
  const Eigen::VectorXd d1 = lu.solve(rhs).head(N);
  d_ = d1;
  lambda_ = 1.0;
  out_.E0_bar_Pa = sys.reaction(d1, 1.0);  // (F1 / side) / (1 / side)
  const double ratio1 = max_ratio(criteria());
  const double lambda_max = o_.max_strain * cell_.side_m;
  const double lambda_act = ratio1 > 0.0 ? 1.0 / ratio1 : std::numeric_limits<double>::infinity();
  const double lambda_end = std::min(lambda_act, lambda_max);
  scale_ = sys.unit_load().norm() * lambda_end;
  const int ne = std::max(1, o_.elastic_states);
  for (int k = 1; k <= ne; ++k) {
    lambda_ = lambda_end * k / ne;
    d_ = lambda_ * d1;
    record(state(0));
  }
  books_.accept(EnergyBooks::imbalance(out_.states.back()));
  note_peak(out_.states.back());
  if (!(lambda_act <= lambda_max)) {
    out_.status = CellStatus::ReachedEnd;
    out_.diagnostic = "no crack reached the growth criterion below max_strain";
    return false;
  }
  return true;
}

bool Analysis::first_cracking() {
  int iterations = 0;
  const Growth g = grow(iterations);
  if (g.outcome == Growth::Outcome::Failed) {
    out_.status = CellStatus::Failed;
    out_.diagnostic = fmt::format("at e_bar = {:.4e}: {}", lambda_ / cell_.side_m, g.why);
    return false;
  }
  if (g.outcome == Growth::Outcome::Settled) accept(state(iterations));
  return true;
}

Analysis::StepPlan Analysis::plan_step() {
  StepPlan p;
  p.jump = !jump_reason_.empty();
  p.reload = !p.jump && reload_.phase() == ReloadPath::Phase::LinearStep;
  p.opening = !p.jump && !p.reload && o_.control == PathControl::CrackOpening && active_length() > 0.0;
  p.zone = p.opening && opening_mode_.mode() == OpeningMode::Mode::ProcessZone && select_zone();
  p.hold = p.zone ? Hold::Zone : p.opening ? Hold::Opening : Hold::Lambda;
  p.opening_before = stage_.system().opening_integral(d_);
  const double step = steps_.size(p.hold);
  p.target = p.reload    ? reload_.target_lambda()
             : p.zone    ? stage_.system().opening_gradient(zone_).dot(d_) + step * law_.critical_opening() * zone_length_
             : p.opening ? p.opening_before + step * law_.critical_opening() * active_length()
                         : lambda_ + step * cell_.side_m;
  return p;
}

bool Analysis::cut(const StepPlan& p, const Snapshot& start) {
  if (p.jump) return false;  // a jump is not cut: it is accepted as it is, or the cell fails
  d_ = start.d;
  lambda_ = start.lambda;
  if (p.reload) {  // below 1/64 of the unloading strain: reload by the ordinary steps instead
    reload_.halve();
    return true;
  }
  return steps_.cut(p.hold);
}

Analysis::StepEnd Analysis::jump_or_fail(const StepPlan& p, const std::string& diagnostic) {
  // A failure at the smallest step becomes a jump, once (JumpFallback::Relax), else the cell fails.
  if (o_.jump == JumpFallback::Relax && !p.jump && reload_.phase() != ReloadPath::Phase::LinearStep) {
    jump_reason_ = diagnostic;
    return StepEnd::Retry;
  }
  out_.status = CellStatus::Failed;
  out_.diagnostic = p.jump ? fmt::format("{}; it followed a jump taken because {}", diagnostic, jump_reason_) : diagnostic;
  return StepEnd::Stop;
}

Analysis::StepEnd Analysis::retry(const StepPlan& p, const Snapshot& start, const std::string& diagnostic) {
  return cut(p, start) ? StepEnd::Retry : jump_or_fail(p, diagnostic);
}

bool Analysis::in_compression() const {
  // The tension path stays at lambda >= 0 and F >= 0 (a snap-back tends to the origin); past it lies a
  // spurious branch where contact closes the cell around a still-opening process zone.
  return lambda_ < 0.0 || stage_.system().reaction(d_, lambda_) < 0.0;
}

Analysis::StepEnd Analysis::path_step(int step) {
  const StepPlan p = plan_step();
  const Snapshot start = snapshot();
  const double e0 = start.lambda / cell_.side_m;
  std::vector<CohesiveHistory> trial;
  NewtonResult n;
  if (p.jump) {
    n.why = relax(o_.strain_increment * cell_.side_m, n.iterations);
    n.ok = n.why.empty();
    trial = flat_history();  // relax() commits its pseudo-steps
  } else {
    n = newton(p.hold, p.target, trial);
  }
  if (!n.ok) {
    if (cut(p, start)) return StepEnd::Retry;
    // The global opening integral may pass a maximum (points elsewhere close faster than the process
    // zone opens): the process zone's own opening still grows, so step on it instead.
    if (p.opening && !p.zone && o_.zone_control == ZoneControl::Fallback && select_zone()) {
      opening_mode_.folded(n.why);
      steps_.reset_openings();
      return StepEnd::Retry;
    }
    return jump_or_fail(p, fmt::format("at e_bar = {:.4e}, step {}: {} ({}{})", e0, step, n.why,
                                       p.jump ? "the jump" : "smallest step",
                                       p.zone ? "; the crack-opening step before: " + opening_mode_.fold_reason() : ""));
  }
  if (!p.reload && in_compression())
    return retry(p, start, fmt::format("at e_bar = {:.4e}, step {}: the smallest step crosses into compression", e0, step));
  const std::vector<CohesiveHistory> committed = flat_history();
  // The first reload step is linear: it may not dissipate (then its trapezoid work is exact).
  if (p.reload && dissipated(trial) > dissipated(committed) + dissipation_round_off()) {
    cut(p, start);
    return StepEnd::Retry;
  }
  commit(trial);
  if (p.reload) {
    reload_.linear_step_taken();
    scale_to_envelope();
  }
  // Overshoot of the growth criterion: cut, so cracks advance close to f_t.
  if (max_ratio(criteria()) > 1.0 + o_.growth_tolerance) {
    commit(committed);
    if (cut(p, start)) return StepEnd::Retry;
    commit(trial);  // at the smallest step: accept the overshoot
  }
  int iterations = n.iterations;
  const Growth g = grow(iterations);
  if (g.outcome == Growth::Outcome::Failed) {
    restore(start, true);  // back to the start of the step, geometry included, with a smaller step
    return retry(p, start, fmt::format("at e_bar = {:.4e}: {} (smallest step)", lambda_ / cell_.side_m, g.why));
  }
  if (g.outcome == Growth::Outcome::Unloaded) return StepEnd::Retry;  // reload, then on with the step sizes in use
  // The growth's re-equilibration can land on the compression branch too (a 3.0 mm cell went from
  // e = 3.8e-4 to -2.3e-4 at -9.6 MPa in one step and was taken as separated).
  if (!p.reload && in_compression()) {
    restore(start, true);
    return retry(p, start, fmt::format("at e_bar = {:.4e}, step {}: the growth at the smallest step crosses into compression",
                                       e0, step));
  }
  // Energy admissibility: an equilibrium at the end of a step can still be out of reach from its start
  // (a fragment whose cracks opened past w_c at zero load, dissipating what no work paid for).
  const EnergyBooks::Work before = books_.work_books();
  CellState next = state(iterations);
  if (const double created = excess_energy(next); created > 0.0) {
    books_.restore(before);
    restore(start, true);
    return retry(p, start, fmt::format("at e_bar = {:.4e}, step {}: the smallest step creates energy ({:.3g} of the "
                                       "largest work)", e0, step, created / books_.largest_work()));
  }
  if (p.jump) {
    // What the jump released: the stored and dissipated energy it lost against the work.
    books_.book_jump(books_.accepted_imbalance() - EnergyBooks::imbalance(next));
    next.jump_dissipated_J_m = books_.jump_dissipated();
    jump_reason_.clear();
    steps_.reset_openings();
    opening_mode_.back_to_global();
  }
  accept(next);
  return after_accepted(p, n.iterations);
}

Analysis::StepEnd Analysis::after_accepted(const StepPlan& p, int iterations) {
  const CellState& s = out_.states.back();
  if (iterations <= o_.easy_iterations) steps_.grow(p.hold);
  // Back to the global opening once it grows again.
  if (p.zone && !opening_mode_.always_zone() && stage_.system().opening_integral(d_) > p.opening_before)
    opening_mode_.back_to_global();
  // Back on the envelope once some point dissipates beyond round-off.
  reload_.dissipated(s.dissipated_J_m, dissipation_round_off());
  // Separated: sigma_bar below separation_fraction x the peak; on a reload (a secant through the
  // origin), the stress it would have at the strain it was unloaded from.
  const double floor = o_.separation_fraction * peak_ * reload_.separation_scale(s.strain);
  if (active_length() > 0.0 && s.sigma_bar_Pa < floor) {
    out_.status = CellStatus::Separated;
    return StepEnd::Stop;
  }
  if (std::abs(s.strain) > o_.max_strain) {
    out_.diagnostic = "reached max_strain";
    return StepEnd::Stop;
  }
  return StepEnd::Accepted;
}

}  // namespace

CellResponse analyze_cell(const CellGeometry& cell, const CellDiscretization& mesh, const CellMaterial& material,
                          const CellAnalysisOptions& options, const FractureObserver& observer,
                          std::vector<Crack>* final_cracks) {
  const auto t0 = std::chrono::steady_clock::now();
  Analysis a(cell, mesh, material, options);
  CellResponse r = a.run(observer);
  if (final_cracks) *final_cracks = a.cracks();
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

double state_damage(const CellResponse& r, const CellState& s) {
  if (s.strain == 0.0 || r.E0_bar_Pa == 0.0) return 0.0;
  return 1.0 - s.sigma_bar_Pa / (r.E0_bar_Pa * s.strain);
}

}  // namespace uhpc::micro
