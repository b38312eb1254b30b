#pragma once
// The cohesive law of the matrix cracks (docs/physics.md section 2, Table 2), in the crack's local frame
// (n: normal opening w_n, s: sliding w_t), plain doubles with the consistent tangent. One
// implementation: the assembly, the energy sums and the unit tests all call these functions.
//
// Envelope T(kappa) of the effective opening kappa (history maximum):
//   0 <= kappa <= w0       T = K0 kappa                      (stiff activation branch, K0 = f_t / w0)
//   w0 < kappa < w_c       T = f_t (w_c - kappa)/(w_c - w0)  (linear softening, Table 2)
//   kappa >= w_c           T = 0                             (traction free)
// w_c = 2 G_f / f_t. Segments are only inserted (cracks activated) once the stress ahead of a tip
// reaches f_t (crack_growth.hpp), so the law is extrinsic in spirit: the short branch of slope K0 only
// regularises the infinite secant stiffness at w = 0 (the secant unloading below needs a finite one).
// [choice] The softening line runs from (w0, f_t) to (w_c, 0) rather than from (0, f_t), so the area
// under the envelope is exactly G_f whatever w0, and the peak traction is exactly f_t; with the
// default w0 = 1e-3 w_c the difference to t = f_t (1 - w/w_c) is at most 0.1 % of f_t.
//
// Unloading and reloading are secant (toward the origin): t = S(kappa) [[u]], S = T(kappa)/kappa, so
// the recoverable energy of a point is 1/2 t . [[u]] (eq. 20) and the dissipated energy is
// D(kappa) = int_0^kappa T - 1/2 kappa T(kappa), which reaches G_f at kappa = w_c.
// Effective opening: Mode I (default): kappa follows <w_n>_+, and the sliding stiffness is the same
// secant S (shear degrades with the normal damage, which keeps sliding of a fully open crack free and
// of a closed one resisted). [choice] MixedMode: kappa follows sqrt(<w_n>_+^2 + w_t^2).
// No interpenetration: for w_n < 0 the normal traction is the penalty K_p w_n (elastic, recoverable).
// [choice] Residual stiffness: an elastic spring K_r = residual_stiffness_ratio x K0 in parallel with
// the law, in both directions (t += K_r [[u]], recoverable; it dissipates nothing). At the default 1e-8
// it carries 1e-5 f_t at w = w_c. Without it a fragment cut loose by fully opened cracks, its faces in
// frictionless contact, has no stiffness in sliding: Newton moved it by residual noise over a
// tangent-only floor (a 4.5 mm cell slid one by 2e4 w_c, 60 mm, over 30 states).
#include <algorithm>
#include <array>
#include <cmath>

namespace uhpc::micro {

enum class CohesiveMode { ModeI, MixedMode };

struct CohesiveLaw {
  double tensile_strength_Pa = 0.0;   // f_t
  double fracture_energy_J_m2 = 0.0;  // G_f
  double activation_ratio = 1e-3;     // [choice] w0 / w_c of the stiff activation branch
  double contact_penalty_ratio = 1.0; // [choice] K_p / K0 of the no-interpenetration penalty
  double residual_stiffness_ratio = 1e-8;  // [choice] K_r / K0 of the parallel residual spring
  CohesiveMode mode = CohesiveMode::ModeI;

  double critical_opening() const { return 2.0 * fracture_energy_J_m2 / tensile_strength_Pa; }  // w_c
  double activation_opening() const { return activation_ratio * critical_opening(); }            // w0
  double initial_stiffness() const { return tensile_strength_Pa / activation_opening(); }        // K0
  double residual_stiffness() const { return residual_stiffness_ratio * initial_stiffness(); }   // K_r

  // Envelope T(kappa) and its slope.
  double envelope(double kappa) const {
    const double wc = critical_opening(), w0 = activation_opening();
    if (kappa <= w0) return initial_stiffness() * std::max(kappa, 0.0);
    if (kappa >= wc) return 0.0;
    return tensile_strength_Pa * (wc - kappa) / (wc - w0);
  }
  double envelope_slope(double kappa) const {
    const double wc = critical_opening(), w0 = activation_opening();
    if (kappa <= w0) return initial_stiffness();
    if (kappa >= wc) return 0.0;
    return -tensile_strength_Pa / (wc - w0);
  }
  // D(kappa) = int_0^kappa T - 1/2 kappa T(kappa): energy dissipated per unit crack length.
  double dissipated(double kappa) const {
    const double wc = critical_opening(), w0 = activation_opening(), ft = tensile_strength_Pa;
    if (kappa <= w0) return 0.0;
    const double k = std::min(kappa, wc);
    const double area = 0.5 * ft * w0 + 0.5 * (ft + envelope(k)) * (k - w0);
    return area - 0.5 * k * envelope(k);
  }
};

struct CohesiveResponse {
  std::array<double, 2> t{0.0, 0.0};                 // (t_n, t_t)
  std::array<double, 4> tangent{0.0, 0.0, 0.0, 0.0};  // d t_a / d w_b at 2a + b
  double kappa = 0.0;                                 // updated history (trial)
};

// Traction and consistent tangent at the opening (w_n, w_t) with committed history kappa_old
// (>= w0: a new point starts at w0, the end of the activation branch it is inserted at).
inline CohesiveResponse cohesive_response(const CohesiveLaw& law, double w_n, double w_t, double kappa_old) {
  CohesiveResponse r;
  const double wp = std::max(w_n, 0.0);
  const double weff = law.mode == CohesiveMode::ModeI ? wp : std::sqrt(wp * wp + w_t * w_t);
  const bool loading = weff > kappa_old;
  const double kappa = loading ? weff : kappa_old;
  r.kappa = kappa;
  const double T = law.envelope(kappa);
  const double S = kappa > 0.0 ? T / kappa : law.initial_stiffness();
  const double Kp = law.contact_penalty_ratio * law.initial_stiffness();
  r.t[0] = w_n >= 0.0 ? S * w_n : Kp * w_n;
  r.t[1] = S * w_t;
  r.tangent = {w_n >= 0.0 ? S : Kp, 0.0, 0.0, S};
  if (loading && kappa > 0.0) {
    // dS/dkappa (zero on the activation branch, where S = K0), times d kappa / d w.
    const double dS = (law.envelope_slope(kappa) * kappa - T) / (kappa * kappa);
    std::array<double, 2> dk{1.0, 0.0};
    if (law.mode == CohesiveMode::MixedMode) dk = {wp / weff, w_t / weff};
    const std::array<double, 2> w{w_n >= 0.0 ? w_n : 0.0, w_t};
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) r.tangent[2 * a + b] += w[a] * dS * dk[b];
  }
  const double Kr = law.residual_stiffness();
  r.t[0] += Kr * w_n;
  r.t[1] += Kr * w_t;
  r.tangent[0] += Kr;
  r.tangent[3] += Kr;
  return r;
}

}  // namespace uhpc::micro
