// The paper's coupling (d+ only through the tensile cutoff Tmax (1 - d+) and eq. 35, docs/physics.md
// section 4.5) at a single material point, on fully failed material and on random strain paths, and
// the two ways failed, opened material takes pressure again (AfcOptions::opened_volume).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include <Eigen/Eigenvalues>

#include "materials/afc.hpp"
#include "materials/afc_config.hpp"
#include "materials/point_driver.hpp"
#include "afc_point_tests.hpp"

namespace uhpc::macro {
namespace {

using namespace afc_test;

// A point with d+ = d- = 1 (both history variables can only stay there).
Driver failed_point(const AfcMaterial& law) {
  Driver pt(law, kSpacing);
  pt.state().d_plus = 1.0;
  pt.state().d_minus = 1.0;
  return pt;
}

TEST(AfcPaperCoupling, IsTheShippedDefault) {
  EXPECT_EQ(AfcOptions{}.tensile_degradation, TensileDegradation::Cutoff);
  EXPECT_EQ(shipped().options.tensile_degradation, TensileDegradation::Cutoff);
}

TEST(AfcPaperCoupling, FailedMaterialInTriaxialCompressionReturnsOntoTheResidualMeridian) {
  // d+ = d- = 1: eq. 33 becomes q = C1 (1 - exp(-An P)) + C4 P (quasi-static, F = 1). Compress
  // hydrostatically to P, then shear along the compressive meridian (axial shortening, lateral
  // stretching, no volume change, so P stays): q must end on that meridian.
  const AfcMaterial law(shipped());
  const AfcParams& p = law.params();
  for (const double P_target : {50 * MPa, 100 * MPa, 300 * MPa}) {
    Driver pt = failed_point(law);
    const double mu = mu_at_pressure(law.hydrostat(), P_target);
    for (int i = 1; i <= 50; ++i) pt.volumetric_step_to(mu * i / 50.0, 1e3);
    const double P = pressure_of(pt.state().stress);
    ASSERT_NEAR(P, P_target, 1e-6 * P_target);
    Mat3 de = Mat3::Zero();
    de(0, 0) = de(1, 1) = 2e-5;
    de(2, 2) = -4e-5;  // q grows by 3G 4e-5 = 2.2 MPa a step while elastic
    for (int i = 0; i < 400; ++i) pt.strain_step(de, 1e3);  // rate far below the reference: F = 1
    const double residual = p.C1_Pa * (1.0 - std::exp(-p.An_1_Pa * P)) + p.C4 * P;
    EXPECT_NEAR(von_mises(pt.state().stress), residual, 1e-9 * residual) << P / MPa << " MPa";
    EXPECT_NEAR(pressure_of(pt.state().stress), P, 1e-6 * P);  // no dilatancy
    const Mat3 s = deviator(pt.state().stress);
    EXPECT_LT(s(2, 2), 0.0);  // on the compressive meridian
    EXPECT_NEAR(s(0, 0), s(1, 1), 1e-9 * residual);
  }
}

TEST(AfcPaperCoupling, UniaxialTensionNeverPullsThePressureBelowTheDamagedCutoff) {
  // Uniaxial strain and uniaxial stress in tension, driven past full damage: at every step
  // P >= -Tmax (1 - d+), and once d+ = 1 nothing tensile is left.
  const AfcMaterial law(shipped());
  const double Tmax = law.params().Tmax_Pa;
  for (const bool uniaxial_stress : {false, true}) {
    Driver pt(law, kSpacing);
    double worst = -1.0;
    for (int i = 0; i < 3000; ++i) {
      if (uniaxial_stress) {
        pt.uniaxial_stress_step(1e-6, 1e-2);
      } else {
        Mat3 de = Mat3::Zero();
        de(0, 0) = 1e-6;
        pt.strain_step(de, 1e-2);
      }
      const double P = pressure_of(pt.state().stress);
      const double cutoff = -Tmax * (1.0 - pt.state().d_plus);
      worst = std::max(worst, (cutoff - P) / Tmax);
      ASSERT_GE(P, cutoff - 1e-9 * Tmax) << "step " << i << (uniaxial_stress ? " (uniaxial stress)" : "");
    }
    EXPECT_LT(worst, 1e-9);
    ASSERT_EQ(pt.state().d_plus, 1.0);
    // Nothing tensile is left: no principal stress above zero.
    const double largest = Eigen::SelfAdjointEigenSolver<Mat3>(pt.state().stress).eigenvalues()[2];
    EXPECT_LE(largest, 1e-9 * Tmax) << (uniaxial_stress ? "uniaxial stress" : "uniaxial strain");
  }
}

// Work per unit reference volume of one step (trapezoid of the stresses at its ends).
double step_work(const Mat3& s0, const Mat3& s1, const Mat3& de, double density_ratio) {
  return 0.5 * (s0 + s1).cwiseProduct(de).sum() / density_ratio;
}

// The volumetric free energy of the cutoff coupling per unit reference volume, exact in the volumetric strain:
// the unloading line's potential, the integral of P dmu / (1 + mu)^2 (= -P dV / V0) from zero pressure
// (the crushing strain mu_p) to mu; below mu_T, where the line meets the cutoff -T, the recoverable
// hydrostat holds P = -T and stores T (V - V_T) / V0 more (it gives it back on closing), the permanent
// opening never goes there (it moves o instead). (Law::stored_energy is the small-strain
// 1/2 sigma : C^-1 : sigma per current volume, a factor 1 + mu / 2 off the line's potential.) The
// deviatoric part, s : s / (4G) per current volume, is hypoelastic: it has no potential in the reference
// volume, so the test books its change step by step at the step's mid volume.
double volumetric_free_energy(const AfcMaterial& law, const AfcMaterial::State& st) {
  const AfcHydrostat& h = law.hydrostat();
  const double K = h.unloading_modulus(st.mu_max);
  const double c = h.loading_pressure(st.mu_max) - K * (1.0 + st.mu_max);  // line: P = K (1 + m) + c
  // In the hydrostat's strain m = rho/rho0 - 1 - o (o the permanent opening): -P dV / V0 = P dm / u^2,
  // u = 1 + m + o, and P = K u + c - K o.
  const double o = st.opening_strain;
  const auto W = [&](double m) { return K * std::log1p(m + o) - (c - K * o) / (1.0 + m + o); };
  const double mu_p = h.crushing_strain(st.mu_max);
  const double T = law.params().Tmax_Pa * (1.0 - st.d_plus);
  const double mu_T = mu_p - T / K;
  const double mu = std::min(st.mu, st.mu_max);  // the hydrostat's strain (on or below the curve)
  double volumetric = W(std::max(mu, mu_T)) - W(mu_p);
  if (mu < mu_T) volumetric += T * (1.0 / (1.0 + mu + o) - 1.0 / (1.0 + mu_T + o));
  return volumetric;
}

// A random symmetric strain increment of size ~amplitude with a volumetric drift.
Mat3 random_increment(std::mt19937& rng, double amplitude, double drift) {
  std::normal_distribution<double> n(0.0, amplitude);
  Mat3 de;
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) de(i, j) = de(j, i) = n(rng);
  de += drift * Mat3::Identity();
  return de;
}

TEST(AfcPaperCoupling, EveryStepOfRandomStrainPathsDissipatesAndTheBookedPartsNeverDecrease) {
  // Mechanical dissipation of a step: the work put in minus the growth of the free energy (both per
  // reference volume) must be >= 0; the parts the law books (plastic, crushing, opening) and both damages
  // must never decrease. The paths mix compression into crushing, shear and tension to full damage. The
  // work is the trapezoid of the stresses at the ends of each of 10 substeps: exact to third order on
  // a smooth path, off by at most |d sigma : d eps| / 2 on a substep that crosses a kink (the cutoff,
  // C7, a return), so their sum is the tolerance; the worst step measured is printed.
  for (const OpenedVolume opened : {OpenedVolume::Recoverable, OpenedVolume::Permanent}) {
    AfcParams p = shipped();
    p.options.opened_volume = opened;
    const AfcMaterial law(p);
    std::mt19937 rng(20261206);
    std::uniform_real_distribution<double> drift(-3e-5, 6e-5);
    double worst = 0.0;
    int yielded = 0, crushed = 0, failed = 0;
    for (int path = 0; path < 200; ++path) {
      Driver pt(law, kSpacing);
      const double d = drift(rng);
      for (int i = 0; i < 300; ++i) {
        // One random increment in 10 equal substeps (the law called for each): the work is the sum of
        // the substeps' trapezoids, its quadrature bound the sum of their |d sigma : d eps| / 2.
        const AfcMaterial::State before = pt.state();
        const Mat3 de = random_increment(rng, 8e-5, d);
        double work = 0.0, kink = 0.0, deviatoric = 0.0;
        for (int k = 0; k < 10; ++k) {
          const Mat3 s0 = pt.state().stress;
          const double r0 = pt.density_ratio();
          pt.strain_step(0.1 * de, 1e-7);
          const double rho_mid = 0.5 * (r0 + pt.density_ratio());
          work += step_work(s0, pt.state().stress, 0.1 * de, rho_mid);
          kink += 0.5 * std::fabs((pt.state().stress - s0).cwiseProduct(0.1 * de).sum()) / rho_mid;
          const Mat3 a = deviator(s0), b = deviator(pt.state().stress);
          deviatoric += (b.squaredNorm() - a.squaredNorm()) / (4.0 * law.params().shear_modulus_Pa) / rho_mid;
        }
        const AfcMaterial::State& after = pt.state();
        const double stored = volumetric_free_energy(law, after) - volumetric_free_energy(law, before) + deviatoric;
        const double dissipation = work - stored;
        worst = std::min(worst, dissipation + kink);
        // (1e-4 J/m^3: the round-off of the potential's terms, of size K ~ 2e10 Pa)
        ASSERT_GE(dissipation, -kink - 1e-4) << "path " << path << ", step " << i;
        ASSERT_GE(after.plastic_work, before.plastic_work);
        ASSERT_GE(after.crushing_work, before.crushing_work);
        ASSERT_GE(after.opening_work, before.opening_work);
        ASSERT_GE(after.d_plus, before.d_plus);
        ASSERT_GE(after.d_minus, before.d_minus);
      }
      yielded += pt.state().plastic_strain > 0.0;
      crushed += pt.state().crushing_work > 0.0;
      failed += pt.state().d_plus > 0.999;
    }
    std::printf("%s: worst step dissipation + |d sigma : d eps| / 2: %.3e J/m^3; of 200 paths %d yielded, %d crushed, %d failed in tension\n",
                opened == OpenedVolume::Permanent ? "permanent" : "recoverable", worst, yielded, crushed, failed);
    EXPECT_GT(yielded, 50);
    EXPECT_GT(crushed, 20);
    EXPECT_GT(failed, 20);
  }
}

// ---------------------------------------------------------------------------------------------------
// Opened volume

TEST(AfcOpenedVolume, PermanentOpeningCarriesPressureAtOnceOnRecompression) {
  // A fully damaged point opened by 5 % and pushed back: with the permanent opening the pressure rises
  // from the first recompression step along the unloading line (K_e for an uncrushed point); with the
  // recoverable hydrostat it stays zero until the point is back at its intact density.
  for (const OpenedVolume opened : {OpenedVolume::Recoverable, OpenedVolume::Permanent}) {
    AfcParams p = shipped();
    p.options.opened_volume = opened;
    const AfcMaterial law(p);
    const double Ke = law.hydrostat().elastic_bulk_modulus();
    Driver pt(law, kSpacing);
    pt.state().d_plus = 1.0;
    for (int i = 1; i <= 50; ++i) pt.volumetric_step_to(-0.05 * i / 50.0, 1.0);
    EXPECT_EQ(pressure_of(pt.state().stress), 0.0);
    EXPECT_TRUE(law.stress_free(pt.state(), pt.density_ratio()));
    const double mu_open = pt.density_ratio() - 1.0;
    pt.volumetric_step_to(mu_open + 1e-4, 1.0);
    const double P = pressure_of(pt.state().stress);
    if (opened == OpenedVolume::Permanent) {
      EXPECT_NEAR(pt.state().opening_strain, -0.05, 1e-12);
      EXPECT_NEAR(P, Ke * 1e-4, 1e-9 * Ke * 1e-4);
      EXPECT_FALSE(law.stress_free(pt.state(), pt.density_ratio()));
      EXPECT_NEAR(law.moduli(pt.state()).bulk_Pa, (1.0 + mu_open + 1e-4) * Ke, 1e-12 * Ke);
    } else {
      EXPECT_EQ(P, 0.0);
      EXPECT_TRUE(law.stress_free(pt.state(), pt.density_ratio()));
    }
  }
}

TEST(AfcOpenedVolume, AnExpandingFailedPointKeepsTheWaveSpeedOfTheClosedMaterial) {
  // Ejecta: a fully failed point, crushed first (mu_p > 0), then expanded to 1000 times its volume
  // through the law's update. It is stress-free throughout and its wave speed stays that of the closed
  // material (finite, never growing with the volume), with either opened volume.
  for (const OpenedVolume opened : {OpenedVolume::Recoverable, OpenedVolume::Permanent}) {
    AfcParams p = shipped();
    p.options.opened_volume = opened;
    const AfcMaterial law(p);
    Driver pt(law, kSpacing);
    for (int i = 1; i <= 40; ++i) pt.volumetric_step_to(0.06 * i / 40.0, 1e-6);  // crushing
    ASSERT_GT(law.hydrostat().crushing_strain(pt.state().mu_max), 0.01);
    pt.state().d_plus = 1.0;
    double c_closed = 0.0;
    for (int i = 1; i <= 200; ++i) {
      const double ratio = std::pow(1e-3 / 1.06, i / 200.0) * 1.06;  // rho/rho0 from 1.06 down to 1e-3
      pt.volumetric_step_to(ratio - 1.0, 1e-6);
      if (!law.stress_free(pt.state(), pt.density_ratio())) continue;
      const double c = law.wave_speed(pt.state(), pt.density_ratio());
      ASSERT_TRUE(std::isfinite(c)) << "rho/rho0 " << pt.density_ratio();
      if (c_closed == 0.0) c_closed = c;
      ASSERT_EQ(c, c_closed) << "rho/rho0 " << pt.density_ratio();
    }
    EXPECT_GT(c_closed, 0.0);
    EXPECT_TRUE(law.stress_free(pt.state(), pt.density_ratio()));
  }
}

TEST(AfcOpenedVolume, PermanentOpeningBooksTheCutoffWorkAndNeverPullsBelowTheCutoff) {
  // d+ held at 0.5 (T = Tmax / 2): open hydrostatically by 5 %, then close by 2 %. The work put in equals
  // the stored energy plus the booked opening work (the books close), the pressure never goes below
  // -T, and reloading starts from -T at once.
  AfcParams p = shipped();
  p.options.opened_volume = OpenedVolume::Permanent;
  p.options.tensile_damage = TensileDamage::Off;
  const AfcMaterial law(p);
  const double T = 0.5 * p.Tmax_Pa;
  Driver pt(law, kSpacing);
  pt.state().d_plus = 0.5;
  double work = 0.0;
  const auto to = [&](double mu) {
    const Mat3 s0 = pt.state().stress;
    const double r0 = pt.density_ratio();
    pt.volumetric_step_to(mu, 1.0);
    const double de = -std::log(pt.density_ratio() / r0) / 3.0;
    work += step_work(s0, pt.state().stress, de * Mat3::Identity(), 0.5 * (r0 + pt.density_ratio()));
    ASSERT_GE(pressure_of(pt.state().stress), -T * (1 + 1e-12));
  };
  for (int i = 1; i <= 2000; ++i) to(-0.05 * i / 2000.0);
  EXPECT_NEAR(pressure_of(pt.state().stress), -T, 1e-9 * T);
  const double stored = law.stored_energy(pt.state()) / pt.density_ratio();
  EXPECT_NEAR(work, stored + pt.state().opening_work, 1e-4 * work);
  EXPECT_GT(pt.state().opening_work, 0.9 * work);
  const double mu_open = pt.density_ratio() - 1.0;
  to(mu_open + 1e-5);
  EXPECT_NEAR(pressure_of(pt.state().stress), -T + law.hydrostat().elastic_bulk_modulus() * 1e-5, 1e-6 * T);
}

}  // namespace
}  // namespace uhpc::macro
