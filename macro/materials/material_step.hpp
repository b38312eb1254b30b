#pragma once
// What a material law sees of one particle in one explicit step. The solver computes the rate of
// deformation D and the spin W from the RK velocity gradient, rotates the stress with the Jaumann
// rate (objectivity is kinematics, done once for every law), and hands the law the strain increment
// D dt in that co-rotated frame. Laws are then small-strain incremental updates, testable at a point.
#include <cmath>

#include <Eigen/Core>

namespace uhpc::macro {

using Mat3 = Eigen::Matrix3d;

struct MaterialStep {
  Mat3 strain_increment = Mat3::Zero();  // D dt, symmetric
  double dt_s = 0.0;
  double density_ratio = 1.0;            // rho / rho0 (> 0)
  double spacing_m = 0.0;                // the particle's nodal spacing h_I (length-scale-aware laws)
};

// Isotropic moduli a law reports for the solver (the NSNI stabilization stress gradient, see
// macro/README.md): the tangent (or a bound of it) at the particle's state.
struct Moduli {
  double bulk_Pa = 0.0;
  double shear_Pa = 0.0;
  // What the law's last return mapping did to the stress, so that the NSNI stress gradient (the
  // stress variation across the particle) is returned with it (solver/nsni_gradient_return.hpp): the
  // radial-return factor S / q_trial of the deviator (1 for an elastic step, 0 when no deviatoric
  // stress is admissible), the fraction of a change along the current deviator that the strength
  // follows (hardening: H / (3G + H); 0 for a strength that does not grow with plastic flow), and
  // whether the pressure sits on a fixed limit (tensile cutoff).
  double deviatoric_return = 1.0;
  double along_deviator_return = 0.0;
  bool pressure_fixed = false;
};

inline double pressure_of(const Mat3& stress) { return -stress.trace() / 3.0; }  // > 0 in compression

inline Mat3 deviator(const Mat3& m) { return m - (m.trace() / 3.0) * Mat3::Identity(); }

// von Mises equivalent stress q = sqrt(3 J2) = sqrt(3/2 s:s).
inline double von_mises(const Mat3& stress) {
  const Mat3 s = deviator(stress);
  return std::sqrt(1.5 * s.cwiseProduct(s).sum());
}

}  // namespace uhpc::macro
