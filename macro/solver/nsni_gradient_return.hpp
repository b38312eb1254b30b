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
#include <algorithm>
#include <cmath>

#include "materials/material_step.hpp"

namespace uhpc::macro {

// The return of one particle's step, set up once from the law's stress after its return mapping and
// Law::moduli of that state, then applied to each direction's trial gradient (already advanced
// elastically, in the frame of that stress).
class StressGradientReturn {
 public:
  StressGradientReturn(const Mat3& stress, const Moduli& mod)
      : mod_(mod), active_(mod.deviatoric_return < 1.0 || mod.pressure_fixed) {
    if (mod.deviatoric_return >= 1.0) return;
    s_ = deviator(stress);
    const double norm2 = s_.cwiseProduct(s_).sum();
    if (norm2 > 0.0) s_ /= std::sqrt(norm2);  // unit deviator n (zero when there is none)
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
  Moduli mod_;
  bool active_;
  Mat3 s_ = Mat3::Zero();
};

// One direction's gradient (tests and single uses).
inline void return_stress_gradient(Mat3& g, const Mat3& stress, const Moduli& mod) {
  StressGradientReturn(stress, mod).apply(g);
}

}  // namespace uhpc::macro
