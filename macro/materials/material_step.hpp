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
  // The factor (1 - d+) by which the law's split hands the solver the positive principal part of its
  // effective stress (eq. 21; 1 when the law does not split): the gradient, kept as an effective
  // gradient, is mapped through the same split (StressGradientReturn::nominal).
  double tension_factor = 1.0;
};

// What a law has dissipated so far, per unit reference volume (J/m^3), by mechanism. The rest of the
// dissipation (what the stress power put in minus what stays stored, EnergyLedger) is what the law
// released without booking it: damage.
struct DissipationParts {
  double plastic = 0.0;   // deviatoric plastic work
  double crushing = 0.0;  // work of pore collapse on the hydrostat (volumetric plastic work)
  double opening = 0.0;   // work of the tensile cutoff over volume opened past it and kept (AFC option)
};

// Half the complementary energy product 1/2 a : C^-1 : b of an isotropic compliance (K, G): with
// a = b the elastic energy per unit volume a stress holds; with a the stress handed to the solver and b
// the law's effective stress, the free energy of eq. 21, 1/2 sigma : eps_e.
inline double half_compliance_product(const Mat3& a, const Mat3& b, double K, double G) {
  const double ta = a.trace(), tb = b.trace();
  const double dev = a.cwiseProduct(b).sum() - ta * tb / 3.0;  // s_a : s_b
  return 0.5 * (ta * tb / (9.0 * K) + dev / (2.0 * G));
}

inline double pressure_of(const Mat3& stress) { return -stress.trace() / 3.0; }  // > 0 in compression

inline Mat3 deviator(const Mat3& m) { return m - (m.trace() / 3.0) * Mat3::Identity(); }

// von Mises equivalent stress q = sqrt(3 J2) = sqrt(3/2 s:s).
inline double von_mises(const Mat3& stress) {
  const Mat3 s = deviator(stress);
  return std::sqrt(1.5 * s.cwiseProduct(s).sum());
}

}  // namespace uhpc::macro
