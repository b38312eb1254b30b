#include "sdel_fit.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>
#include <stdexcept>

#include <Eigen/Dense>
#include <ceres/ceres.h>
#include <fmt/format.h>

#include "uhpc/errors.hpp"

namespace uhpc {
namespace {

// One sample's residual w (d_ref - d+(lambda, e; s)). Two parameter blocks: `a` itself (bounded below
// by SdelFitOptions::a_lower_bound) and `q` = (ln A, ln nu, ln chi).
struct SampleResidual {
  SampleResidual(double lambda, double strain, double damage, double weight)
      : lambda_(lambda), strain_(strain), damage_(damage), weight_(weight) {}

  template <typename T>
  bool operator()(const T* const a, const T* const q, T* residual) const {
    using std::exp;
    const SdelConstants<T> c{a[0], exp(q[0]), exp(q[1]), exp(q[2])};
    residual[0] = T(weight_) * (T(damage_) - sdel_damage(T(lambda_), T(strain_), c));
    return true;
  }

 private:
  double lambda_, strain_, damage_, weight_;
};

// The solver's parameters u = (a, ln A, ln nu, ln chi).
std::array<double, 4> to_params(const SdelConstants<double>& c) {
  return {c.a, std::log(c.A), std::log(c.nu), std::log(c.chi)};
}
SdelConstants<double> from_params(const std::array<double, 4>& u) {
  return {u[0], std::exp(u[1]), std::exp(u[2]), std::exp(u[3])};
}
std::array<double, 4> values(const SdelConstants<double>& c) { return {c.a, c.A, c.nu, c.chi}; }

double weight_of(const SdelFitData& data, const SdelFitOptions& o, std::size_t k, std::size_t j) {
  if (o.weighting == SdelWeighting::None) return 1.0;
  return 1.0 / std::max(data.sigma[k][j], o.damage_resolution);
}

// The problem for the parameters `u` (which must outlive it): blocks u[0] (a) and u[1..3].
std::unique_ptr<ceres::Problem> build_problem(const SdelFitData& data, const SdelFitOptions& o,
                                              const std::vector<std::vector<bool>>& mask, double* u) {
  auto problem = std::make_unique<ceres::Problem>();
  for (std::size_t k = 0; k < data.lambdas.size(); ++k) {
    for (std::size_t j = 0; j < data.strain.size(); ++j) {
      if (!mask[k][j]) continue;
      auto* cost = new ceres::AutoDiffCostFunction<SampleResidual, 1, 1, 3>(
          new SampleResidual(data.lambdas[k], data.strain[j], data.damage[k][j], weight_of(data, o, k, j)));
      problem->AddResidualBlock(cost, nullptr, u, u + 1);
    }
  }
  problem->SetParameterLowerBound(u, 0, o.a_lower_bound);
  return problem;
}

// First strain where the curve reaches `level` (linear interpolation); NaN if it never does.
double first_crossing(const std::vector<double>& strain, const std::vector<double>& d, double level) {
  for (std::size_t j = 0; j < d.size(); ++j) {
    if (d[j] < level) continue;
    if (j == 0) return strain[0];
    const double t = (level - d[j - 1]) / (d[j] - d[j - 1]);
    return strain[j - 1] + t * (strain[j] - strain[j - 1]);
  }
  return std::nan("");
}

// Per curve: the strain at d = 0.5 and the logistic slope lambda chi = 2 ln 9 / (e(0.9) - e(0.1)).
struct CurveFigures {
  double e50 = 0, slope = 0;
};

std::vector<CurveFigures> curve_figures(const SdelFitData& data) {
  std::vector<CurveFigures> out;
  for (std::size_t k = 0; k < data.lambdas.size(); ++k) {
    const double e10 = first_crossing(data.strain, data.damage[k], 0.1);
    const double e50 = first_crossing(data.strain, data.damage[k], 0.5);
    const double e90 = first_crossing(data.strain, data.damage[k], 0.9);
    if (std::isnan(e10) || std::isnan(e50) || std::isnan(e90) || !(e90 > e10)) {
      throw std::invalid_argument(fmt::format(
          "size index {} (lambda {:.6g}): the mean damage curve does not rise through 0.1, 0.5 and 0.9 on "
          "the strain grid, so the softening the SDEL describes is not in the data",
          k, data.lambdas[k]));
    }
    out.push_back({e50, 2.0 * std::log(9.0) / (e90 - e10)});
  }
  return out;
}

}  // namespace

std::vector<std::vector<bool>> sdel_fit_mask(const SdelFitData& data, const SdelFitOptions& o) {
  std::vector<std::vector<bool>> mask(data.lambdas.size(), std::vector<bool>(data.strain.size(), false));
  for (std::size_t k = 0; k < mask.size(); ++k) {
    for (std::size_t j = 0; j < data.strain.size(); ++j) {
      const double e = data.strain[j], d = data.damage[k][j];
      bool use = e >= o.strain_min && e <= o.strain_max;
      if (o.damage_window) use = use && d >= o.damage_min && d <= o.damage_max;
      mask[k][j] = use;
    }
  }
  return mask;
}

std::vector<SdelStart> sdel_candidate_starts(const SdelFitData& data) {
  const std::vector<CurveFigures> fig = curve_figures(data);
  const std::size_t n = fig.size();
  double chi = 0;
  for (std::size_t k = 0; k < n; ++k) chi += fig[k].slope / data.lambdas[k] / static_cast<double>(n);

  std::vector<SdelStart> starts;
  auto add = [&](const std::string& origin, double a, double A, double nu) {
    if (std::isfinite(a) && std::isfinite(A) && std::isfinite(nu) && a > 0 && A > 0 && nu > 0 && chi > 0) {
      SdelStart s;
      s.origin = origin;
      s.initial = {a, A, nu, chi};
      starts.push_back(s);
    }
  };

  // Data-driven: e50_k = e_i(lambda_k) + ln nu / slope_k with e_i ~ A - (A a / 2) lambda_k is linear
  // in (A, A a / 2, ln nu); three or more sizes determine it.
  double nu_linear = std::nan("");
  if (n >= 3) {
    Eigen::MatrixXd M(n, 3);
    Eigen::VectorXd y(n);
    for (std::size_t k = 0; k < n; ++k) {
      const auto r = static_cast<Eigen::Index>(k);
      M(r, 0) = 1.0;
      M(r, 1) = -data.lambdas[k];
      M(r, 2) = 1.0 / fig[k].slope;
      y(r) = fig[k].e50;
    }
    const Eigen::Vector3d x = M.colPivHouseholderQr().solve(y);
    const double A = x(0), a = 2.0 * x(1) / x(0);
    if (std::abs(x(2)) < 50.0) nu_linear = std::exp(x(2));
    if (a > 0) {
      add("data-driven linear solve", a, A, nu_linear);
    } else {
      add("data-driven linear solve (a <= 0 replaced by 0.1)", 0.1, A, nu_linear);
    }
  }
  // Grid over nu and a; for each, e_i per size from e50 and the slope, then A as their mean scaled back
  // to lambda = 0.
  std::vector<double> nus = {100.0, 10.0, 1000.0, 3.0};
  if (std::isfinite(nu_linear)) nus.insert(nus.begin(), nu_linear);
  for (double nu : nus) {
    for (double a : {1.0, 0.1, 10.0}) {
      double A = 0;
      bool ok = true;
      for (std::size_t k = 0; k < n; ++k) {
        const double ei = fig[k].e50 - std::log(nu) / fig[k].slope;
        ok = ok && ei > 0;
        A += ei * std::sqrt(1.0 + a * data.lambdas[k]) / static_cast<double>(n);
      }
      if (ok) add(fmt::format("grid nu={:.6g} a={:g}", nu, a), a, A, nu);
    }
  }
  return starts;
}

SdelFitResult fit_sdel(const SdelFitData& data, const SdelFitOptions& o) {
  const std::size_t n_sizes = data.lambdas.size();
  if (n_sizes < 2) {
    throw std::invalid_argument(
        "one size cannot separate a from A (e_i = A / sqrt(1 + a lambda) is then a single number): "
        "the fit needs at least 2 sizes");
  }
  if (data.damage.size() != n_sizes || data.sigma.size() != n_sizes) {
    throw std::invalid_argument("fit_sdel: one damage and one sigma curve per size expected");
  }
  if (o.starts < 1) throw std::invalid_argument("fit_sdel: starts must be >= 1");

  const auto mask = sdel_fit_mask(data, o);
  int samples = 0;
  for (const auto& row : mask) samples += static_cast<int>(std::count(row.begin(), row.end(), true));
  if (samples <= 4) {
    throw std::invalid_argument(fmt::format("only {} samples are selected for 4 constants", samples));
  }

  SdelFitResult result;
  result.samples = samples;
  std::vector<SdelStart> candidates = sdel_candidate_starts(data);
  if (candidates.empty()) throw std::invalid_argument("no positive start can be built from the curves");
  if (candidates.size() > static_cast<std::size_t>(o.starts)) candidates.resize(static_cast<std::size_t>(o.starts));

  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = o.max_iterations;
  solver.function_tolerance = o.function_tolerance;
  solver.gradient_tolerance = o.gradient_tolerance;
  solver.parameter_tolerance = o.parameter_tolerance;
  solver.logging_type = ceres::SILENT;
  solver.num_threads = 1;

  for (std::size_t i = 0; i < candidates.size(); ++i) {
    SdelStart& s = candidates[i];
    std::array<double, 4> p = to_params(s.initial);
    p[0] = std::max(p[0], o.a_lower_bound);
    auto problem = build_problem(data, o, mask, p.data());
    ceres::Solver::Summary summary;
    ceres::Solve(solver, problem.get(), &summary);
    s.final = from_params(p);
    s.cost = summary.final_cost;
    s.converged = summary.termination_type == ceres::CONVERGENCE;
    s.iterations = static_cast<int>(summary.iterations.size());
    s.message = summary.message;
    const bool usable = summary.IsSolutionUsable() && std::isfinite(s.cost) &&
                        std::all_of(p.begin(), p.end(), [](double v) { return std::isfinite(v); });
    if (usable && (result.best_start < 0 || s.cost < candidates[static_cast<std::size_t>(result.best_start)].cost)) {
      result.best_start = static_cast<int>(i);
    }
  }
  if (result.best_start < 0) throw SdelFitFailure(std::move(candidates));
  result.starts = candidates;
  const SdelStart& best = candidates[static_cast<std::size_t>(result.best_start)];
  result.constants = best.final;
  result.cost = best.cost;
  // How many starts found the same optimum: a cheap check that the minimum is not an accident of one start.
  for (const SdelStart& s : candidates) {
    const std::array<double, 4> a = values(s.final), b = values(best.final);
    bool same = std::isfinite(s.cost);
    for (std::size_t i = 0; i < 4; ++i) same = same && std::abs(a[i] - b[i]) <= 1e-6 * std::abs(b[i]);
    result.starts_agreeing += same ? 1 : 0;
  }

  // Covariance of u = (a, ln A, ln nu, ln chi) at the optimum, scaled by the residual variance. At the
  // bound a = a_lower_bound it is that of the linearized problem: how far a could move either way.
  std::array<double, 4> u = to_params(result.constants);
  auto problem = build_problem(data, o, mask, u.data());
  ceres::Covariance::Options cov_options;
  cov_options.algorithm_type = ceres::DENSE_SVD;  // reports rank deficiency instead of failing silently
  cov_options.num_threads = 1;
  ceres::Covariance covariance(cov_options);
  const double* a_block = u.data();
  const double* q_block = u.data() + 1;
  std::vector<std::pair<const double*, const double*>> blocks = {
      {a_block, a_block}, {a_block, q_block}, {q_block, q_block}};
  std::array<double, 16> cu{};
  result.covariance_ok = covariance.Compute(blocks, problem.get()) &&
                         covariance.GetCovarianceMatrix({a_block, q_block}, cu.data());
  result.residual_scale_raw = std::sqrt(2.0 * result.cost / static_cast<double>(samples - 4));
  const double floor = o.weighting == SdelWeighting::None ? o.damage_resolution : 1.0;
  result.residual_scale = std::max(result.residual_scale_raw, floor);
  const double s2 = result.residual_scale * result.residual_scale;
  const std::array<double, 4> v = values(result.constants);
  // Delta method: d a = d u0, d X = X d(ln X) for the other three.
  const std::array<double, 4> scale = {1.0, v[1], v[2], v[3]};
  for (std::size_t i = 0; i < 4; ++i) {
    for (std::size_t j = 0; j < 4; ++j) {
      result.covariance[i][j] = result.covariance_ok ? s2 * scale[i] * scale[j] * cu[i * 4 + j] : std::nan("");
    }
  }
  for (std::size_t i = 0; i < 4; ++i) {
    result.standard_error[i] = std::sqrt(result.covariance[i][i]);
    result.relative_standard_error[i] = result.standard_error[i] / v[i];
  }
  result.a_at_lower_bound = result.constants.a <= o.a_lower_bound * (1.0 + 1e-9);
  if (result.a_at_lower_bound) {
    result.notes.push_back(fmt::format(
        "a is at its lower bound {:g}: the data show no decrease of the initiation strain with size; its standard "
        "error is that of the linearized problem at the bound",
        o.a_lower_bound));
  }
  for (std::size_t i = 0; i < 4; ++i) {
    for (std::size_t j = 0; j < 4; ++j) {
      result.correlation[i][j] = result.covariance[i][j] / (result.standard_error[i] * result.standard_error[j]);
    }
  }

  // Identifiability.
  if (!result.covariance_ok) {
    result.notes.push_back("the Jacobian is rank-deficient at the optimum: the data do not determine all four "
                           "constants, no covariance is reported");
  }
  if (n_sizes == 2) {
    // The SDEL is a logistic in the strain: each curve carries its midpoint and its slope, nothing more.
    // The slopes fix chi; two midpoints cannot fix the three of A, a and nu.
    result.notes.push_back("two sizes give two midpoints for the three constants A, a, nu (each curve is a "
                           "logistic: midpoint and slope): at least 3 sizes are needed to determine all four");
  }
  for (std::size_t i = 0; i < 4; ++i) {
    result.identifiable[i] =
        result.covariance_ok && result.relative_standard_error[i] <= o.max_relative_standard_error;
    if (result.covariance_ok && !result.identifiable[i]) {
      result.notes.push_back(fmt::format("{} is not identifiable from these data: relative standard error {:.3g} > {:g}",
                                         kSdelConstantNames[i], result.relative_standard_error[i],
                                         o.max_relative_standard_error));
    }
    for (std::size_t j = i + 1; j < 4 && result.covariance_ok; ++j) {
      if (std::abs(result.correlation[i][j]) > o.max_abs_correlation) {
        result.notes.push_back(fmt::format("{} and {} are strongly correlated ({:.4f}): the data fix a combination "
                                           "of the two better than each",
                                           kSdelConstantNames[i], kSdelConstantNames[j], result.correlation[i][j]));
      }
    }
  }
  const double lambda_max = *std::max_element(data.lambdas.begin(), data.lambdas.end());
  result.a_lambda_max = result.constants.a * lambda_max;
  result.a_weak = result.a_lambda_max < o.min_a_lambda;
  if (result.a_weak) {
    result.notes.push_back(fmt::format(
        "a is weakly identifiable: a * lambda <= {:.3g} << 1, so e_i = A / sqrt(1 + a lambda) changes by only "
        "about {:.2g} % across the sizes",
        result.a_lambda_max, 50.0 * result.constants.a * (lambda_max - *std::min_element(data.lambdas.begin(),
                                                                                          data.lambdas.end()))));
  }

  // Fit quality per size (unweighted, over the fitted samples).
  for (std::size_t k = 0; k < n_sizes; ++k) {
    SdelSizeQuality q;
    q.lambda = data.lambdas[k];
    double sum = 0, ssr = 0;
    for (std::size_t j = 0; j < data.strain.size(); ++j) {
      if (!mask[k][j]) continue;
      const double r = data.damage[k][j] - sdel_damage(data.lambdas[k], data.strain[j], result.constants);
      ++q.samples;
      sum += data.damage[k][j];
      ssr += r * r;
      q.max_abs = std::max(q.max_abs, std::abs(r));
    }
    double sst = 0;
    const double mean = q.samples > 0 ? sum / q.samples : 0.0;
    for (std::size_t j = 0; j < data.strain.size(); ++j) {
      if (mask[k][j]) sst += (data.damage[k][j] - mean) * (data.damage[k][j] - mean);
    }
    q.rms = q.samples > 0 ? std::sqrt(ssr / q.samples) : std::nan("");
    q.r_squared = sst > 0 ? 1.0 - ssr / sst : std::nan("");
    result.sizes.push_back(q);
  }
  return result;
}

}  // namespace uhpc
