#pragma once
// The energy books of the crack analysis of one cell (per unit thickness, J/m): the external work done
// on the far face, booked by the trapezoid rule between accepted states (exact on the linear branches
// of the piecewise-linear cohesive law), and the admissibility test every step must pass: a step may
// not create energy, i.e. raise the imbalance (stored + dissipated - work) by more than
// `tolerance` x the largest work so far (docs/physics.md section 2; CellAnalysisOptions::energy_tolerance).
// Jumps (JumpFallback::Relax) release energy a real test would lose as kinetic energy; it is booked
// apart. Pure bookkeeping: the caller evaluates the states.
#include <algorithm>
#include <cstddef>

#include "cell_response.hpp"

namespace uhpc::micro {

class EnergyBooks {
 public:
  explicit EnergyBooks(double tolerance) : tolerance_(tolerance) {}

  // stored + dissipated - work of a state.
  static double imbalance(const CellState& s) { return s.accounted_energy_J_m() - s.external_work_J_m; }

  // Books the work of the path from the last booked point to (lambda, F) and returns the total.
  double book_work(double lambda, double F) {
    work_ += 0.5 * (last_force_ + F) * (lambda - last_lambda_);
    last_force_ = F;
    last_lambda_ = lambda;
    largest_work_ = std::max(largest_work_, work_);
    return work_;
  }
  // Unloading along the secants from (lambda, F) to zero (exact for this law: -1/2 F lambda), after
  // booking the step that reached (lambda, F); nothing is stored at zero load, so the imbalance there
  // is the dissipated energy less the work.
  void book_unload(double lambda, double F, double dissipated) {
    work_ += 0.5 * (last_force_ + F) * (lambda - last_lambda_) - 0.5 * F * lambda;
    last_force_ = 0.0;
    last_lambda_ = 0.0;
    accepted_imbalance_ = dissipated - work_;
  }
  // |operator energy - stored energy| of a state relative to the largest work
  // (CellResponse::operator_energy_mismatch); ignored before any work is done.
  void note_operator_mismatch(double absolute) {
    if (largest_work_ > 0.0) operator_mismatch_ = std::max(operator_mismatch_, absolute / largest_work_);
  }
  // The imbalance of the last accepted state: the reference of the admissibility test.
  void accept(double imbalance) { accepted_imbalance_ = imbalance; }
  double accepted_imbalance() const { return accepted_imbalance_; }
  // The energy created since the last accepted state by a state of this imbalance, if beyond the
  // tolerance (else 0).
  double excess(double imbalance_now) const {
    const double created = imbalance_now - accepted_imbalance_;
    return created > tolerance_ * std::max(largest_work_, 1e-300) ? created : 0.0;
  }
  // A jump released this much (negative: round-off, booked as zero).
  void book_jump(double released) {
    jump_dissipated_ += std::max(released, 0.0);
    ++jumps_;
  }

  double largest_work() const { return largest_work_; }
  double operator_mismatch() const { return operator_mismatch_; }
  double jump_dissipated() const { return jump_dissipated_; }
  std::size_t jumps() const { return jumps_; }

  // The work books (not the accepted imbalance or the jumps), to evaluate a trial state and undo it.
  struct Work {
    double work, last_force, last_lambda, largest_work, operator_mismatch;
  };
  Work work_books() const { return {work_, last_force_, last_lambda_, largest_work_, operator_mismatch_}; }
  void restore(const Work& w) {
    work_ = w.work;
    last_force_ = w.last_force;
    last_lambda_ = w.last_lambda;
    largest_work_ = w.largest_work;
    operator_mismatch_ = w.operator_mismatch;
  }

 private:
  double tolerance_;
  double work_ = 0.0, last_force_ = 0.0, last_lambda_ = 0.0;
  double largest_work_ = 0.0, operator_mismatch_ = 0.0;
  double accepted_imbalance_ = 0.0;
  double jump_dissipated_ = 0.0;
  std::size_t jumps_ = 0;
};

}  // namespace uhpc::micro
