#pragma once
// The SDEL calibration (docs/physics.md section 3, paper eq. 27): find s = {a, A, nu, chi} > 0 minimising
//   sum_k sum_j w_kj^2 (d_ref^(k)(e_j) - d+(lambda_k, e_j; s))^2
// over all cell sizes k at once. Pure numerics, no I/O: the driver builds SdelFitData from an
// ensemble file and writes the result.
//
// - Positivity: A, nu and chi are fitted as ln A, ln nu, ln chi (always positive, and scales of 1e-4 ..
//   1e6 become numbers of order 1 for the solver). a is fitted as is with a lower bound
//   (a_lower_bound > 0): with noisy data the best a is often at zero (a lambda << 1 leaves a weak trace),
//   and in log space it would run off to -infinity with a singular covariance.
// - Derivatives: automatic differentiation (ceres::Jet) through uhpc::sdel_damage, the same template
//   the 3D code runs.
// - Starts: a data-driven start (per curve: the strain at d = 0.5 and the slope between d = 0.1 and
//   0.9; then a linear least-squares solve for A, a and ln nu across the sizes) followed by a grid of
//   (nu, a) starts built from the same per-curve figures. The lowest cost wins.
// - Uncertainty: ceres::Covariance (dense SVD) of the log-parameters, scaled by the residual
//   variance s^2 = SSR / (n - 4), but never by less than the data's stated resolution (see
//   SdelFitOptions::damage_resolution); transformed to the constants by the delta method.
//   Correlated residuals (real ensemble curves are smooth, their errors correlated along the strain)
//   make these standard errors too small; they are exact for independent noise.
#include <array>
#include <string>
#include <vector>

#include "uhpc/errors.hpp"

#include "uhpc/sdel.hpp"

namespace uhpc {

enum class SdelWeighting {
  None,    // plain least squares, the paper's eq. 27 (default)
  Spread,  // each sample divided by the standard error of its mean, std / sqrt(cells)
};

struct SdelFitOptions {
  SdelWeighting weighting = SdelWeighting::None;
  int starts = 8;  // how many of the candidate starts to run (>= 1)
  // Sample selection. A sample (size k, strain e) is fitted when strain_min <= e <= strain_max and,
  // if damage_window, damage_min <= d_ref <= damage_max. Defaults: every sample (eq. 27 as printed).
  double strain_min = 0.0;
  double strain_max = 1.0;
  bool damage_window = false;
  double damage_min = 0.02;
  double damage_max = 0.98;
  // The smallest damage uncertainty the fit assumes: floors the spread used as a weight and the
  // residual scatter used for the covariance. Without it noise-free curves (synthetic, or a perfect
  // fit) would report standard errors of round-off size. 1e-6 is below any ensemble's scatter and
  // about a quasi-static solver's equilibrium tolerance.
  double damage_resolution = 1e-6;
  // a is kept >= a_lower_bound (> 0, so the handoff stays valid); at the bound the data show no size
  // dependence of the initiation strain.
  double a_lower_bound = 1e-6;
  // Levenberg-Marquardt settings.
  int max_iterations = 200;
  double function_tolerance = 1e-15;
  double gradient_tolerance = 1e-15;
  double parameter_tolerance = 1e-14;
  // Identifiability flags: a constant is "not identifiable" when its relative standard error exceeds
  // max_relative_standard_error; a pair is reported when |correlation| > max_abs_correlation; a is
  // flagged "weak" when a * lambda_max < min_a_lambda (e_i then changes by ~a lambda / 2 across sizes).
  double max_relative_standard_error = 0.5;
  double max_abs_correlation = 0.99;
  double min_a_lambda = 0.1;
};

// One damage curve per size on a common strain grid.
struct SdelFitData {
  std::vector<double> lambdas;                   // l_mic / l_mac per size, > 0
  std::vector<double> strain;                    // common grid
  std::vector<std::vector<double>> damage;       // [size][strain]
  std::vector<std::vector<double>> sigma;        // [size][strain] standard error of each value (>= 0)
};

inline constexpr std::array<const char*, 4> kSdelConstantNames = {"a", "A", "nu", "chi"};

struct SdelStart {
  std::string origin;              // "data-driven linear solve", "grid nu=100 a=1", ...
  SdelConstants<double> initial{};
  SdelConstants<double> final{};
  double cost = 0;                 // 1/2 sum of weighted squared residuals at the end
  bool converged = false;
  int iterations = 0;
  std::string message;             // the solver's termination message
};

struct SdelSizeQuality {
  double lambda = 0;
  int samples = 0;          // fitted samples of this size
  double rms = 0;           // of d_ref - d_fit over the fitted samples (unweighted)
  double max_abs = 0;
  double r_squared = 0;     // 1 - SSR / SST over the fitted samples
};

struct SdelFitResult {
  SdelConstants<double> constants{};
  int best_start = -1;
  int starts_agreeing = 0;         // starts that ended at the best constants (each within 1e-6 relative)
  std::vector<SdelStart> starts;
  int samples = 0;                 // fitted samples, all sizes
  double cost = 0;                 // best start's cost
  double residual_scale = 0;       // s used for the covariance (weighted units), after the floor
  double residual_scale_raw = 0;   // sqrt(SSR_w / (n - 4)) before the floor
  bool covariance_ok = false;      // false: the Jacobian is rank-deficient at the optimum
  std::array<std::array<double, 4>, 4> covariance{};    // of (a, A, nu, chi)
  std::array<std::array<double, 4>, 4> correlation{};
  std::array<double, 4> standard_error{};
  std::array<double, 4> relative_standard_error{};      // standard error / value
  bool a_at_lower_bound = false;
  std::array<bool, 4> identifiable{};
  double a_lambda_max = 0;         // a * largest lambda
  bool a_weak = false;             // a_lambda_max < min_a_lambda
  std::vector<std::string> notes;  // human-readable identifiability findings
  std::vector<SdelSizeQuality> sizes;
};

// No start reached a finite optimum: the error carries every start (where it began, where it ended,
// the solver's message) so the caller can write them into a diagnostic file.
class SdelFitFailure : public NumericalError {
 public:
  explicit SdelFitFailure(std::vector<SdelStart> starts_run)
      : NumericalError("no start of the SDEL fit reached a finite optimum"), starts(std::move(starts_run)) {}
  std::vector<SdelStart> starts;
};

// Which samples enter the fit ([size][strain]).
std::vector<std::vector<bool>> sdel_fit_mask(const SdelFitData& data, const SdelFitOptions& options);

// The candidate starts in order of preference (the first `options.starts` are run).
std::vector<SdelStart> sdel_candidate_starts(const SdelFitData& data);

// Fits the SDEL. Throws std::invalid_argument for unusable data (fewer than 2 sizes: a and A cannot
// both be fitted; fewer than 4 samples; a curve that never reaches d = 0.5 ...) and SdelFitFailure when
// no start gives a finite optimum.
SdelFitResult fit_sdel(const SdelFitData& data, const SdelFitOptions& options);

}  // namespace uhpc
