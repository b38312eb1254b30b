// Ensemble statistics of cell curves (micro/app/ensemble_curves.hpp): hand-computable means and spreads,
// the nominal strength, and the conversion to the ensemble.h5 contract read back by the calibrate reader.
#include <cmath>

#include <gtest/gtest.h>

#include "ensemble_curves.hpp"
#include "test_support.hpp"
#include "uhpc/ensemble_file.hpp"
#include "uhpc/errors.hpp"

namespace uhpc::micro {
namespace {

TEST(MicroEnsembleCurves, StrainGridIsEvenAndEndsExactly) {
  const std::vector<double> g = strain_grid(1.5e-3, 301);
  ASSERT_EQ(g.size(), 301u);
  EXPECT_EQ(g.front(), 0.0);
  EXPECT_EQ(g.back(), 1.5e-3);
  EXPECT_DOUBLE_EQ(g[100], 5e-4);
  for (std::size_t j = 1; j < g.size(); ++j) EXPECT_GT(g[j], g[j - 1]);
  EXPECT_THROW(strain_grid(1e-3, 1), std::invalid_argument);
  EXPECT_THROW(strain_grid(0.0, 10), std::invalid_argument);
}

TEST(MicroEnsembleCurves, SpreadIsTheSampleStandardDeviation) {
  const Spread s = spread({1.0, 2.0, 3.0, 4.0});
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_DOUBLE_EQ(s.std, std::sqrt(5.0 / 3.0));  // sum of squares 5, n - 1 = 3
  EXPECT_EQ(s.count, 4u);
  EXPECT_EQ(spread({7.0}).std, 0.0);
  EXPECT_EQ(spread({7.0}).mean, 7.0);
  EXPECT_EQ(spread({}).count, 0u);
  // Two-pass: no cancellation for a small spread on a large mean.
  EXPECT_NEAR(spread({1e8 + 1.0, 1e8 - 1.0}).std, std::sqrt(2.0), 1e-9);
}

ResampledCurve curve(std::vector<double> d, std::vector<double> s) {
  ResampledCurve c;
  c.damage = std::move(d);
  c.stress_Pa = std::move(s);
  c.valid_points = c.damage.size();
  c.complete = true;
  return c;
}

TEST(MicroEnsembleCurves, MeanStdAndNominalStrengthPerSize) {
  const std::vector<double> grid = {0.0, 1e-4, 2e-4, 3e-4};
  const ResampledCurve a = curve({0.0, 0.2, 0.4, 1.0}, {0.0, 4e6, 6e6, 0.0});
  const ResampledCurve b = curve({0.0, 0.4, 0.8, 1.0}, {0.0, 3e6, 2e6, 0.0});
  const ResampledCurve c = curve({0.0, 0.3, 0.6, 1.0}, {0.0, 5e6, 7e6, 0.0});
  const SizeCurves s = size_curves(0.003, grid, {&a, &b, &c});
  EXPECT_EQ(s.cells, 3u);
  const std::vector<double> dm = {0.0, 0.3, 0.6, 1.0}, ds = {0.0, 0.1, 0.2, 0.0};
  const std::vector<double> sm = {0.0, 4e6, 5e6, 0.0};
  for (std::size_t j = 0; j < 4; ++j) {
    EXPECT_NEAR(s.damage_mean[j], dm[j], 1e-15) << j;
    EXPECT_NEAR(s.damage_std[j], ds[j], 1e-15) << j;
    EXPECT_NEAR(s.stress_mean_Pa[j], sm[j], 1e-9) << j;
  }
  EXPECT_NEAR(s.stress_std_Pa[1], 1e6, 1e-6);
  EXPECT_NEAR(s.stress_std_Pa[2], std::sqrt(7.0) * 1e6, 1e-6);  // deviations 1, -3, 2 MPa: 14 / 2
  // The peak of the mean curve, not the mean of the peaks (which is (6 + 3 + 7)/3 = 5.33 MPa).
  EXPECT_DOUBLE_EQ(s.nominal_strength_Pa, 5e6);
  EXPECT_DOUBLE_EQ(s.strain_at_nominal_strength, 2e-4);
  const ResampledCurve wrong = curve({0.0, 1.0}, {0.0, 0.0});
  EXPECT_THROW(size_curves(0.003, grid, {&a, &wrong}), std::invalid_argument);
}

class MicroEnsembleFile : public test::ScratchDirTest {};

TEST_F(MicroEnsembleFile, SizesWithoutCellsAreLeftOutAndTheFileReadsBack) {
  const std::vector<double> grid = {0.0, 1e-4, 2e-4};
  const ResampledCurve a = curve({0.0, 0.1, 0.5}, {0.0, 4e6, 3e6});
  const ResampledCurve b = curve({0.0, 0.3, 0.7}, {0.0, 2e6, 1e6});
  std::vector<SizeCurves> sizes = {size_curves(0.003, grid, {&a, &b}), size_curves(0.0045, grid, {}),
                                   size_curves(0.005, grid, {&b})};
  std::vector<double> skipped;
  const Ensemble e = to_ensemble(grid, sizes, &skipped);
  ASSERT_EQ(skipped, std::vector<double>{0.0045});
  ASSERT_EQ(e.size_count(), 2u);
  write_ensemble(dir_ / "ensemble.h5", e, Provenance::make("test", "abc"));
  const Ensemble back = read_ensemble(dir_ / "ensemble.h5");
  EXPECT_EQ(back.sizes_m, (std::vector<double>{0.003, 0.005}));
  EXPECT_EQ(back.cells, (std::vector<std::int64_t>{2, 1}));
  EXPECT_DOUBLE_EQ(back.nominal_strength_Pa[0], 3e6);  // mean stress (0, 3, 2) MPa
  EXPECT_DOUBLE_EQ(back.nominal_strength_Pa[1], 2e6);
  EXPECT_DOUBLE_EQ(back.damage_mean[0][2], 0.6);
  EXPECT_NEAR(back.damage_std[0][2], std::sqrt(0.02), 1e-15);
  EXPECT_EQ(back.damage_std[1][2], 0.0);  // one cell: no spread
}

}  // namespace
}  // namespace uhpc::micro
