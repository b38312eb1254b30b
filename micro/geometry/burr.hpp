#pragma once
// Burr type XII distribution with location (docs/physics.md section 1, eq. 31), explicitly truncated.
// Pore equivalent sphere diameters (ESD) of the paper's micro-CT fit follow it. For x > gamma,
// z = (x - gamma) / beta:
//   pdf f0(x) = (alpha k / beta) z^(alpha-1) (1 + z^alpha)^-(k+1),   CDF F0(x) = 1 - (1 + z^alpha)^-k.
// The tail is heavy (moments of order >= alpha k diverge), so the law used for sampling is F0
// conditioned on x <= truncation: F(x) = F0(x) / F0(T). A truncation of +infinity gives the
// untruncated law (the one docs/specification.md's check values refer to). Pure functions, no I/O.
#include <cstdint>
#include <limits>
#include <random>

namespace uhpc::micro {

struct BurrParameters {
  double k = 0.0;        // shape (tail)
  double alpha = 0.0;    // shape
  double beta_m = 0.0;   // scale, m
  double gamma_m = 0.0;  // location (smallest ESD), m
};

// Uniform double in [0, 1) from the top 53 bits of one 64-bit draw. std::mt19937_64 is fully
// specified by the standard and this conversion is ours, so a seed gives the same numbers on every
// platform (std::uniform_real_distribution is implementation-defined).
inline double uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

class BurrXII {
 public:
  // Throws std::invalid_argument when a parameter is not positive and finite, or when
  // truncation_m <= gamma_m.
  explicit BurrXII(const BurrParameters& p, double truncation_m = std::numeric_limits<double>::infinity());

  const BurrParameters& parameters() const { return p_; }
  double truncation_m() const { return truncation_; }
  bool truncated() const { return truncation_ < std::numeric_limits<double>::infinity(); }
  // Probability mass of the untruncated law below the truncation, F0(T) (1 when untruncated).
  double kept_mass() const { return kept_mass_; }

  // The (renormalised) truncated law; equal to the untruncated one when truncation is infinite.
  double pdf(double x_m) const;
  double cdf(double x_m) const;
  double quantile(double u) const;  // u in [0, 1]

  // The untruncated law.
  double pdf_untruncated(double x_m) const;
  double cdf_untruncated(double x_m) const;
  double quantile_untruncated(double u) const;

  // Moments of the law sampled (truncated if truncation is finite). mean(): closed form
  // gamma + beta k B(k - 1/alpha, 1 + 1/alpha) when untruncated, quadrature otherwise;
  // mean_square() (E[x^2], needed for expected pore counts) requires a finite truncation or
  // alpha k > 2.
  double mean() const;
  double mean_square() const;
  double median() const { return quantile(0.5); }

  // Inverse-transform draw: one uniform per draw, so streams are reproducible.
  double sample(std::mt19937_64& rng) const { return quantile(uniform01(rng)); }

 private:
  // E[(x - gamma)^n] of the sampled law, by quadrature of n (x-gamma)^(n-1) (1 - F(x)).
  double central_moment_about_gamma(int n) const;

  BurrParameters p_;
  double truncation_;
  double kept_mass_;
};

}  // namespace uhpc::micro
