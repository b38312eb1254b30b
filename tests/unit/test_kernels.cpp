// Kernel functions: values, continuity of the piecewise pieces, derivatives against finite differences.
#include <gtest/gtest.h>

#include <stdexcept>

#include "uhpc/kernels.hpp"

using uhpc::KernelType;
using uhpc::kernel_value;

namespace {

const KernelType kAll[] = {KernelType::CubicBSpline, KernelType::QuarticSpline};

TEST(Kernels, CubicBSplineKnownValues) {
  EXPECT_DOUBLE_EQ(kernel_value(KernelType::CubicBSpline, 0.0).w, 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(kernel_value(KernelType::CubicBSpline, 0.5).w, 1.0 / 6.0);
  EXPECT_DOUBLE_EQ(kernel_value(KernelType::CubicBSpline, 0.25).w, 2.0 / 3.0 - 0.25 + 1.0 / 16.0);
  EXPECT_DOUBLE_EQ(kernel_value(KernelType::QuarticSpline, 0.0).w, 1.0);
  EXPECT_DOUBLE_EQ(kernel_value(KernelType::QuarticSpline, 0.5).w, 1.0 - 1.5 + 1.0 - 3.0 / 16.0);
}

TEST(Kernels, VanishOutsideSupportAndAtItsEdge) {
  for (KernelType t : kAll) {
    EXPECT_EQ(kernel_value(t, 1.0).w, 0.0);
    EXPECT_EQ(kernel_value(t, 1.5).w, 0.0);
    EXPECT_NEAR(kernel_value(t, 1.0 - 1e-9).w, 0.0, 1e-15);
    EXPECT_NEAR(kernel_value(t, 1.0 - 1e-9).dw_dz, 0.0, 1e-12);
    EXPECT_EQ(kernel_value(t, 0.0).dw_dz, 0.0);  // smooth at the centre
  }
}

TEST(Kernels, PiecesJoinWithContinuousValueAndSlope) {
  const double e = 1e-12;
  const auto below = kernel_value(KernelType::CubicBSpline, 0.5 - e);
  const auto above = kernel_value(KernelType::CubicBSpline, 0.5 + e);
  EXPECT_NEAR(below.w, above.w, 1e-11);
  EXPECT_NEAR(below.dw_dz, above.dw_dz, 1e-10);
}

TEST(Kernels, DerivativeMatchesFiniteDifferences) {
  const double step = 1e-6;
  for (KernelType t : kAll)
    for (double z = 0.013; z < 0.99; z += 0.0371) {
      const double fd = (kernel_value(t, z + step).w - kernel_value(t, z - step).w) / (2 * step);
      EXPECT_NEAR(kernel_value(t, z).dw_dz, fd, 1e-8) << uhpc::kernel_name(t) << " z=" << z;
    }
}

TEST(Kernels, PositiveAndDecreasingInsideSupport) {
  for (KernelType t : kAll) {
    double previous = kernel_value(t, 0.0).w;
    for (double z = 0.01; z < 1.0; z += 0.01) {
      const double w = kernel_value(t, z).w;
      EXPECT_GT(w, 0.0);
      EXPECT_LT(w, previous);
      previous = w;
    }
  }
}

TEST(Kernels, NamesRoundTripAndUnknownNameIsRejected) {
  for (KernelType t : kAll) EXPECT_EQ(uhpc::kernel_from_name(uhpc::kernel_name(t)), t);
  try {
    uhpc::kernel_from_name("gaussian");
    FAIL() << "expected an exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "unknown kernel 'gaussian', expected one of: cubic_bspline, quartic_spline");
  }
}

}  // namespace
