#pragma once
// A single material point driven by strain increments, for testing laws outside the solver (any law
// with the members of material_set.hpp). It carries what the solver would: the density ratio
// rho/rho0 (updated as rho <- rho exp(-tr d eps), the solver's volume update), the spacing h_I and dt.
//
// Mixed control: uniaxial_stress_step() prescribes the axial strain increment d eps_11 and solves for
// the lateral increment d eps_22 = d eps_33 = x that makes the lateral stress sigma_22 vanish (the
// law must be isotropic, so sigma_33 = sigma_22 and the shear stresses stay 0 on this path). sigma_22
// rises with x (lateral stretching adds tension through the bulk response), so the root is bracketed
// by expanding from the previous step's ratio x / d eps_11 and refined by the Illinois variant of
// regula falsi. Each trial updates a copy of the state; the accepted one is kept.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "materials/material_step.hpp"

namespace uhpc::macro {

template <class Law>
class PointDriver {
 public:
  using State = typename Law::State;

  PointDriver(const Law& law, double spacing_m) : law_(law) { step_.spacing_m = spacing_m; }

  // Full strain control: one step with the given (symmetric) increment over dt.
  void strain_step(const Mat3& increment, double dt_s) { state_ = trial(increment, dt_s); commit(increment); }

  // Hydrostatic control: moves the volumetric strain mu = rho/rho0 - 1 to `mu` in one step with the
  // consistent isotropic increment -(1/3) ln(rho_new / rho_old) I.
  void volumetric_step_to(double mu, double dt_s) {
    const double de = -std::log((1.0 + mu) / density_ratio_) / 3.0;
    strain_step(de * Mat3::Identity(), dt_s);
  }

  // Uniaxial stress along x: returns the lateral increment found. The iteration stops at |sigma_22| <=
  // tol_Pa or when the bracket is down to round-off. Throws std::runtime_error when the root cannot be
  // bracketed or the iteration does not end.
  double uniaxial_stress_step(double axial_increment, double dt_s, double tol_Pa = 1e-3) {
    const auto f = [&](double x) { return trial(lateral(axial_increment, x), dt_s).stress(1, 1); };
    double a = ratio_ * axial_increment, fa = f(a);
    if (fa == 0.0) return accept(axial_increment, a, dt_s);
    // Expand towards the root: sigma_22 too tensile -> less lateral stretch, and the other way round.
    double step = (fa > 0.0 ? -1.0 : 1.0) * std::max(std::abs(axial_increment), 1e-12);
    double b = a + step, fb = f(b);
    for (int i = 0; fa * fb > 0.0; ++i) {
      if (i == 200) throw std::runtime_error("PointDriver: lateral stress root not bracketed");
      a = b, fa = fb;
      step *= 2.0;
      b = a + step, fb = f(b);
    }
    int side = 0;
    for (int it = 0; it < 300; ++it) {
      const double c = (a * fb - b * fa) / (fb - fa);
      const double fc = f(c);
      // Done at the tolerance, or when the bracket has shrunk to round-off (the sign change then sits
      // between neighbouring doubles: the best answer there is).
      const double width = std::abs(b - a), scale = std::max(std::abs(a), std::abs(b));
      if (std::abs(fc) <= tol_Pa || width <= 8.0 * std::numeric_limits<double>::epsilon() * scale)
        return accept(axial_increment, c, dt_s);
      if (fc * fb > 0.0) {
        b = c, fb = fc;
        if (side == -1) fa *= 0.5;  // Illinois: halve the stale end's value
        side = -1;
      } else {
        a = c, fa = fc;
        if (side == 1) fb *= 0.5;
        side = 1;
      }
    }
    throw std::runtime_error("PointDriver: lateral stress iteration did not converge");
  }

  const State& state() const { return state_; }
  State& state() { return state_; }
  const Law& law() const { return law_; }
  double density_ratio() const { return density_ratio_; }
  const Mat3& total_strain() const { return strain_; }  // sum of the increments

 private:
  static Mat3 lateral(double axial, double x) {
    Mat3 de = Mat3::Zero();
    de(0, 0) = axial;
    de(1, 1) = de(2, 2) = x;
    return de;
  }

  State trial(const Mat3& de, double dt_s) const {
    State s = state_;
    MaterialStep step = step_;
    step.strain_increment = de;
    step.dt_s = dt_s;
    step.density_ratio = density_ratio_ * std::exp(-de.trace());
    law_.update(s, step);
    return s;
  }

  double accept(double axial, double x, double dt_s) {
    if (axial != 0.0) ratio_ = x / axial;
    const Mat3 de = lateral(axial, x);
    state_ = trial(de, dt_s);
    commit(de);
    return x;
  }

  void commit(const Mat3& de) {
    density_ratio_ *= std::exp(-de.trace());
    strain_ += de;
  }

  Law law_;
  State state_{};
  MaterialStep step_{};
  double density_ratio_ = 1.0;
  double ratio_ = -0.2;  // lateral / axial increment of the last uniaxial step (elastic guess)
  Mat3 strain_ = Mat3::Zero();
};

}  // namespace uhpc::macro
