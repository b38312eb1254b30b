#pragma once
// The principal-stress (Rankine) limit of AfcOptions::principal_stress_limit as a plastic return of the
// deviator at fixed pressure: sigma_1 = s_1 - P <= T_R becomes s_1 <= c = T_R + P on the deviator s.
// The admissible deviators {tr s = 0, s_i <= c} form a convex set that holds s = 0 for c >= 0; the
// return is the closest point of that set in the Euclidean norm of deviators (the elastic energy norm
// 1/(4G) |ds|^2 at fixed pressure), so its dissipation s_new : (s - s_new) / (2G) is >= 0 and |s_new| <= |s|.
// In the principal frame (s_1 >= s_2 >= s_3):
//   one active value: s_1 = c, s_2 and s_3 each raised by (s_1 - c) / 2 (the move along dev(e_1 e_1));
//   if that lifts s_2 above c, the corner: s_1 = s_2 = c, s_3 = -2 c.
#include <Eigen/Eigenvalues>

#include "materials/material_step.hpp"

namespace uhpc::macro {

// The returned deviator; `s` itself when it is admissible. Precondition: tr s = 0, c >= 0.
inline Mat3 limit_principal_deviator(const Mat3& s, double c) {
  // The iterative solver, not the closed form: its eigenvectors stay orthonormal to round-off when two
  // principal values nearly coincide (the closed form's lose 1e-9 there, and the corner needs them).
  Eigen::SelfAdjointEigenSolver<Mat3> es(s);
  const Eigen::Vector3d l = es.eigenvalues();  // ascending: l[2] is s_1
  if (l[2] <= c) return s;
  Eigen::Vector3d r = l;
  const double lift = 0.5 * (l[2] - c);
  r[2] = c;
  r[1] = l[1] + lift;
  r[0] = l[0] + lift;
  if (r[1] > c) r = Eigen::Vector3d(-2.0 * c, c, c);
  const Mat3& Q = es.eigenvectors();
  return Q * r.asDiagonal() * Q.transpose();
}

}  // namespace uhpc::macro
