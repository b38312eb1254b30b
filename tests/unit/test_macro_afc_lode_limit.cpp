// The two options that give AFC a third-invariant dependence (docs/physics.md section 4.2): the
// Willam-Warnke Lode factor (AfcOptions::lode) and the principal-stress limit of damaged material
// (AfcOptions::principal_stress_limit), at a single material point.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include <Eigen/Eigenvalues>

#include "materials/afc.hpp"
#include "materials/afc_config.hpp"
#include "materials/afc_strength.hpp"
#include "materials/point_driver.hpp"
#include "afc_point_tests.hpp"
#include "materials/principal_stress_limit.hpp"

namespace uhpc::macro {
namespace {

using namespace afc_test;

AfcParams with_lode() {
  AfcParams p = shipped();
  p.options.lode = LodeDependence::WillamWarnke;
  return p;
}

AfcParams with_limit(PrincipalStressLimit limit) {
  AfcParams p = shipped();
  p.options.principal_stress_limit = limit;
  return p;
}

// (The iterative solver: the closed form loses sqrt(eps) on the repeated principal values of the corner.)
double largest_principal(const Mat3& m) {
  return Eigen::SelfAdjointEigenSolver<Mat3>(m, Eigen::EigenvaluesOnly).eigenvalues()[2];
}

// The deviatoric strength reached at pressure P along a meridian: compress hydrostatically to P, then
// shear without volume change along diag(a, b, c) (a + b + c = 0), quasi-statically. `d_minus_last`:
// d- at the start of the last step (the one its strength used).
struct Reached {
  double q, d_minus_last;
};
Reached meridian_strength(const AfcMaterial& law, double P_target, const Mat3& direction, double d_minus, double d_plus) {
  Driver pt(law, kSpacing);
  pt.state().d_minus = d_minus;
  pt.state().d_plus = d_plus;
  const double mu = mu_at_pressure(law.hydrostat(), P_target);
  for (int i = 1; i <= 50; ++i) pt.volumetric_step_to(mu * i / 50.0, 1e3);
  double last = 0.0;
  for (int i = 0; i < 400; ++i) {
    last = pt.state().d_minus;
    pt.strain_step(2e-5 * direction, 1e3);
  }
  return {von_mises(pt.state().stress), last};
}

Mat3 diag(double a, double b, double c) { return Eigen::Vector3d(a, b, c).asDiagonal(); }

// ---------------------------------------------------------------------------------------------------
// Lode dependence

TEST(AfcLode, WillamWarnkeFactorIsOneOnCompressionPsiOnExtensionAndConvexInBetween) {
  for (const double psi : {0.5, 0.6, 0.8, 1.0}) {
    EXPECT_NEAR(willam_warnke_factor(-1.0, psi), 1.0, 1e-14);
    EXPECT_NEAR(willam_warnke_factor(1.0, psi), psi, 1e-14);
    double last = 1.0 + 1e-15;
    for (int i = 0; i <= 100; ++i) {  // falls monotonically from compression to extension
      const double r = willam_warnke_factor(-1.0 + 2.0 * i / 100.0, psi);
      EXPECT_LE(r, last);
      last = r;
    }
  }
  EXPECT_NEAR(lode_cos3theta(diag(2, -1, -1)), 1.0, 1e-14);  // extension
  EXPECT_NEAR(lode_cos3theta(diag(1, 1, -2)), -1.0, 1e-14);  // compression
  EXPECT_NEAR(lode_cos3theta(diag(1, 0, -1)), 0.0, 1e-14);   // shear
}

TEST(AfcLode, PsiIsTheMohrCoulombRatioOfTheMeridiansSlope) {
  const AfcParams p = shipped();
  // Intact at P = 0: dS/dP = C2 An + C4.
  EXPECT_NEAR(lode_psi(0.0, 0.0, 1.0, p), 3.0 / (3.0 + p.C2_Pa * p.An_1_Pa + p.C4), 1e-14);
  EXPECT_NEAR(lode_psi(-5 * MPa, 0.0, 1.0, p), lode_psi(0.0, 0.0, 1.0, p), 1e-15);  // tension: psi(0)
  // Residual (d- = 1) at 170 MPa: dS/dP = C1 An exp(-An P) + C4.
  const double P = 170 * MPa;
  EXPECT_NEAR(lode_psi(P, 1.0, 1.0, p), 3.0 / (3.0 + p.C1_Pa * p.An_1_Pa * std::exp(-p.An_1_Pa * P) + p.C4), 1e-14);
  EXPECT_NEAR(lode_psi(5000 * MPa, 1.0, 1.0, p), 1.0, 1e-3);  // flat at high pressure: no Lode effect
}

TEST(AfcLode, TriaxialCompressionIsUnchangedAndExtensionOverCompressionIsPsi) {
  const AfcMaterial plain(shipped()), lode(with_lode());
  const Mat3 compression = diag(1, 1, -2), extension = diag(-1, -1, 2);
  for (const double dm : {0.0, 1.0})
    for (const double P : {50 * MPa, 100 * MPa, 300 * MPa}) {
      const Reached c_plain = meridian_strength(plain, P, compression, dm, 1.0);
      const Reached c_lode = meridian_strength(lode, P, compression, dm, 1.0);
      const Reached e_lode = meridian_strength(lode, P, extension, dm, 1.0);
      EXPECT_NEAR(c_lode.q, c_plain.q, 1e-12 * c_plain.q) << P / MPa << " MPa, d- " << dm;
      // Each meridian's last step used its own d- (eq. 36 grows it with the plastic strain): on the
      // extension meridian the strength is S(P, d-) psi(P, d-), on the compressive one S(P, d-).
      const AfcParams& p = lode.params();
      const double e_expected = afc_strength_compression(P, e_lode.d_minus_last, 1.0, p) * lode_psi(P, e_lode.d_minus_last, 1.0, p);
      EXPECT_NEAR(c_lode.q, afc_strength_compression(P, c_lode.d_minus_last, 1.0, p), 1e-9 * c_lode.q);
      EXPECT_NEAR(e_lode.q, e_expected, 1e-9 * e_expected) << P / MPa << " MPa, d- " << dm;
      if (dm == 1.0) {
        EXPECT_NEAR(e_lode.q / c_lode.q, lode_psi(P, 1.0, 1.0, p), 1e-9);
      }
      // Without the option extension is as strong as compression.
      EXPECT_NEAR(meridian_strength(plain, P, extension, dm, 1.0).q, c_plain.q, 1e-9 * c_plain.q);
    }
}

TEST(AfcLode, RubbleInTriaxialExtensionCarriesNoPrincipalTensionWithIt) {
  // d+ = d- = 1 on the extension meridian at 170 MPa: sigma_1 = -P + 2 S r / 3. Without the Lode factor
  // the residual meridian gives tens of MPa of tension; with psi it stays compressive.
  const Mat3 extension = diag(-1, -1, 2);
  const double P = 170 * MPa;
  const double q_plain = meridian_strength(AfcMaterial(shipped()), P, extension, 1.0, 1.0).q;
  const double q_lode = meridian_strength(AfcMaterial(with_lode()), P, extension, 1.0, 1.0).q;
  std::printf("sigma_1 in triaxial extension at 170 MPa, d+ = d- = 1: %.1f MPa without, %.1f MPa with the Lode factor\n",
              (-P + 2.0 * q_plain / 3.0) / MPa, (-P + 2.0 * q_lode / 3.0) / MPa);
  EXPECT_GT(-P + 2.0 * q_plain / 3.0, 30 * MPa);
  EXPECT_LT(-P + 2.0 * q_lode / 3.0, 0.0);
}

TEST(AfcLode, RandomPathsStayInsideTheLodeSurface) {
  const AfcMaterial law(with_lode());
  std::mt19937 rng(4511);
  std::normal_distribution<double> n(0.0, 3e-5);
  std::uniform_real_distribution<double> drift(-1e-5, 4e-5);
  for (int path = 0; path < 300; ++path) {
    Driver pt(law, kSpacing);
    const double d = drift(rng);
    for (int i = 0; i < 100; ++i) {
      Mat3 de;
      for (int a = 0; a < 3; ++a)
        for (int b = a; b < 3; ++b) de(a, b) = de(b, a) = n(rng);
      const double d_minus = pt.state().d_minus;  // the strength of the step uses d- from its start
      pt.strain_step(de + d * Mat3::Identity(), 1e3);
      const AfcMaterial::State& st = pt.state();
      const double P = pressure_of(st.stress);
      const double S = afc_strength(P, d_minus, st.d_plus, 1.0, law.params());
      const double r = willam_warnke_factor(lode_cos3theta(deviator(st.stress)), lode_psi(P, d_minus, 1.0, law.params()));
      ASSERT_LE(von_mises(st.stress), S * r * (1 + 1e-9) + 1.0) << "path " << path << " step " << i;
    }
  }
}

// ---------------------------------------------------------------------------------------------------
// Principal-stress limit

TEST(AfcPrincipalLimit, TheReturnIsTheClosestAdmissibleDeviator) {
  // One active value, the corner, and an admissible deviator left alone.
  const Mat3 one = limit_principal_deviator(diag(6, -2, -4), 2.0);
  EXPECT_NEAR(one(0, 0), 2.0, 1e-12);
  EXPECT_NEAR(one(1, 1), 0.0, 1e-12);
  EXPECT_NEAR(one(2, 2), -2.0, 1e-12);
  const Mat3 corner = limit_principal_deviator(diag(5, 4, -9), 1.0);
  EXPECT_NEAR(corner(0, 0), 1.0, 1e-12);
  EXPECT_NEAR(corner(1, 1), 1.0, 1e-12);
  EXPECT_NEAR(corner(2, 2), -2.0, 1e-12);
  const Mat3 ok = diag(1, 0.5, -1.5);
  EXPECT_EQ(limit_principal_deviator(ok, 1.0), ok);
  // Closest: no admissible deviator on a grid around the answer is nearer to the trial.
  std::mt19937 rng(7);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int k = 0; k < 200; ++k) {
    Mat3 s;
    for (int a = 0; a < 3; ++a)
      for (int b = a; b < 3; ++b) s(a, b) = s(b, a) = n(rng);
    s = deviator(s);
    const double c = 0.2;
    const Mat3 r = limit_principal_deviator(s, c);
    ASSERT_LE(largest_principal(r), c + 1e-14 * s.norm()) << largest_principal(r) - c;  // to round-off
    ASSERT_NEAR(r.trace(), 0.0, 1e-12);
    ASSERT_GE(r.cwiseProduct(s - r).sum(), -1e-14 * s.squaredNorm());  // its work s_new : (s - s_new) >= 0
    for (int t = 0; t < 50; ++t) {
      Mat3 dz;
      for (int a = 0; a < 3; ++a)
        for (int b = a; b < 3; ++b) dz(a, b) = dz(b, a) = 0.05 * n(rng);
      const Mat3 other = r + deviator(dz);
      if (largest_principal(other) <= c) {
        ASSERT_GE((other - s).norm(), (r - s).norm() - 1e-12);
      }
    }
  }
}

TEST(AfcPrincipalLimit, RandomPathsOfFailedMaterialCarryNoPrincipalTension) {
  // d+ = d- = 1 over 10^4 random strain paths (compression, shear, tension, rates up to 1e3 1/s):
  // sigma_1 <= 0 to round-off (1e-9 of the stress), with either limit.
  for (const PrincipalStressLimit limit : {PrincipalStressLimit::UniaxialTensileStrength, PrincipalStressLimit::Tmax}) {
    const AfcMaterial law(with_limit(limit));
    std::mt19937 rng(1000 + static_cast<int>(limit));
    std::normal_distribution<double> n(0.0, 5e-5);
    std::uniform_real_distribution<double> drift(-2e-5, 5e-5), dt(1e-7, 1e2);
    double worst = 0.0;
    for (int path = 0; path < 10000; ++path) {
      Driver pt(law, kSpacing);
      pt.state().d_plus = pt.state().d_minus = 1.0;
      const double d = drift(rng);
      for (int i = 0; i < 20; ++i) {
        Mat3 de;
        for (int a = 0; a < 3; ++a)
          for (int b = a; b < 3; ++b) de(a, b) = de(b, a) = n(rng);
        pt.strain_step(de + d * Mat3::Identity(), dt(rng));
        const Mat3& sig = pt.state().stress;
        const double s1 = largest_principal(sig);
        worst = std::max(worst, s1);
        ASSERT_LE(s1, 1e-9 * sig.norm() + 1e-6) << "path " << path << " step " << i;
      }
    }
    std::printf("largest principal stress over 10^4 paths: %.3e Pa\n", worst);
  }
}

TEST(AfcPrincipalLimit, IntactUniaxialTensionKeepsFtWithTheUniaxialFormAndDropsToTmaxWithTheTmaxForm) {
  for (const PrincipalStressLimit limit : {PrincipalStressLimit::UniaxialTensileStrength, PrincipalStressLimit::Tmax}) {
    AfcParams p = with_limit(limit);
    p.options.tensile_damage = TensileDamage::Off;
    Driver pt(AfcMaterial(p), kSpacing);
    const double de = 1e-7, dt = de / p.reference_strain_rate_1_s;
    double peak = 0.0;
    for (int i = 0; i < 6000; ++i) {
      pt.uniaxial_stress_step(de, dt);
      peak = std::max(peak, pt.state().stress(0, 0));
    }
    const double expected = limit == PrincipalStressLimit::Tmax ? p.Tmax_Pa : afc_uniaxial_tensile_strength(p);
    EXPECT_NEAR(peak, expected, 1e-4 * expected);
  }
  EXPECT_NEAR(afc_uniaxial_tensile_strength(shipped()) / MPa, 15.94, 0.005);
}

TEST(AfcPrincipalLimit, EveryReturnDissipates) {
  const AfcMaterial law(with_limit(PrincipalStressLimit::UniaxialTensileStrength));
  std::mt19937 rng(3);
  std::normal_distribution<double> n(0.0, 5e-5);
  for (int path = 0; path < 500; ++path) {
    Driver pt(law, kSpacing);
    pt.state().d_plus = 0.7;
    for (int i = 0; i < 40; ++i) {
      Mat3 de;
      for (int a = 0; a < 3; ++a)
        for (int b = a; b < 3; ++b) de(a, b) = de(b, a) = n(rng);
      const double before = pt.state().plastic_work;
      pt.strain_step(de + 1e-5 * Mat3::Identity(), 1e3);
      ASSERT_GE(pt.state().plastic_work, before);
    }
  }
}

TEST(AfcPrincipalLimit, NeedsTheCutoffCoupling) {
  AfcParams p = with_limit(PrincipalStressLimit::Tmax);
  p.options.tensile_degradation = TensileDegradation::Split;
  EXPECT_THROW(AfcMaterial{p}, std::invalid_argument);
}

}  // namespace
}  // namespace uhpc::macro
