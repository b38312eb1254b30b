// The SDEL (common/include/uhpc/sdel.hpp): values, the paper's check strains, monotonicity, safety at
// extreme strains, automatic derivatives against finite differences, and the closed-form inverse.
#include <cmath>
#include <limits>

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include "uhpc/sdel.hpp"

namespace {

using uhpc::SdelConstants;

constexpr double kLmac = 0.4064;  // m, panel diameter
const SdelConstants<double> kTable4{1.0, 0.0002, 120.5, 4.1e6};

TEST(Sdel, InitiationStrainByHand) {
  // a = 3, lambda = 1: e_i = A / sqrt(4) = A / 2.
  const SdelConstants<double> c{3.0, 0.002, 1.0, 100.0};
  EXPECT_DOUBLE_EQ(uhpc::sdel_initiation_strain(1.0, c), 0.001);
  // lambda = 0: e_i = A.
  EXPECT_DOUBLE_EQ(uhpc::sdel_initiation_strain(0.0, c), 0.002);
}

TEST(Sdel, DamageByHand) {
  const SdelConstants<double> c{3.0, 0.002, 1.0, 100.0};  // e_i = 0.001 at lambda = 1
  // nu = 1: d = 1/2 exactly at e = e_i.
  EXPECT_DOUBLE_EQ(uhpc::sdel_damage(1.0, 0.001, c), 0.5);
  // e - e_i = ln(3) / (lambda chi): exp(-ln 3) = 1/3, d = 1 / (1 + 1/3) = 3/4.
  EXPECT_NEAR(uhpc::sdel_damage(1.0, 0.001 + std::log(3.0) / 100.0, c), 0.75, 1e-15);
  // e - e_i = -ln(3) / (lambda chi): d = 1 / (1 + 3) = 1/4 (the branch for s > 0).
  EXPECT_NEAR(uhpc::sdel_damage(1.0, 0.001 - std::log(3.0) / 100.0, c), 0.25, 1e-15);
  // nu = e^2, at e = e_i: d = 1 / (1 + e^2).
  const SdelConstants<double> c2{3.0, 0.002, std::exp(2.0), 100.0};
  EXPECT_NEAR(uhpc::sdel_damage(1.0, 0.001, c2), 1.0 / (1.0 + std::exp(2.0)), 1e-15);
}

TEST(Sdel, Table4ValuesAgainstDirectFormula) {
  // Reference values computed independently (Python, the unguarded textbook formula) at
  // l_mic = 4.5 mm, where the direct formula does not overflow.
  const double lambda = 0.0045 / kLmac;
  EXPECT_NEAR(uhpc::sdel_initiation_strain(lambda, kTable4), 1.989018280735505e-4, 1e-18);
  EXPECT_NEAR(uhpc::sdel_damage(lambda, 2.5e-4, kTable4), 0.07785436803004885, 1e-14);
  EXPECT_NEAR(uhpc::sdel_damage(lambda, 3.0e-4, kTable4), 0.4496878330023322, 1e-14);
  EXPECT_NEAR(uhpc::sdel_damage(lambda, 0.0, kTable4), 9.940089123758339e-07, 1e-19);
}

TEST(Sdel, SpecCheckStrainsForHalfDamage) {
  // docs/specification.md: with Table 4, d+ = 0.5 at 3.58e-4 (l_mic = 3.0 mm) and 2.71e-4 (6.5 mm), to the printed
  // digits (half a unit in the last printed place).
  const double e3 = uhpc::sdel_strain_at_damage(uhpc::sdel_lambda(0.0030, kLmac), 0.5, kTable4);
  const double e65 = uhpc::sdel_strain_at_damage(uhpc::sdel_lambda(0.0065, kLmac), 0.5, kTable4);
  EXPECT_NEAR(e3, 3.58e-4, 0.005e-4);
  EXPECT_NEAR(e65, 2.71e-4, 0.005e-4);
  // And the forward law really gives one half there.
  EXPECT_NEAR(uhpc::sdel_damage(uhpc::sdel_lambda(0.0030, kLmac), e3, kTable4), 0.5, 1e-12);
  EXPECT_NEAR(uhpc::sdel_damage(uhpc::sdel_lambda(0.0065, kLmac), e65, kTable4), 0.5, 1e-12);
}

TEST(Sdel, LambdaHelper) {
  EXPECT_DOUBLE_EQ(uhpc::sdel_lambda(3.0, 406.4), 3.0 / 406.4);
  EXPECT_THROW(uhpc::sdel_lambda(0.0, 406.4), std::invalid_argument);
  EXPECT_THROW(uhpc::sdel_lambda(3.0, -1.0), std::invalid_argument);
  EXPECT_THROW(uhpc::sdel_lambda(std::numeric_limits<double>::quiet_NaN(), 1.0), std::invalid_argument);
}

TEST(Sdel, MonotoneInStrain) {
  for (const double l_mic : {0.003, 0.0045, 0.005, 0.0065}) {
    const double lambda = l_mic / kLmac;
    double previous = uhpc::sdel_damage(lambda, -1e-3, kTable4);
    for (int i = 1; i <= 4000; ++i) {
      const double e = -1e-3 + i * 1e-6;  // through the whole transition
      const double d = uhpc::sdel_damage(lambda, e, kTable4);
      ASSERT_GE(d, previous) << "l_mic " << l_mic << " strain " << e;
      ASSERT_GE(d, 0.0);
      ASSERT_LE(d, 1.0);
      previous = d;
    }
  }
}

TEST(Sdel, SmallerCellsDamageLater) {
  // The size effect the law encodes: at a fixed strain in the transition, the larger cell (larger
  // lambda, steeper law, smaller e_i) is more damaged.
  const double e = 3.0e-4;
  EXPECT_LT(uhpc::sdel_damage(0.003 / kLmac, e, kTable4), uhpc::sdel_damage(0.0065 / kLmac, e, kTable4));
}

TEST(Sdel, ResidualDamageAtZeroStrainIsSmallButNotZero) {
  const double lambda = 0.003 / kLmac;
  const double d0 = uhpc::sdel_damage_at_zero_strain(lambda, kTable4);
  const double s0 = std::log(kTable4.nu) + lambda * kTable4.chi * uhpc::sdel_initiation_strain(lambda, kTable4);
  EXPECT_GT(d0, 0.0);
  EXPECT_NEAR(d0, 1.0 / (1.0 + std::exp(s0)), 1e-20);
  EXPECT_LT(d0, 1e-4);
  // The zero-anchored variant starts at 0 exactly and still reaches 1.
  EXPECT_EQ(uhpc::sdel_damage_zero_anchored(lambda, 0.0, kTable4), 0.0);
  EXPECT_NEAR(uhpc::sdel_damage_zero_anchored(lambda, 1e-2, kTable4), 1.0, 1e-15);
}

TEST(Sdel, FiniteAtExtremeStrainsDouble) {
  for (const double l_mic : {0.003, 0.0065, 0.4064}) {
    const double lambda = l_mic / kLmac;
    for (const double e : {-1.0, 0.0, 1e-2, 1.0, -1e6, 1e6}) {
      const double d = uhpc::sdel_damage(lambda, e, kTable4);
      EXPECT_TRUE(std::isfinite(d)) << "strain " << e;
      EXPECT_GE(d, 0.0);
      EXPECT_LE(d, 1.0);
    }
    EXPECT_EQ(uhpc::sdel_damage(lambda, -1.0, kTable4), 0.0);
    EXPECT_EQ(uhpc::sdel_damage(lambda, 1.0, kTable4), 1.0);
  }
}

using Jet6 = ceres::Jet<double, 6>;

// All six inputs as independent variables: a, A, nu, chi, lambda, strain.
Jet6 damage_jet(const double x[6]) {
  const SdelConstants<Jet6> c{Jet6(x[0], 0), Jet6(x[1], 1), Jet6(x[2], 2), Jet6(x[3], 3)};
  return uhpc::sdel_damage(Jet6(x[4], 4), Jet6(x[5], 5), c);
}

double damage_double(const double x[6]) {
  const SdelConstants<double> c{x[0], x[1], x[2], x[3]};
  return uhpc::sdel_damage(x[4], x[5], c);
}

TEST(Sdel, FiniteAtExtremeStrainsJet) {
  for (const double e : {-1.0, 0.0, 1e-2, 1.0}) {
    const double x[6] = {1.0, 0.0002, 120.5, 4.1e6, 0.003 / kLmac, e};
    const Jet6 d = damage_jet(x);
    EXPECT_TRUE(std::isfinite(d.a)) << "strain " << e;
    for (int i = 0; i < 6; ++i) EXPECT_TRUE(std::isfinite(d.v[i])) << "strain " << e << " derivative " << i;
  }
}

TEST(Sdel, JetDerivativesMatchCentralDifferences) {
  // Points in the transition on both sides of d = 1/2 (both branches of the stable logistic), plus a
  // hand-sized set of constants.
  const double points[][6] = {
      {1.0, 0.0002, 120.5, 4.1e6, 0.003 / kLmac, 3.3e-4},   // d about 0.3, s > 0 branch
      {1.0, 0.0002, 120.5, 4.1e6, 0.003 / kLmac, 3.8e-4},   // d about 0.8, s < 0 branch
      {1.0, 0.0002, 120.5, 4.1e6, 0.0065 / kLmac, 2.71e-4}, // d about 0.5
      {3.0, 0.002, 2.0, 100.0, 1.0, 0.0015},
  };
  const char* names[6] = {"a", "A", "nu", "chi", "lambda", "strain"};
  for (const auto& x : points) {
    const Jet6 d = damage_jet(x);
    EXPECT_DOUBLE_EQ(d.a, damage_double(x));
    for (int i = 0; i < 6; ++i) {
      // Relative step: central differences are accurate to O(h^2), far below the 1e-6 tolerance.
      const double h = 1e-5 * std::abs(x[i]);
      double xp[6], xm[6];
      for (int j = 0; j < 6; ++j) xp[j] = xm[j] = x[j];
      xp[i] += h;
      xm[i] -= h;
      const double fd = (damage_double(xp) - damage_double(xm)) / (2.0 * h);
      EXPECT_NEAR(d.v[i], fd, 1e-6 * std::abs(fd)) << "d/d" << names[i] << " at strain " << x[5];
      EXPECT_NE(d.v[i], 0.0) << names[i];
    }
  }
}

TEST(Sdel, InitiationStrainJetDerivative) {
  // de_i/da = -A lambda / (2 (1 + a lambda)^(3/2)), de_i/dA = 1 / sqrt(1 + a lambda).
  const double a = 1.0, A = 0.0002, lambda = 0.01;
  const SdelConstants<Jet6> c{Jet6(a, 0), Jet6(A, 1), Jet6(120.5), Jet6(4.1e6)};
  const Jet6 ei = uhpc::sdel_initiation_strain(Jet6(lambda, 4), c);
  EXPECT_NEAR(ei.v[0], -A * lambda / (2.0 * std::pow(1.0 + a * lambda, 1.5)), 1e-20);
  EXPECT_NEAR(ei.v[1], 1.0 / std::sqrt(1.0 + a * lambda), 1e-15);
  EXPECT_NEAR(ei.v[4], -A * a / (2.0 * std::pow(1.0 + a * lambda, 1.5)), 1e-18);
}

TEST(Sdel, InverseAgreesWithForwardLaw) {
  for (const double l_mic : {0.003, 0.0045, 0.005, 0.0065, 0.05}) {
    const double lambda = l_mic / kLmac;
    for (const double d : {1e-12, 1e-3, 0.1, 0.5, 0.9, 0.999, 1.0 - 1e-9}) {
      const double e = uhpc::sdel_strain_at_damage(lambda, d, kTable4);
      EXPECT_NEAR(uhpc::sdel_damage(lambda, e, kTable4), d, 1e-9 * std::min(d, 1.0 - d) + 1e-15)
          << "l_mic " << l_mic << " d " << d;
    }
  }
  EXPECT_THROW(uhpc::sdel_strain_at_damage(0.01, 0.0, kTable4), std::invalid_argument);
  EXPECT_THROW(uhpc::sdel_strain_at_damage(0.01, 1.0, kTable4), std::invalid_argument);
  EXPECT_THROW(uhpc::sdel_strain_at_damage(0.0, 0.5, kTable4), std::invalid_argument);
}

}  // namespace
