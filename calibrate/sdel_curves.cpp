#include "sdel_curves.hpp"

#include <cmath>
#include <stdexcept>

namespace uhpc {

namespace {

double stress(const SdelConstants<double>& c, double lambda, double E, double e) {
  return (1.0 - sdel_damage(lambda, e, c)) * E * e;
}

// Golden-section search for the maximum of a unimodal function on [a, b].
template <class F>
double argmax_golden(F&& f, double a, double b) {
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double x1 = b - g * (b - a), x2 = a + g * (b - a), f1 = f(x1), f2 = f(x2);
  for (int it = 0; it < 200 && b - a > 1e-15 * std::abs(b); ++it) {
    if (f1 < f2) {
      a = x1, x1 = x2, f1 = f2, x2 = a + g * (b - a), f2 = f(x2);
    } else {
      b = x2, x2 = x1, f2 = f1, x1 = b - g * (b - a), f1 = f(x1);
    }
  }
  return 0.5 * (a + b);
}

}  // namespace

double sdel_dissipated_energy(const SdelConstants<double>& c, double lambda, double E) {
  const double e_end = sdel_strain_at_damage(lambda, 1.0 - 1e-15, c);
  const int n = 20000;  // even: Simpson's rule
  const double h = e_end / n;
  double sum = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    sum += w * stress(c, lambda, E, i * h);
  }
  return sum * h / 3.0;
}

double sdel_dissipated_energy_closed_form(const SdelConstants<double>& c, double lambda, double E) {
  const double k = lambda * c.chi;
  const double x = k * sdel_strain_at_damage(lambda, 0.5, c);
  if (!(x > 0.0)) throw std::invalid_argument("closed form needs the half-damage strain to be positive");
  // Li2(-y) = sum (-y)^n / n^2, y = exp(-x) < 1.
  const double y = std::exp(-x);
  double li2 = 0.0, term = 1.0;
  for (int j = 1; j < 200; ++j) {
    term *= -y;
    li2 += term / (static_cast<double>(j) * j);
    if (std::abs(term) < 1e-18) break;
  }
  const double pi = std::acos(-1.0);
  return E / (k * k) * (0.5 * x * x + pi * pi / 6.0 + li2);
}

SdelCurve sdel_curve(const SdelConstants<double>& c, double l_mac_m, double length_m, double strain_max, int points,
                     double E) {
  if (!(strain_max > 0.0) || points < 2 || !(E > 0.0))
    throw std::invalid_argument("sdel_curve: strain_max and E must be > 0 and points >= 2");
  const double lambda = sdel_lambda(length_m, l_mac_m);
  SdelCurve curve;
  curve.strain.resize(points);
  curve.damage.resize(points);
  curve.stress_Pa.resize(points);
  for (int i = 0; i < points; ++i) {
    const double e = strain_max * i / (points - 1);
    curve.strain[i] = e;
    curve.damage[i] = sdel_damage(lambda, e, c);
    curve.stress_Pa[i] = (1.0 - curve.damage[i]) * E * e;
  }

  SdelLengthSummary& s = curve.summary;
  s.length_m = length_m;
  s.lambda = lambda;
  s.initiation_strain = sdel_initiation_strain(lambda, c);
  s.damage_at_zero_strain = sdel_damage_at_zero_strain(lambda, c);
  s.strain_at_damage_10 = sdel_strain_at_damage(lambda, 0.1, c);
  s.strain_at_damage_50 = sdel_strain_at_damage(lambda, 0.5, c);
  s.strain_at_damage_90 = sdel_strain_at_damage(lambda, 0.9, c);
  // The peak lies before d+ = 0.9 (past it the stress only falls); search there, independent of the
  // output grid.
  auto f = [&](double e) { return stress(c, lambda, E, e); };
  s.strain_at_peak = argmax_golden(f, 0.0, s.strain_at_damage_90);
  s.peak_stress_Pa = f(s.strain_at_peak);
  s.dissipated_energy_J_m3 = sdel_dissipated_energy(c, lambda, E);
  s.crack_band_energy_J_m2 = s.dissipated_energy_J_m3 * length_m;
  return curve;
}

}  // namespace uhpc
