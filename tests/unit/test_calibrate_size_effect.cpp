// Bazant's size effect law fit (calibrate/size_effect_fit.hpp).
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "size_effect_fit.hpp"

namespace uhpc {
namespace {

constexpr double kFt = 22.7e6;

TEST(CalibrateSizeEffect, RecoversTheLawFromExactStrengths) {
  const std::vector<double> D = {0.003, 0.0045, 0.005, 0.0065};
  std::vector<double> s;
  for (double d : D) s.push_back(size_effect_strength(0.6, kFt, 0.005, d));
  const SizeEffectFit f = fit_size_effect(D, s, kFt);
  ASSERT_TRUE(f.size_effect);
  EXPECT_NEAR(f.B, 0.6, 1e-9);
  EXPECT_NEAR(f.D0_m, 0.005, 1e-11);
  EXPECT_LT(f.rms_Pa, 1e-3);
  EXPECT_NEAR(f.r_squared, 1.0, 1e-12);
}

// Values worked by hand, not made by the law under test: with B = 0.6, D0 = 4 mm and f_t = 22.7 MPa,
// 1 + D / D0 is 4, 9 and 16 at D = 12, 32 and 60 mm, so sigma_N = 0.6 x 22.7 / 2, / 3 and / 4 MPa = 6.81,
// 4.54 and 3.405 MPa exactly; at D = D0, 13.62 / sqrt(2) = 9.630794359761 MPa.
TEST(CalibrateSizeEffect, LawAndFitAgainstHandValues) {
  EXPECT_NEAR(size_effect_strength(0.6, kFt, 0.004, 0.012), 6.81e6, 1e-8);
  EXPECT_NEAR(size_effect_strength(0.6, kFt, 0.004, 0.032), 4.54e6, 1e-8);
  EXPECT_NEAR(size_effect_strength(0.6, kFt, 0.004, 0.004), 9.630794359761e6, 1e-5);
  const SizeEffectFit f = fit_size_effect({0.012, 0.032, 0.06}, {6.81e6, 4.54e6, 3.405e6}, kFt);
  ASSERT_TRUE(f.size_effect);
  EXPECT_NEAR(f.B, 0.6, 1e-9);
  EXPECT_NEAR(f.D0_m, 0.004, 1e-11);
  EXPECT_LT(f.rms_Pa, 1e-3);
  ASSERT_EQ(f.fitted_Pa.size(), 3u);
  EXPECT_NEAR(f.fitted_Pa[2], 3.405e6, 1e-3);
}

TEST(CalibrateSizeEffect, WithinThreeStandardErrorsUnderNoise) {
  std::mt19937_64 rng(9);
  std::normal_distribution<double> noise(0.0, 0.01);
  std::vector<double> D, s;
  for (int i = 0; i < 8; ++i) {
    D.push_back(0.002 * std::pow(1.4, i));
    s.push_back(size_effect_strength(0.6, kFt, 0.005, D.back()) * (1.0 + noise(rng)));
  }
  const SizeEffectFit f = fit_size_effect(D, s, kFt);
  ASSERT_TRUE(f.size_effect);
  EXPECT_GT(f.standard_error[0], 0);
  EXPECT_LE(std::abs(f.B - 0.6), 3 * f.standard_error[0]);
  EXPECT_LE(std::abs(f.D0_m - 0.005), 3 * f.standard_error[1]);
  EXPECT_LT(std::abs(f.correlation), 1.0);
}

TEST(CalibrateSizeEffect, TwoSizesAreFittedExactlyWithoutStandardErrors) {
  const std::vector<double> D = {0.003, 0.0065};
  const std::vector<double> s = {size_effect_strength(0.7, kFt, 0.004, D[0]), size_effect_strength(0.7, kFt, 0.004, D[1])};
  const SizeEffectFit f = fit_size_effect(D, s, kFt);
  EXPECT_NEAR(f.B, 0.7, 1e-9);
  EXPECT_NEAR(f.D0_m, 0.004, 1e-11);
  EXPECT_TRUE(std::isnan(f.standard_error[0]));
}

TEST(CalibrateSizeEffect, StrengthRisingWithSizeIsNotASizeEffect) {
  const SizeEffectFit f = fit_size_effect({0.003, 0.005}, {9e6, 10e6}, kFt);
  EXPECT_FALSE(f.size_effect);
  EXPECT_NE(f.note.find("does not fall with size"), std::string::npos);
  EXPECT_NEAR(f.B * kFt, 9.5e6, 1e-6);
}

TEST(CalibrateSizeEffect, RefusesMismatchedInput) {
  EXPECT_THROW((void)fit_size_effect({0.003}, {9e6}, kFt), std::invalid_argument);
  EXPECT_THROW((void)fit_size_effect({0.003, 0.004}, {9e6}, kFt), std::invalid_argument);
}

}  // namespace
}  // namespace uhpc
