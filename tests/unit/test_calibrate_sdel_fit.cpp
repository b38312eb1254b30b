// The SDEL fitter's parts (calibrate/sdel_fit.hpp): sample selection, the data-driven start, the
// refusals (one size, no softening), positivity, weighting and the identifiability flags.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "ensemble_fit_data.hpp"
#include "sdel_fit.hpp"
#include "synthetic_ensemble.hpp"
#include "test_support.hpp"

namespace uhpc {
namespace {

const SdelConstants<double> kTable4{1.0, 2e-4, 120.5, 4.1e6};

SdelFitData data_for(const SdelConstants<double>& c, std::vector<double> sizes, double noise = 0.0,
                     std::uint64_t seed = 1) {
  SyntheticEnsembleSettings s;
  s.sizes_m = std::move(sizes);
  s.noise_std = noise;
  s.seed = seed;
  return fit_data_from_ensemble(synthesize_ensemble(c, s), s.l_mac_m);
}

const std::vector<double> kSizes = {0.003, 0.0045, 0.005, 0.0065};

TEST(CalibrateSdelFitMask, DefaultSelectsEverySampleAndWindowsSelectTheirRange) {
  const SdelFitData d = data_for(kTable4, kSizes);
  SdelFitOptions o;
  for (const auto& row : sdel_fit_mask(d, o)) EXPECT_EQ(std::count(row.begin(), row.end(), true), 201);
  o.strain_min = 2e-4;
  o.strain_max = 4e-4;
  for (const auto& row : sdel_fit_mask(d, o)) EXPECT_EQ(std::count(row.begin(), row.end(), true), 41);  // 5e-6 grid
  o = SdelFitOptions{};
  o.damage_window = true;
  const auto mask = sdel_fit_mask(d, o);
  for (std::size_t k = 0; k < mask.size(); ++k) {
    for (std::size_t j = 0; j < d.strain.size(); ++j) {
      EXPECT_EQ(mask[k][j], d.damage[k][j] >= 0.02 && d.damage[k][j] <= 0.98);
    }
  }
}

TEST(CalibrateSdelFitStarts, TheDataDrivenStartComesFirstAndIsClose) {
  const auto starts = sdel_candidate_starts(data_for(kTable4, kSizes));
  ASSERT_GE(starts.size(), 8u);
  EXPECT_EQ(starts.front().origin, "data-driven linear solve");
  const SdelConstants<double>& c = starts.front().initial;
  // Per-curve crossings interpolated on a 5e-6 grid: a few per cent, enough to start Gauss-Newton.
  EXPECT_NEAR(c.chi / kTable4.chi, 1.0, 0.01);
  EXPECT_NEAR(c.A / kTable4.A, 1.0, 0.02);
  EXPECT_NEAR(std::log(c.nu) / std::log(kTable4.nu), 1.0, 0.05);
  for (const auto& s : starts) {
    EXPECT_GT(s.initial.a, 0);
    EXPECT_GT(s.initial.A, 0);
    EXPECT_GT(s.initial.nu, 0);
    EXPECT_GT(s.initial.chi, 0);
  }
}

TEST(CalibrateSdelFit, OneSizeCannotSeparateAFromA) {
  const std::string what =
      test::error_of<std::invalid_argument>([] { (void)fit_sdel(data_for(kTable4, {0.003}), SdelFitOptions{}); });
  EXPECT_NE(what.find("one size cannot separate a from A"), std::string::npos) << what;
}

TEST(CalibrateSdelFit, CurvesWithoutSofteningAreRefused) {
  SdelFitData d = data_for(kTable4, kSizes);
  for (auto& v : d.damage[2]) v = std::min(v, 0.4);  // size 2 never reaches 0.5
  const std::string what = test::error_of<std::invalid_argument>([&] { (void)fit_sdel(d, SdelFitOptions{}); });
  EXPECT_NE(what.find("size index 2"), std::string::npos) << what;
}

TEST(CalibrateSdelFit, SpreadWeightingWithZeroSpreadFallsBackToTheResolutionAndAgrees) {
  const SdelFitData d = data_for(kTable4, kSizes);
  SdelFitOptions none, spread;
  spread.weighting = SdelWeighting::Spread;
  const SdelFitResult a = fit_sdel(d, none), b = fit_sdel(d, spread);
  EXPECT_NEAR(b.constants.nu / a.constants.nu, 1.0, 1e-9);
  EXPECT_NEAR(b.constants.chi / a.constants.chi, 1.0, 1e-9);
  // Uniform weights 1/resolution and residual scale floored at 1: the same standard errors.
  for (std::size_t i = 0; i < 4; ++i) EXPECT_NEAR(b.standard_error[i] / a.standard_error[i], 1.0, 1e-6);
}

TEST(CalibrateSdelFit, ConstantsStayPositiveWhenTheTrueAIsTiny) {
  const SdelConstants<double> c{1e-3, 2e-4, 120.5, 4.1e6};
  const SdelFitResult r = fit_sdel(data_for(c, kSizes, 0.01, 5), SdelFitOptions{});
  EXPECT_GT(r.constants.a, 0.0);
  EXPECT_TRUE(r.a_weak);
  EXPECT_FALSE(r.identifiable[0]);  // a = 1e-3 leaves no trace in 1 % noise
  EXPECT_TRUE(r.identifiable[2]);
  EXPECT_TRUE(r.identifiable[3]);
  bool noted = false;
  for (const auto& n : r.notes) noted = noted || n.rfind("a is not identifiable from these data", 0) == 0;
  EXPECT_TRUE(noted);
}

// Each curve of the SDEL is a logistic in the strain and carries two numbers, its midpoint and slope.
// With two sizes the slopes fix chi, but two midpoints cannot fix A, a and nu: the Jacobian is
// rank-deficient whatever the sizes, and nothing is claimed identifiable.
TEST(CalibrateSdelFit, TwoSizesGiveARankDeficientFitAndSaySo) {
  for (const std::vector<double>& sizes : {std::vector<double>{0.003, 0.0065}, std::vector<double>{0.003, 0.00301}}) {
    const SdelFitResult r = fit_sdel(data_for(kTable4, sizes, 0.01, 2), SdelFitOptions{});
    EXPECT_FALSE(r.covariance_ok);
    for (std::size_t i = 0; i < 4; ++i) {
      EXPECT_FALSE(r.identifiable[i]);
      EXPECT_TRUE(std::isnan(r.standard_error[i]));
    }
    ASSERT_GE(r.notes.size(), 2u);
    EXPECT_EQ(r.notes[0].rfind("the Jacobian is rank-deficient", 0), 0u) << r.notes[0];
    EXPECT_EQ(r.notes[1].rfind("two sizes give two midpoints", 0), 0u) << r.notes[1];
    // The curves themselves are fitted: the residual is the noise.
    for (const auto& q : r.sizes) EXPECT_NEAR(q.rms, 0.01, 0.0015);
  }
}

// Three sizes are the minimum: all four constants then have a covariance.
TEST(CalibrateSdelFit, ThreeSizesDetermineAllFour) {
  const SdelFitResult r = fit_sdel(data_for(kTable4, {0.003, 0.0045, 0.0065}), SdelFitOptions{});
  EXPECT_TRUE(r.covariance_ok);
  EXPECT_NEAR(r.constants.nu / kTable4.nu, 1.0, 1e-6);
}

TEST(CalibrateSdelFit, QualityPerSizeMatchesTheNoise) {
  const SdelFitResult r = fit_sdel(data_for(kTable4, kSizes, 0.01, 11), SdelFitOptions{});
  ASSERT_EQ(r.sizes.size(), 4u);
  for (const auto& q : r.sizes) {
    EXPECT_EQ(q.samples, 201);
    EXPECT_NEAR(q.rms, 0.01, 0.002);   // 201 samples: the rms of N(0, 0.01) within ~3 sigma
    EXPECT_GT(q.r_squared, 0.999);
  }
  EXPECT_NEAR(r.residual_scale, 0.01, 0.001);
  EXPECT_EQ(r.residual_scale, r.residual_scale_raw);  // above the 1e-6 floor
  EXPECT_EQ(r.starts_agreeing, static_cast<int>(r.starts.size()));
}

TEST(CalibrateSdelFit, CorrelationMatrixIsSymmetricWithUnitDiagonal) {
  const SdelFitResult r = fit_sdel(data_for(kTable4, kSizes, 0.01, 4), SdelFitOptions{});
  ASSERT_TRUE(r.covariance_ok);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(r.correlation[i][i], 1.0, 1e-12);
    for (std::size_t j = 0; j < 4; ++j) {
      EXPECT_NEAR(r.correlation[i][j], r.correlation[j][i], 1e-12);
      EXPECT_LE(std::abs(r.correlation[i][j]), 1.0 + 1e-12);
    }
  }
}

}  // namespace
}  // namespace uhpc
