#pragma once
// Scaled damage evolution law (SDEL), docs/physics.md section 3 (paper eq. 24-26 and 37):
//
//   d+(lambda, e) = 1 / (1 + nu * exp(-lambda * chi * (e - e_i)))
//   e_i           = A / sqrt(1 + a * lambda)
//   lambda        = l_mic / l_mac
//
// One templated implementation serves the Ceres fit (T = ceres::Jet, derivatives by automatic
// differentiation) and the 3D code (T = double), so the law that is fitted is exactly the law that is
// run. This header does not include Ceres: a Jet is recognised only through its scalar member `a`.
//
// Preconditions (the handoff reader enforces them): a, A, nu, chi > 0 and lambda > 0. The law is then
// finite for every finite strain, including compressive (negative) ones, for double and for Jet.
//
// At e = 0 the law does NOT give zero: d+(lambda, 0) = 1 / (1 + nu exp(lambda chi e_i)) > 0. With the
// paper's Table 4 constants this is about 2e-5 at l_mic = 3 mm, small but not zero. It is returned as
// is (no silent clamp); sdel_damage_at_zero_strain() reports it and sdel_damage_zero_anchored() is the
// documented alternative that starts exactly at 0. Callers pass the history maximum of the equivalent
// tensile strain, so d+ never decreases.
#include <cmath>
#include <stdexcept>
#include <string>

namespace uhpc {

// The four SDEL constants; all dimensionless (A is a strain). The paper's Table 4 calls chi "kappa".
template <typename T>
struct SdelConstants {
  T a;    // size dependence of the initiation strain
  T A;    // initiation strain at lambda = 0
  T nu;   // offset of the sigmoid (d+ = 1/(1+nu) at e = e_i)
  T chi;  // steepness; the effective steepness is lambda * chi
};

namespace sdel_detail {

// The scalar (value) part of a number, to branch on without breaking automatic differentiation.
inline double scalar_part(double x) { return x; }
inline double scalar_part(float x) { return x; }
// ceres::Jet<T, N> keeps its value in member `a` (which is itself a Jet for nested Jets).
template <typename J>
double scalar_part(const J& x) {
  return scalar_part(x.a);
}

// 1 / (1 + exp(s)) without overflow: exp is only ever taken of a non-positive argument.
template <typename T>
T logistic_of_negative(const T& s) {
  using std::exp;
  if (scalar_part(s) <= 0.0) return T(1.0) / (T(1.0) + exp(s));
  const T t = exp(-s);
  return t / (T(1.0) + t);
}

}  // namespace sdel_detail

// lambda = l_mic / l_mac (eq. 25). Both lengths in the same unit, both > 0.
inline double sdel_lambda(double l_mic, double l_mac) {
  if (!(l_mic > 0.0) || !(l_mac > 0.0) || !std::isfinite(l_mic) || !std::isfinite(l_mac)) {
    throw std::invalid_argument("sdel_lambda: lengths must be finite and > 0, got l_mic = " +
                                std::to_string(l_mic) + ", l_mac = " + std::to_string(l_mac));
  }
  return l_mic / l_mac;
}

// Damage initiation strain e_i = A / sqrt(1 + a lambda) (eq. 26).
template <typename T>
T sdel_initiation_strain(const T& lambda, const SdelConstants<T>& c) {
  using std::sqrt;
  return c.A / sqrt(T(1.0) + c.a * lambda);
}

// Tensile damage d+ (eq. 24/37) at `strain` (the history maximum of the equivalent tensile strain).
// Computed as d = 1 / (1 + exp(s)), s = ln(nu) - lambda chi (e - e_i), through a logistic that never
// overflows: at e = -1 or e = 1 the result is exactly 0 or 1 with finite derivatives.
template <typename T>
T sdel_damage(const T& lambda, const T& strain, const SdelConstants<T>& c) {
  using std::log;
  const T s = log(c.nu) - lambda * c.chi * (strain - sdel_initiation_strain(lambda, c));
  return sdel_detail::logistic_of_negative(s);
}

// The residual damage the law gives at zero strain, 1 / (1 + nu exp(lambda chi e_i)) (> 0).
template <typename T>
T sdel_damage_at_zero_strain(const T& lambda, const SdelConstants<T>& c) {
  return sdel_damage(lambda, T(0.0), c);
}

// Optional variant, not the paper's law: the SDEL shifted and rescaled so that it is exactly 0 at
// e = 0 and still tends to 1, (d(e) - d(0)) / (1 - d(0)). Negative for e < 0, so pass a non-negative
// history strain. Offered for callers that need d+(0) = 0 exactly; the default everywhere is
// sdel_damage().
template <typename T>
T sdel_damage_zero_anchored(const T& lambda, const T& strain, const SdelConstants<T>& c) {
  const T d0 = sdel_damage_at_zero_strain(lambda, c);
  return (sdel_damage(lambda, strain, c) - d0) / (T(1.0) - d0);
}

// Inverse of sdel_damage in the strain: the strain at which d+ reaches `damage` (0 < damage < 1),
//   e = e_i + (ln nu + ln(d / (1 - d))) / (lambda chi).
// With the Table 4 constants, damage 0.5 gives 3.58e-4 at l_mic = 3.0 mm and 2.71e-4 at 6.5 mm.
inline double sdel_strain_at_damage(double lambda, double damage, const SdelConstants<double>& c) {
  if (!(damage > 0.0 && damage < 1.0)) {
    throw std::invalid_argument("sdel_strain_at_damage: damage must be in (0, 1), got " +
                                std::to_string(damage));
  }
  if (!(lambda > 0.0)) {
    throw std::invalid_argument("sdel_strain_at_damage: lambda must be > 0, got " + std::to_string(lambda));
  }
  const double logit = std::log(damage) - std::log1p(-damage);  // ln(d / (1 - d)), accurate near 0 and 1
  return sdel_initiation_strain(lambda, c) + (std::log(c.nu) + logit) / (lambda * c.chi);
}

}  // namespace uhpc
