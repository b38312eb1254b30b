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

#include "materials/material_step.hpp"

namespace uhpc::macro {

// g: the trial stress gradient of one direction (already advanced elastically), in the frame of
// `stress`, the law's stress after its return mapping; `mod` from Law::moduli of that state.
inline void return_stress_gradient(Mat3& g, const Mat3& stress, const Moduli& mod) {
  if (mod.deviatoric_return >= 1.0 && !mod.pressure_fixed) return;
  const double p = g.trace() / 3.0;
  Mat3 dev = g - p * Mat3::Identity();
  if (mod.deviatoric_return < 1.0) {
    const Mat3 s = deviator(stress);
    const double norm2 = s.cwiseProduct(s).sum();
    const Mat3 along = norm2 > 0.0 ? Mat3((s.cwiseProduct(dev).sum() / norm2) * s) : Mat3::Zero();
    dev = std::max(mod.deviatoric_return, 0.0) * (dev - along) + mod.along_deviator_return * along;
  }
  g = dev + (mod.pressure_fixed ? 0.0 : p) * Mat3::Identity();
}

}  // namespace uhpc::macro
