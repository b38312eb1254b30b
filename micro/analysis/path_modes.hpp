#pragma once
// The two modes a crack analysis's path can be in besides plain loading (cell_analysis.hpp: 2.'s
// GrowthFallback and 3.'s process-zone control),
// each a small state machine with named phases, so that the path's code asks "which phase" instead of
// reading flags that together mean one.
#include <cstddef>
#include <string>

namespace uhpc::micro {

// GrowthFallback::UnloadAndRegrow's way back onto the loading path:
//
//   Loading     --unloaded()-->          LinearStep  a growth event found no equilibrium: the cell was
//                                                    unloaded along its secants to zero (at strain e_u,
//                                                    having dissipated D_u) and its tips advanced there
//                                        OnSecant    the same at e_u <= 0 (a re-equilibration that had
//                                                    landed in compression): no linear step to take
//   LinearStep  --linear_step_taken()--> OnSecant    the first reload step, linear under displacement
//                                                    control to e_u, was accepted
//   LinearStep  --halve()-->             LinearStep  it dissipated or failed: half its target, or
//                                        OnSecant    ordinary steps once the target is below e_u / 64
//   OnSecant    --dissipated()-->        Loading     an accepted state has dissipated beyond D_u again
//   LinearStep  --dissipated()-->        Loading     the same, reached by a jump (a relaxation taken right
//                                                    after the unload): the cell is on its envelope, and a
//                                                    linear step, which must not dissipate, has no use
//
// Until Loading again the cell is on a secant through the origin, so its separation is measured at
// the stress that secant has at the strain it was unloaded from (separation_scale).
class ReloadPath {
 public:
  enum class Phase { Loading, LinearStep, OnSecant };
  Phase phase() const { return phase_; }
  std::size_t unloads() const { return unloads_; }

  void unloaded(double unload_strain, double side_m, double dissipated_J_m) {
    unload_strain_ = unload_strain;
    side_m_ = side_m;
    dissipated_at_unload_ = dissipated_J_m;
    target_lambda_ = unload_strain_ * side_m_;
    phase_ = Phase::LinearStep;
    if (!(target_lambda_ > 0.0)) to_secant();
    ++unloads_;
  }
  // The far-face displacement the linear step goes to (LinearStep only).
  double target_lambda() const { return target_lambda_; }
  void halve() {
    target_lambda_ *= 0.5;
    if (target_lambda_ < unload_strain_ * side_m_ / 64.0) to_secant();
  }
  void linear_step_taken() { to_secant(); }
  // An accepted state that has dissipated `dissipated_J_m`: back on the envelope once that passes the
  // dissipation at the unload by more than `round_off`.
  void dissipated(double dissipated_J_m, double round_off) {
    if (phase_ != Phase::Loading && dissipated_J_m > dissipated_at_unload_ + round_off) {
      target_lambda_ = 0.0;
      phase_ = Phase::Loading;
    }
  }
  // The factor on the separation threshold at `strain`: strain / e_u on the secant, 1 when loading.
  double separation_scale(double strain) const { return phase_ == Phase::Loading ? 1.0 : strain / unload_strain_; }

 private:
  void to_secant() {
    target_lambda_ = 0.0;
    phase_ = Phase::OnSecant;
  }
  Phase phase_ = Phase::Loading;
  std::size_t unloads_ = 0;
  double unload_strain_ = 0.0, side_m_ = 0.0, dissipated_at_unload_ = 0.0, target_lambda_ = 0.0;
};

// ZoneControl::Fallback's choice of the opening a crack-opening step holds:
//
//   Global       --folded(why)-->     ProcessZone  the global opening integral passed a maximum (a
//                                                  crack-opening step failed at its smallest size) and
//                                                  the process zone's own opening still grows
//   ProcessZone  --back_to_global()-> Global       the global integral grows again, or a jump was taken
//
// The verification hook zone_at_every_step keeps it in ProcessZone for good.
class OpeningMode {
 public:
  enum class Mode { Global, ProcessZone };
  explicit OpeningMode(bool always_zone) : always_zone_(always_zone), mode_(always_zone ? Mode::ProcessZone : Mode::Global) {}
  Mode mode() const { return mode_; }
  bool always_zone() const { return always_zone_; }

  void folded(std::string why) {
    mode_ = Mode::ProcessZone;
    fold_reason_ = std::move(why);
  }
  void back_to_global() { mode_ = always_zone_ ? Mode::ProcessZone : Mode::Global; }
  // Why the global step failed before the zone took over (for a later failure's diagnostic).
  const std::string& fold_reason() const { return fold_reason_; }

 private:
  bool always_zone_;
  Mode mode_;
  std::string fold_reason_;
};

}  // namespace uhpc::micro
