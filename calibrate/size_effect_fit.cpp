#include "size_effect_fit.hpp"

#include <cmath>
#include <stdexcept>

#include <ceres/ceres.h>

namespace uhpc {
namespace {

// (sigma_N - B f_t / sqrt(1 + D / D0)) / f_t, p = (ln B, ln D0): dimensionless, positive by construction.
struct StrengthResidual {
  StrengthResidual(double D, double strength_over_ft) : D_(D), s_(strength_over_ft) {}
  template <typename T>
  bool operator()(const T* const p, T* r) const {
    using std::exp;
    using std::sqrt;
    r[0] = T(s_) - exp(p[0]) / sqrt(T(1.0) + T(D_) / exp(p[1]));
    return true;
  }

 private:
  double D_, s_;
};

}  // namespace

double size_effect_strength(double B, double f_t_Pa, double D0_m, double D_m) {
  return B * f_t_Pa / std::sqrt(1.0 + D_m / D0_m);
}

SizeEffectFit fit_size_effect(const std::vector<double>& D, const std::vector<double>& sigma, double f_t) {
  const std::size_t n = D.size();
  if (n < 2 || sigma.size() != n) throw std::invalid_argument("size effect law: needs >= 2 sizes with one strength each");
  if (!(f_t > 0)) throw std::invalid_argument("size effect law: f_t must be > 0");
  SizeEffectFit fit;
  fit.f_t_Pa = f_t;

  // Linear start: Y = (f_t / sigma)^2 = p + q D with p = 1/B^2, q = 1/(B^2 D0).
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double y = (f_t / sigma[k]) * (f_t / sigma[k]);
    sx += D[k];
    sy += y;
    sxx += D[k] * D[k];
    sxy += D[k] * y;
  }
  const double nn = static_cast<double>(n);
  const double q = (nn * sxy - sx * sy) / (nn * sxx - sx * sx);
  const double p0 = (sy - q * sx) / nn;
  if (!(q > 0) || !(p0 > 0)) {
    fit.note = "the nominal strength does not fall with size as the law requires ((f_t/sigma_N)^2 against D has "
               "slope <= 0 or intercept <= 0): no size effect fitted";
    double mean = 0;
    for (double s : sigma) mean += s / nn;
    fit.B = mean / f_t;
    fit.D0_m = std::nan("");
    fit.standard_error = {std::nan(""), std::nan("")};
    fit.correlation = std::nan("");
    fit.rms_Pa = fit.r_squared = std::nan("");
    return fit;
  }

  std::array<double, 2> p = {-0.5 * std::log(p0), std::log(p0 / q)};
  ceres::Problem problem;
  for (std::size_t k = 0; k < n; ++k) {
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<StrengthResidual, 1, 2>(
                                 new StrengthResidual(D[k], sigma[k] / f_t)),
                             nullptr, p.data());
  }
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.function_tolerance = options.gradient_tolerance = 1e-15;
  options.parameter_tolerance = 1e-14;
  options.max_num_iterations = 200;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  fit.size_effect = true;
  fit.B = std::exp(p[0]);
  fit.D0_m = std::exp(p[1]);

  double ssr = 0, mean = 0, sst = 0;
  for (std::size_t k = 0; k < n; ++k) {
    fit.fitted_Pa.push_back(size_effect_strength(fit.B, f_t, fit.D0_m, D[k]));
    ssr += (sigma[k] - fit.fitted_Pa[k]) * (sigma[k] - fit.fitted_Pa[k]);
    mean += sigma[k] / nn;
  }
  for (double s : sigma) sst += (s - mean) * (s - mean);
  fit.rms_Pa = std::sqrt(ssr / nn);
  fit.r_squared = sst > 0 ? 1.0 - ssr / sst : std::nan("");

  // Covariance only with a residual degree of freedom (n > 2); 2 sizes determine the law exactly.
  fit.standard_error = {std::nan(""), std::nan("")};
  fit.correlation = std::nan("");
  if (n > 2) {
    ceres::Covariance::Options co;
    co.algorithm_type = ceres::DENSE_SVD;
    ceres::Covariance covariance(co);
    std::vector<std::pair<const double*, const double*>> blocks = {{p.data(), p.data()}};
    std::array<double, 4> c{};
    if (covariance.Compute(blocks, &problem) && covariance.GetCovarianceBlock(p.data(), p.data(), c.data())) {
      const double s2 = 2.0 * summary.final_cost / (nn - 2.0);
      fit.standard_error = {fit.B * std::sqrt(s2 * c[0]), fit.D0_m * std::sqrt(s2 * c[3])};
      fit.correlation = c[1] / std::sqrt(c[0] * c[3]);
    }
  }
  return fit;
}

}  // namespace uhpc
