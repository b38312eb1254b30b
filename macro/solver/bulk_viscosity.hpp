#pragma once
// Artificial bulk viscosity (von Neumann-Richtmyer quadratic + Landshoff linear term, the form and
// defaults of LS-DYNA's *CONTROL_BULK_VISCOSITY), acting in compression only:
//   q = rho h (c_quadratic h tr(D)^2 - c_linear c tr(D))   if tr(D) < 0,   q = 0 otherwise,
// added to the pressure in the internal force (sigma - q I). It spreads a shock over a few spacings
// instead of letting it ring; the energy it takes, -q tr(D) V dt >= 0, is booked as dissipated.
// The stable step shrinks accordingly: dt = h / (Q + sqrt(Q^2 + c^2)), Q = c_linear c + c_quadratic h |tr D|.
#include <cmath>

namespace uhpc::macro {

// The length h of a particle in its critical step and its bulk viscosity: the side of its current cell,
// cbrt(V), but never more than its spacing h_I. The RK gradients scale with the support a_I =
// support_factor h_I, which stays fixed, so a particle that expands (an ejected fragment, up to 1e3 V0)
// is as stiff against its neighbours as at h_I: its cbrt(V) would overstate the stable step and the
// viscous damping length (found: shots blowing up at a steady dt with V/V0 ~ 10 ejecta in front).
inline double stable_length(double volume, double spacing) { return std::fmin(std::cbrt(volume), spacing); }

struct BulkViscosity {
  double c_linear = 0.06;
  double c_quadratic = 1.5;
  // Whether it also acts on points the law calls stress-free (fully failed, open AFC points): true as
  // LS-DYNA does; false leaves them undamped until they close, as they carry no wave to spread (the
  // option and the finding behind it: macro/README.md, "the viscosity of stress-free ejecta").
  bool damp_stress_free_points = true;

  double pressure(double density, double h, double c, double trace_d) const {
    if (!(trace_d < 0.0)) return 0.0;
    return density * h * (c_quadratic * h * trace_d * trace_d - c_linear * c * trace_d);
  }
  // The critical step of a particle of size h and wave speed c under this viscosity.
  double critical_step(double h, double c, double trace_d) const {
    const double Q = trace_d < 0.0 ? c_linear * c + c_quadratic * h * std::fabs(trace_d) : 0.0;
    return h / (Q + std::sqrt(Q * Q + c * c));
  }
};

}  // namespace uhpc::macro
