#include "materials/afc_strength.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/LU>  // determinant

namespace uhpc::macro {

double effective_deviatoric_rate(const Mat3& strain_increment, double dt_s) {
  if (!(dt_s > 0.0)) return 0.0;
  const Mat3 e = deviator(strain_increment);
  return std::sqrt(2.0 / 3.0 * e.cwiseProduct(e).sum()) / dt_s;
}

double afc_rate_factor(double strain_rate_1_s, const AfcParams& p) {
  // A zero rate would give ln 0 = -inf; the smallest positive double keeps the raw law finite (and
  // the floor then decides).
  const double rate_n = std::max(strain_rate_1_s / p.reference_strain_rate_1_s, std::numeric_limits<double>::min());
  return std::max(1.0 + p.C3 * std::log(rate_n), p.options.rate_factor_floor);
}

namespace {
double cap(double s, const AfcParams& p) { return p.options.cap_strength_with_c5 ? std::min(s, p.C5_Pa) : s; }
}  // namespace

double afc_strength_compression(double P, double d_minus, double F, const AfcParams& p) {
  const double s = p.C1_Pa - (p.C2_Pa + (p.C1_Pa - p.C2_Pa) * d_minus) * std::exp(-p.An_1_Pa * P) + p.C4 * P;
  return std::max(F * cap(s, p), 0.0);
}

double afc_strength_tension(double P, double d_minus, double d_plus, double F, const AfcParams& p, double tensile_dif) {
  const double T = tensile_dif * p.Tmax_Pa * (1.0 - d_plus);
  if (!(T > 1e-12 * p.Tmax_Pa)) return 0.0;  // fully cracked: no strength in tension (the 0/0 guard)
  const double ratio = std::clamp((T + P) / T, 0.0, 1.0);
  return std::max(F * cap((p.C1_Pa - p.C2_Pa) * (1.0 - d_minus), p) * ratio, 0.0);
}

double afc_tensile_dif(double rate, const AfcParams& p) {
  if (p.options.tensile_rate == TensileRate::Off || !(rate > 0.0)) return 1.0;
  constexpr double kRate0 = 1e-6;  // 1/s, fib Model Code 2010
  const double r = rate / kRate0;
  const double dif = rate <= 10.0 ? std::pow(r, 0.018) : 0.0062 * std::cbrt(r);
  return std::max(dif, 1.0);
}

double lode_cos3theta(const Mat3& s) {
  const double q2 = 1.5 * s.cwiseProduct(s).sum();
  if (!(q2 > 0.0)) return 1.0;
  const double q = std::sqrt(q2);
  return std::clamp(13.5 * s.determinant() / (q2 * q), -1.0, 1.0);
}

double willam_warnke_factor(double cos3theta, double e) {
  if (e >= 1.0) return 1.0;
  // theta in [0, pi/3] from the extension meridian (theta = 0, r = e) to the compressive one (r = 1).
  const double c = std::cos(std::acos(std::clamp(cos3theta, -1.0, 1.0)) / 3.0);
  const double a = 1.0 - e * e;
  const double root = std::sqrt(std::max(4.0 * a * c * c + 5.0 * e * e - 4.0 * e, 0.0));
  return (2.0 * a * c + (2.0 * e - 1.0) * root) / (4.0 * a * c * c + (1.0 - 2.0 * e) * (1.0 - 2.0 * e));
}

double lode_psi(double P, double d_minus, double F, const AfcParams& p) {
  const double Pc = std::max(P, 0.0);
  const double b = p.C2_Pa + (p.C1_Pa - p.C2_Pa) * d_minus;
  const double bracket = p.C1_Pa - b * std::exp(-p.An_1_Pa * Pc) + p.C4 * Pc;
  const bool capped = p.options.cap_strength_with_c5 && bracket > p.C5_Pa;
  const double slope = capped ? 0.0 : F * (b * p.An_1_Pa * std::exp(-p.An_1_Pa * Pc) + p.C4);
  return std::clamp(3.0 / (3.0 + slope), 0.5, 1.0);
}

double afc_uniaxial_tensile_strength(const AfcParams& p) {
  const double a = cap(p.C1_Pa - p.C2_Pa, p);
  return a / (1.0 + a / (3.0 * p.Tmax_Pa));
}

double afc_strength(double P, double d_minus, double d_plus, double F, const AfcParams& p) {
  return P >= 0.0 ? afc_strength_compression(P, d_minus, F, p) : afc_strength_tension(P, d_minus, d_plus, F, p);
}

}  // namespace uhpc::macro
