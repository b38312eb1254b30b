#include "burr.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace uhpc::micro {

namespace {

bool positive_finite(double v) { return std::isfinite(v) && v > 0.0; }

}  // namespace

BurrXII::BurrXII(const BurrParameters& p, double truncation_m) : p_(p), truncation_(truncation_m), kept_mass_(1.0) {
  if (!positive_finite(p.k)) throw std::invalid_argument("Burr k must be > 0, got " + std::to_string(p.k));
  if (!positive_finite(p.alpha)) throw std::invalid_argument("Burr alpha must be > 0, got " + std::to_string(p.alpha));
  if (!positive_finite(p.beta_m)) throw std::invalid_argument("Burr beta must be > 0, got " + std::to_string(p.beta_m));
  if (!positive_finite(p.gamma_m)) throw std::invalid_argument("Burr gamma must be > 0, got " + std::to_string(p.gamma_m));
  if (std::isnan(truncation_m) || truncation_m <= p.gamma_m)
    throw std::invalid_argument("Burr truncation must exceed gamma");
  if (truncated()) kept_mass_ = cdf_untruncated(truncation_m);
}

double BurrXII::pdf_untruncated(double x) const {
  if (x <= p_.gamma_m) return 0.0;
  const double z = (x - p_.gamma_m) / p_.beta_m;
  const double za = std::pow(z, p_.alpha);
  return p_.alpha * p_.k / p_.beta_m * std::pow(z, p_.alpha - 1.0) * std::pow(1.0 + za, -(p_.k + 1.0));
}

double BurrXII::cdf_untruncated(double x) const {
  if (x <= p_.gamma_m) return 0.0;
  const double z = (x - p_.gamma_m) / p_.beta_m;
  // 1 - (1 + z^a)^-k = -expm1(-k log1p(z^a)): accurate for small z as well.
  return -std::expm1(-p_.k * std::log1p(std::pow(z, p_.alpha)));
}

double BurrXII::quantile_untruncated(double u) const {
  if (u <= 0.0) return p_.gamma_m;
  if (u >= 1.0) return std::numeric_limits<double>::infinity();
  // (1-u)^(-1/k) - 1 as expm1(-log1p(-u)/k) (docs/physics.md): no cancellation for small u.
  const double t = std::expm1(-std::log1p(-u) / p_.k);
  return p_.gamma_m + p_.beta_m * std::pow(t, 1.0 / p_.alpha);
}

double BurrXII::pdf(double x) const {
  if (x > truncation_) return 0.0;
  return pdf_untruncated(x) / kept_mass_;
}

double BurrXII::cdf(double x) const {
  if (x >= truncation_) return 1.0;
  return cdf_untruncated(x) / kept_mass_;
}

double BurrXII::quantile(double u) const {
  if (u >= 1.0) return truncated() ? truncation_ : std::numeric_limits<double>::infinity();
  const double x = quantile_untruncated(u * kept_mass_);
  return truncated() ? std::fmin(x, truncation_) : x;
}

double BurrXII::central_moment_about_gamma(int n) const {
  // E[y^n] = integral_0^inf n y^(n-1) S(y) dy, y = x - gamma, S the survival function. Substituting
  // y = beta t^2 / (1 - t)^2 (untruncated) or y = (T - gamma) s^2 (truncated) removes the integrable
  // kink at y = 0 (z^(alpha-1)) and maps the domain to a finite interval; composite Simpson on
  // 20 000 panels then converges to ~1e-10 relative (checked against the closed-form mean).
  const int panels = 20000;
  auto integrand = [&](double t) -> double {
    double y, dy;
    if (truncated()) {
      const double span = truncation_ - p_.gamma_m;
      y = span * t * t;
      dy = 2.0 * span * t;
    } else {
      if (t >= 1.0) return 0.0;
      const double s = 1.0 - t;
      y = p_.beta_m * t * t / (s * s);
      dy = p_.beta_m * 2.0 * t / (s * s * s);
    }
    const double survival = 1.0 - cdf(p_.gamma_m + y);
    return n * std::pow(y, n - 1) * survival * dy;
  };
  double sum = integrand(0.0) + integrand(1.0);
  const double h = 1.0 / panels;
  for (int i = 1; i < panels; ++i) sum += (i % 2 ? 4.0 : 2.0) * integrand(i * h);
  return sum * h / 3.0;
}

double BurrXII::mean() const {
  if (!truncated()) {
    if (p_.alpha * p_.k <= 1.0) return std::numeric_limits<double>::infinity();
    return p_.gamma_m + p_.beta_m * p_.k * std::beta(p_.k - 1.0 / p_.alpha, 1.0 + 1.0 / p_.alpha);
  }
  return p_.gamma_m + central_moment_about_gamma(1);
}

double BurrXII::mean_square() const {
  if (!truncated() && p_.alpha * p_.k <= 2.0) return std::numeric_limits<double>::infinity();
  const double m1 = central_moment_about_gamma(1), m2 = central_moment_about_gamma(2);
  return p_.gamma_m * p_.gamma_m + 2.0 * p_.gamma_m * m1 + m2;
}

}  // namespace uhpc::micro
