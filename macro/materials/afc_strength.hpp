#pragma once
// The AFC deviatoric strength S, compared with q = sqrt(3 J2) (docs/physics.md section 4):
//   P >= 0:  S = F (C1 - (C2 + (C1 - C2) d-) exp(-An P) + C4 P)                     (eq. 33)
//   P <  0:  S = F (C1 - C2) (1 - d-) (T + P) / T,   T = Tmax (1 - d+)                (eq. 35)
//   F = max(1 + C3 ln(edot / edot0), rate_factor_floor)                              (eq. 34)
// The two branches agree at P = 0. When d+ -> 1, T -> 0 and (T + P) / T is 0/0: the tensile strength
// is taken as 0 once T is below 1e-12 Tmax, and (T + P) / T is clipped to [0, 1] (P >= -T holds by
// the hydrostat's cutoff; the clip only absorbs round-off). With AfcOptions::cap_strength_with_c5 the
// bracket (the rate-free strength) is capped at C5 before F multiplies it.
#include "materials/afc_params.hpp"
#include "materials/material_step.hpp"

namespace uhpc::macro {

// Effective deviatoric strain rate sqrt(2/3 e:e) / dt, e = dev(strain increment); 0 when dt <= 0.
double effective_deviatoric_rate(const Mat3& strain_increment, double dt_s);

// F of eq. 34 with the floor of AfcOptions::rate_factor_floor.
double afc_rate_factor(double strain_rate_1_s, const AfcParams& p);

// The two branches. Never negative, never NaN for d-, d+ in [0, 1].
double afc_strength_compression(double pressure_Pa, double d_minus, double rate_factor, const AfcParams& p);  // eq. 33
// eq. 35 with T = tensile_dif Tmax (1 - d+) (tensile_dif: AfcOptions::tensile_rate, 1 without it)
double afc_strength_tension(double pressure_Pa, double d_minus, double d_plus, double rate_factor, const AfcParams& p,
                            double tensile_dif = 1.0);
// The tensile dynamic increase factor of AfcOptions::tensile_rate at the largest principal strain rate
// (1 with TensileRate::Off).
double afc_tensile_dif(double principal_strain_rate_1_s, const AfcParams& p);
// S at pressure P (> 0 in compression): eq. 33 for P >= 0, eq. 35 for P < 0. The law chooses the branch
// by the sign of the hydrostat's pressure before the cutoff instead (AfcMaterial::update): with d+ = 1
// the cutoff is 0, an expanded point sits at P = 0 and must still get eq. 35's limit, S = 0.
double afc_strength(double pressure_Pa, double d_minus, double d_plus, double rate_factor, const AfcParams& p);

// The third-invariant factor of LodeDependence::WillamWarnke (afc_params.hpp): the strength on the
// deviator s is S(P) r(theta, psi).
//   cos(3 theta) = 27 J3 / (2 q^3) of the deviator (1: extension, one principal value above the other
//   two; -1: compression, as in a triaxial compression test); 1 for a zero deviator.
double lode_cos3theta(const Mat3& deviator);
//   Willam-Warnke's ellipse: r = 1 at cos 3theta = -1, r = psi at cos 3theta = 1, psi in [0.5, 1].
double willam_warnke_factor(double cos3theta, double psi);
//   psi(P) = 3 / (3 + dS/dP), dS/dP the slope of eq. 33's meridian (with the rate factor and the C5 cap)
//   at max(P, 0), clipped to [0.5, 1].
double lode_psi(double pressure_Pa, double d_minus, double rate_factor, const AfcParams& p);

// f't: the uniaxial tensile strength of the intact, quasi-static surface (eq. 35 with d- = d+ = 0 and
// F = 1 on the path P = -sigma / 3, q = sigma): sigma = a / (1 + a / (3 Tmax)), a = S(0).
double afc_uniaxial_tensile_strength(const AfcParams& p);

}  // namespace uhpc::macro
