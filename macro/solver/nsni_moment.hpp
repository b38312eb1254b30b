#pragma once
// The NSNI moment of a particle's integration cell in each direction, M_L = c V_L^(5/3) / 12: the second
// moment of a cube of volume V_L about its centre (h^5 / 12 for side h), times the coefficient c
// (SolverOptions::nsni_coefficient, 1 by default: Hillman and Chen's NSNI). One definition for the
// stabilization force, its work and the energy its gradients hold.
#include <cmath>

namespace uhpc::macro {

inline double nsni_moment(double volume, double coefficient) {
  return coefficient * std::cbrt(volume * volume * volume * volume * volume) / 12.0;
}

}  // namespace uhpc::macro
