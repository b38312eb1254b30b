#pragma once
// The NSNI stabilization stress gradient returned with the stress (macro/README.md, "NSNI with
// inelastic laws").
//
// NSNI carries, per particle and direction d, the stress gradient sigma_,d: the variation of the stress
// across the particle's volume. Advanced with the elastic moduli alone, it never yields: a particle whose
// stress sits on the strength surface, or a failed particle with no strength at all, keeps an elastic
// gradient stress that stores energy and resists like intact material. In a penetration this is a
// spurious elastic resistance (found on the paper's shot: the sphere stopped within 8 mm and bounced
// back). So the gradient follows the law's return mapping: linearising the radial return
// s = S s_tr / |s_tr| about the particle's state gives ds = (S / q_tr) (I - n (x) n) ds_tr with
// n = s / |s|, for a strength S that does not change with the deviator; with linear hardening the
// component along n follows the yield stress, by H / (3G + H). The gradient's part orthogonal to the
// current deviator is therefore scaled by the return factor S / q_tr and its part along it by
// Moduli::along_deviator_return; a pressure held at a fixed limit (the tensile cutoff) has no gradient.
// An elastic step leaves the gradient untouched.
// A law that splits its stress (eq. 21: sigma = <sigma_e>- + t <sigma_e>+, t = 1 - d+) keeps the
// gradient of its effective stress sigma_e (returned as above) and hands the forces its first-order
// image through the split, nominal(g): in the principal frame of sigma_e (eigenvalues l_i) the
// component g_ij is multiplied by (f(l_i) - f(l_j)) / (l_i - l_j), f(l) = t l for l > 0 and l
// otherwise (f'(l_i) on the diagonal; Daleckii-Krein). At d+ = 1 nothing tensile is left of it either.
#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

#include "materials/material_step.hpp"

namespace uhpc::macro {

// The return of one particle's step, set up once from the law's stress after its return mapping and
// Law::moduli of that state, then applied to each direction's trial gradient (already advanced
// elastically, in the frame of that stress).
class StressGradientReturn {
 public:
  // `stress`: the law's effective stress after its update (Law::effective_stress).
  StressGradientReturn(const Mat3& stress, const Moduli& mod)
      : mod_(mod), active_(mod.deviatoric_return < 1.0 || mod.pressure_fixed) {
    if (mod.tension_factor < 1.0) set_split(stress);
    if (mod.deviatoric_return >= 1.0) return;
    s_ = deviator(stress);
    const double norm2 = s_.cwiseProduct(s_).sum();
    if (norm2 > 0.0) s_ /= std::sqrt(norm2);  // unit deviator n (zero when there is none)
  }
  // The gradient the forces use for an effective gradient g: g itself unless the law splits.
  Mat3 nominal(const Mat3& g) const {
    if (!split_) return g;
    Mat3 h = q_.transpose() * g * q_;
    h = h.cwiseProduct(factor_);
    return q_ * h * q_.transpose();
  }
  bool active() const { return active_; }
  void apply(Mat3& g) const {
    if (!active_) return;
    const double p = g.trace() / 3.0;
    Mat3 dev = g - p * Mat3::Identity();
    if (mod_.deviatoric_return < 1.0) {
      const Mat3 along = s_.cwiseProduct(dev).sum() * s_;
      dev = std::max(mod_.deviatoric_return, 0.0) * (dev - along) + mod_.along_deviator_return * along;
    }
    g = dev + (mod_.pressure_fixed ? 0.0 : p) * Mat3::Identity();
  }

 private:
  void set_split(const Mat3& stress) {
    Eigen::SelfAdjointEigenSolver<Mat3> es;
    es.computeDirect(stress);
    const Eigen::Vector3d l = es.eigenvalues();
    const double t = std::clamp(mod_.tension_factor, 0.0, 1.0);
    if (l[2] <= 0.0) return;  // nothing tensile: the split is the identity here
    split_ = true;
    q_ = es.eigenvectors();
    const auto f = [t](double x) { return x > 0.0 ? t * x : x; };
    const auto df = [t](double x) { return x > 0.0 ? t : 1.0; };
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const double gap = l[i] - l[j];
        const bool close = std::fabs(gap) <= 1e-12 * (std::fabs(l[i]) + std::fabs(l[j]));
        factor_(i, j) = i == j ? df(l[i]) : close ? 0.5 * (df(l[i]) + df(l[j])) : (f(l[i]) - f(l[j])) / gap;
      }
  }

  Moduli mod_;
  bool active_;
  bool split_ = false;
  Mat3 s_ = Mat3::Zero();
  Mat3 q_ = Mat3::Identity();       // principal directions of the effective stress (split only)
  Mat3 factor_ = Mat3::Ones();      // the Daleckii-Krein factors (split only)
};

// One direction's gradient (tests and single uses).
inline void return_stress_gradient(Mat3& g, const Mat3& stress, const Moduli& mod) {
  StressGradientReturn(stress, mod).apply(g);
}

}  // namespace uhpc::macro
