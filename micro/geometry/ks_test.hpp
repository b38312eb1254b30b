#pragma once
// One-sample Kolmogorov-Smirnov test of draws against a continuous CDF (used by the sampler's tests
// and by the ensemble statistics to check that the Burr draws follow the law).
#include <algorithm>
#include <cmath>
#include <vector>

namespace uhpc::micro {

// D = sup |F_n(x) - F(x)| of the sample (sorted internally).
template <class Cdf>
double ks_statistic(std::vector<double> sample, Cdf&& cdf) {
  std::sort(sample.begin(), sample.end());
  const double n = static_cast<double>(sample.size());
  double d = 0.0;
  for (std::size_t i = 0; i < sample.size(); ++i) {
    const double f = cdf(sample[i]);
    d = std::max({d, f - i / n, (i + 1) / n - f});
  }
  return d;
}

// Asymptotic p-value P(D_n > d) with Stephens' small-sample correction
// lambda = (sqrt(n) + 0.12 + 0.11/sqrt(n)) d, Q(lambda) = 2 sum_{j>=1} (-1)^(j-1) exp(-2 j^2 lambda^2).
inline double ks_p_value(double d, std::size_t n) {
  const double sn = std::sqrt(static_cast<double>(n));
  const double lambda = (sn + 0.12 + 0.11 / sn) * d;
  if (lambda < 0.2) return 1.0;  // the series converges slowly there and Q = 1 to 1e-10
  double q = 0.0, sign = 1.0;
  for (int j = 1; j <= 100; ++j) {
    const double term = std::exp(-2.0 * j * j * lambda * lambda);
    q += sign * term;
    sign = -sign;
    if (term < 1e-16) break;
  }
  return std::clamp(2.0 * q, 0.0, 1.0);
}

}  // namespace uhpc::micro
