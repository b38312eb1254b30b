// Known answer: curves generated from the paper's Table 4 SDEL at the four cell sizes, written to and
// read back from an ensemble file, are fitted back.
//   - no noise: all four constants to round-off (1e-12 relative), a also within its reported standard error;
//   - 1 % noise: every constant within three reported standard errors (several seeds, both weightings);
//   - the standard errors are honest: over many seeds about 68 % of the estimates lie within one
//     (more where the bound a >= a_lower_bound is active).
#include <array>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "uhpc/ensemble_file.hpp"
#include "ensemble_fit_data.hpp"
#include "sdel_fit.hpp"
#include "synthetic_ensemble.hpp"
#include "test_support.hpp"

namespace uhpc {
namespace {

const SdelConstants<double> kTable4{1.0, 2e-4, 120.5, 4.1e6};
const std::array<double, 4> kTrue = {1.0, 2e-4, 120.5, 4.1e6};
constexpr double kLmac = 0.4064;
constexpr double kRoundOffFit = 1e-12;  // a noise-free fit's relative error (measured below)

std::array<double, 4> values(const SdelConstants<double>& c) { return {c.a, c.A, c.nu, c.chi}; }

SyntheticEnsembleSettings paper_sizes(double noise, std::uint64_t seed) {
  SyntheticEnsembleSettings s;
  s.sizes_m = {0.003, 0.0045, 0.005, 0.0065};
  s.l_mac_m = kLmac;
  s.noise_std = noise;
  s.seed = seed;
  return s;
}

class CalibrateRecovery : public test::ScratchDirTest {
 protected:
  // Through the file format, as uhpc-calibrate sees it.
  SdelFitData via_file(double noise, std::uint64_t seed) {
    const auto path = dir_ / "ensemble.h5";
    write_ensemble(path, synthesize_ensemble(kTable4, paper_sizes(noise, seed)), Provenance::make("test", "", seed));
    return fit_data_from_ensemble(read_ensemble(path), kLmac);
  }
};

TEST_F(CalibrateRecovery, Table4WithoutNoise) {
  const SdelFitResult r = fit_sdel(via_file(0.0, 1), SdelFitOptions{});
  const auto v = values(r.constants);
  // Exact data are fitted back to round-off: measured relative errors a -4.1e-13, A -4.3e-15, nu 1.5e-14,
  // chi -5.6e-16 (README.md: 4.1e-13 or better). 1e-12 leaves room for another compiler's round-off and
  // fails any fit that stops short (the 1e-3 this asserted before passed a fit 1e9 times worse).
  for (std::size_t i = 0; i < 4; ++i) {
    std::printf("%s: %.17g, relative error %.2e\n", kSdelConstantNames[i], v[i], v[i] / kTrue[i] - 1.0);
    EXPECT_NEAR(v[i] / kTrue[i], 1.0, kRoundOffFit) << kSdelConstantNames[i];
  }
  ASSERT_TRUE(r.covariance_ok);
  EXPECT_GT(r.standard_error[0], 0.0);
  EXPECT_LE(std::abs(v[0] - kTrue[0]), r.standard_error[0]) << "a = " << v[0] << " +- " << r.standard_error[0];
  // The residuals are round-off, so the uncertainty comes from the resolution floor (1e-6).
  EXPECT_LT(r.residual_scale_raw, 1e-12);
  EXPECT_EQ(r.residual_scale, 1e-6);
  for (const auto& q : r.sizes) EXPECT_NEAR(q.r_squared, 1.0, 1e-12);
  // a lambda = 0.016 at 6.5 mm: the law's own warning.
  EXPECT_TRUE(r.a_weak);
  EXPECT_NEAR(r.a_lambda_max, 0.0065 / kLmac, 1e-9);
}

TEST_F(CalibrateRecovery, Table4WithoutNoiseInADamageWindow) {
  SdelFitOptions o;
  o.damage_window = true;
  const SdelFitResult r = fit_sdel(via_file(0.0, 1), o);
  const auto v = values(r.constants);
  // Measured: a -8.8e-14, A -7.8e-16, nu -1.2e-15, chi -5.6e-16.
  for (std::size_t i = 0; i < 4; ++i) {
    std::printf("window %s: %.17g, relative error %.2e\n", kSdelConstantNames[i], v[i], v[i] / kTrue[i] - 1.0);
    EXPECT_NEAR(v[i] / kTrue[i], 1.0, kRoundOffFit) << kSdelConstantNames[i];
  }
  EXPECT_LE(std::abs(v[0] - kTrue[0]), r.standard_error[0]);
  EXPECT_LT(r.samples, 4 * 201);
}

TEST_F(CalibrateRecovery, OnePercentNoiseWithinThreeStandardErrors) {
  for (SdelWeighting w : {SdelWeighting::None, SdelWeighting::Spread}) {
    for (std::uint64_t seed : {1u, 2u, 3u, 4u}) {
      SdelFitOptions o;
      o.weighting = w;
      const SdelFitResult r = fit_sdel(via_file(0.01, seed), o);
      ASSERT_TRUE(r.covariance_ok);
      const auto v = values(r.constants);
      for (std::size_t i = 0; i < 4; ++i) {
        EXPECT_LE(std::abs(v[i] - kTrue[i]), 3.0 * r.standard_error[i])
            << kSdelConstantNames[i] << " seed " << seed << ": " << v[i] << " +- " << r.standard_error[i];
      }
      // chi and nu are well determined; the noise must not hide them.
      EXPECT_TRUE(r.identifiable[2]);
      EXPECT_TRUE(r.identifiable[3]);
    }
  }
}

// If the standard errors were inflated the three-sigma test above could not fail; if they were too
// small it would fail by chance. Where all four constants are well determined (a = 20 and cells up to
// 40 mm, so a lambda reaches 2), the share of 80 seeds within one standard error must be near the
// normal 68 % (binomial sd 5 %: accept 55 - 82 %).
TEST_F(CalibrateRecovery, StandardErrorsHaveTheirNominalCoverage) {
  const SdelConstants<double> truth{20.0, 2e-4, 120.5, 2e6};
  const auto t = values(truth);
  std::array<int, 4> inside{};
  const int seeds = 80;
  SdelFitOptions o;
  o.starts = 1;
  for (int seed = 100; seed < 100 + seeds; ++seed) {
    SyntheticEnsembleSettings s = paper_sizes(0.01, static_cast<std::uint64_t>(seed));
    s.sizes_m = {0.005, 0.01, 0.02, 0.04};
    s.points = 801;  // the steepest curve (lambda chi = 2e5) needs a finer grid than the paper's sizes
    const SdelFitResult r = fit_sdel(fit_data_from_ensemble(synthesize_ensemble(truth, s), kLmac), o);
    ASSERT_FALSE(r.a_at_lower_bound);
    const auto v = values(r.constants);
    for (std::size_t i = 0; i < 4; ++i) inside[i] += std::abs(v[i] - t[i]) <= r.standard_error[i] ? 1 : 0;
  }
  for (std::size_t i = 0; i < 4; ++i) {
    const double share = static_cast<double>(inside[i]) / seeds;
    EXPECT_GE(share, 0.55) << kSdelConstantNames[i];
    EXPECT_LE(share, 0.82) << kSdelConstantNames[i];
  }
}

// At the paper's sizes a lambda <= 0.016 and 1 % noise put the best a at its lower bound in about a
// quarter of the seeds; the constrained estimate then scatters less than its linearized standard error
// says, so a (and A and nu, correlated with it) are covered more often than 68 %: conservative, never
// less. chi, nearly uncorrelated with a, keeps the nominal share.
TEST_F(CalibrateRecovery, AtThePaperSizesTheStandardErrorsAreNominalOrConservative) {
  std::array<int, 4> inside{};
  int at_bound = 0;
  const int seeds = 80;
  SdelFitOptions o;
  o.starts = 1;
  for (int seed = 100; seed < 100 + seeds; ++seed) {
    const SdelFitData d =
        fit_data_from_ensemble(synthesize_ensemble(kTable4, paper_sizes(0.01, static_cast<std::uint64_t>(seed))), kLmac);
    const SdelFitResult r = fit_sdel(d, o);
    ASSERT_TRUE(r.covariance_ok);
    at_bound += r.a_at_lower_bound ? 1 : 0;
    const auto v = values(r.constants);
    for (std::size_t i = 0; i < 4; ++i) inside[i] += std::abs(v[i] - kTrue[i]) <= r.standard_error[i] ? 1 : 0;
  }
  EXPECT_GT(at_bound, 0);
  for (std::size_t i = 0; i < 3; ++i) {
    const double share = static_cast<double>(inside[i]) / seeds;
    EXPECT_GE(share, 0.55) << kSdelConstantNames[i];
    EXPECT_LE(share, 0.97) << kSdelConstantNames[i];
  }
  const double chi_share = static_cast<double>(inside[3]) / seeds;
  EXPECT_GE(chi_share, 0.55);
  EXPECT_LE(chi_share, 0.82);
}

}  // namespace
}  // namespace uhpc
