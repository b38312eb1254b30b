// The AFC concrete model with SDEL damage at a single material point (docs/physics.md section 4), with the
// shipped constants (data/afc_uhpc.json, data/sdel_paper.json): hydrostat through elastic, crushing and
// locking and back; strength surfaces and rate factor; d- (eq. 36) and d+ (SDEL) evolution.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <Eigen/Eigenvalues>

#include "materials/afc.hpp"
#include "materials/afc_config.hpp"
#include "materials/afc_strength.hpp"
#include "materials/point_driver.hpp"

namespace uhpc::macro {
namespace {

// As shipped: the effective tensile strain drives the SDEL, d+ acts through the cutoff and eq. 35.
AfcParams paper_params() {
  return load_afc_params(UHPC_DATA_DIR "/afc_uhpc.json", UHPC_DATA_DIR "/sdel_paper.json");
}

// The paper's AFC coupling as docs/physics.md section 4 states it (d+ in the cutoff and eq. 35) with the
// Mazars strain of the summed total strain: the model of the earlier releases, kept as options.
AfcParams cutoff_mazars_params() {
  AfcParams p = paper_params();
  p.options.tensile_degradation = TensileDegradation::Cutoff;
  p.strain_measure = TensileStrainMeasure::Mazars;
  return p;
}

constexpr double kSpacing = 0.003;  // h_I = 3 mm, the paper's centre spacing
constexpr double MPa = 1e6;

using Driver = PointDriver<AfcMaterial>;

Mat3 simple_shear(double dgamma) {
  Mat3 de = Mat3::Zero();
  de(0, 1) = de(1, 0) = 0.5 * dgamma;
  return de;
}

// ---------------------------------------------------------------------------------------------------
// Hydrostat

TEST(AfcHydrostat, LoadingCurveIsContinuousWithTheStatedPieces) {
  const AfcParams p = paper_params();
  const AfcHydrostat h(p);
  const double Ke = p.C6_Pa / p.C7;
  EXPECT_DOUBLE_EQ(h.elastic_bulk_modulus(), Ke);
  EXPECT_NEAR(h.loading_pressure(p.C7), p.C6_Pa, 1e-6);
  EXPECT_NEAR(h.loading_pressure(p.C7 + 1e-12), p.C6_Pa, 1.0);
  EXPECT_NEAR(h.loading_pressure(p.C9 * (1 + 1e-14)), h.locking_pressure(), 10.0);
  const double x = 0.03;
  EXPECT_NEAR(h.loading_pressure(p.C7 + x), p.C6_Pa + p.K1_Pa * x + p.K2_Pa * x * x + p.K3_Pa * x * x * x, 1e-3);
  EXPECT_NEAR(h.loading_pressure(p.C9 + 0.01), h.locking_pressure() + p.C8_Pa * 0.01, 1e-3);
  EXPECT_DOUBLE_EQ(h.unloading_modulus(0.5 * p.C7), Ke);
  EXPECT_DOUBLE_EQ(h.unloading_modulus(p.C9 + 0.01), p.C8_Pa);
  const double mid = 0.5 * (p.C7 + p.C9);
  EXPECT_NEAR(h.unloading_modulus(mid), 0.5 * (Ke + p.C8_Pa), 1e-6 * Ke);
}

TEST(AfcHydrostat, PathThroughCrushingAndLockingAndBack) {
  const AfcMaterial law(paper_params());
  const AfcParams& p = law.params();
  const AfcHydrostat& h = law.hydrostat();
  Driver pt(law, kSpacing);
  const auto P = [&] { return pressure_of(pt.state().stress); };
  const double dt = 1.0;

  // Loading along the curve through elastic and crushing.
  for (int i = 1; i <= 500; ++i) {
    const double mu = 0.05 * i / 500.0;
    pt.volumetric_step_to(mu, dt);
    ASSERT_NEAR(P(), h.loading_pressure(mu), 1e-9 * h.loading_pressure(mu) + 1e-3) << mu;
    ASSERT_LT(von_mises(pt.state().stress), 1e-6);  // a hydrostatic path stays hydrostatic
  }
  EXPECT_NEAR(pt.state().mu_max, 0.05, 1e-15);

  // Unloading: a straight line anchored at the point where loading stopped, modulus K_u(F).
  const double F = (0.05 - p.C7) / (p.C9 - p.C7);
  const double Ku = p.C6_Pa / p.C7 + F * (p.C8_Pa - p.C6_Pa / p.C7);
  const double P_top = h.loading_pressure(0.05);
  pt.volumetric_step_to(0.045, dt);
  const double P1 = P();
  pt.volumetric_step_to(0.040, dt);
  EXPECT_NEAR((P1 - P()) / 0.005, Ku, 1e-9 * Ku);
  EXPECT_NEAR(P(), P_top + Ku * (0.040 - 0.05), 1e-6 * P_top);
  // Zero pressure at the crushing strain; then tension along the same line down to the cutoff.
  const double mu_p = 0.05 - P_top / Ku;
  EXPECT_NEAR(pt.state().crushing_strain, mu_p, 1e-14);
  pt.volumetric_step_to(mu_p, dt);
  EXPECT_NEAR(P(), 0.0, 1e-6 * P_top);
  pt.volumetric_step_to(mu_p - 1e-4, dt);
  // (down to the damaged cutoff -Tmax (1 - d+) of the default coupling)
  EXPECT_NEAR(P(), std::max(-Ku * 1e-4, -p.Tmax_Pa * (1 - pt.state().d_plus)), 1e-6 * P_top);

  // Reloading follows the same line back to the curve, then the curve again (continuity).
  pt.volumetric_step_to(0.05, dt);
  EXPECT_NEAR(P(), P_top, 1e-6 * P_top);
  pt.volumetric_step_to(0.06, dt);
  EXPECT_NEAR(P(), h.loading_pressure(0.06), 1e-9 * P_top);

  // Locking, and unloading from it with C8.
  for (int i = 1; i <= 100; ++i) pt.volumetric_step_to(0.06 + 0.06 * i / 100.0, dt);
  EXPECT_NEAR(P(), h.locking_pressure() + p.C8_Pa * (0.12 - p.C9), 1e-9 * P());
  const double P_lock = P();
  pt.volumetric_step_to(0.119, dt);
  EXPECT_NEAR((P_lock - P()) / 0.001, p.C8_Pa, 1e-6 * p.C8_Pa);
  EXPECT_EQ(pt.state().plastic_strain, 0.0);
}

TEST(AfcHydrostat, TensionIsElasticUpToTheCutoff) {
  for (const OpenedVolume opened : {OpenedVolume::Recoverable, OpenedVolume::Permanent}) {
    AfcParams p = paper_params();
    p.options.tensile_damage = TensileDamage::Off;
    p.options.opened_volume = opened;
    Driver pt(AfcMaterial(p), kSpacing);
    const double Ke = p.C6_Pa / p.C7;
    pt.volumetric_step_to(-1e-4, 1.0);
    EXPECT_NEAR(pressure_of(pt.state().stress), -Ke * 1e-4, 1e-9 * Ke * 1e-4);
    pt.volumetric_step_to(-1e-3, 1.0);  // K_e mu = -22 MPa: cut off at -Tmax
    EXPECT_DOUBLE_EQ(pressure_of(pt.state().stress), -p.Tmax_Pa);
    pt.volumetric_step_to(-1e-4, 1.0);
    if (opened == OpenedVolume::Recoverable) {  // back on the line (cracks close)
      EXPECT_NEAR(pressure_of(pt.state().stress), -Ke * 1e-4, 1e-9 * Ke * 1e-4);
    } else {  // the opening past the cutoff, -1e-3 + Tmax / K_e, is kept: the point is now compressed
      const double opening = -1e-3 + p.Tmax_Pa / Ke;
      EXPECT_NEAR(pt.state().opening_strain, opening, 1e-12);
      EXPECT_NEAR(pressure_of(pt.state().stress), Ke * (-1e-4 - opening), 1e-6 * Ke * 1e-4);
    }
  }
}

TEST(AfcHydrostat, TensileCutoffFollowsTheSdelDamage) {
  const AfcMaterial law(cutoff_mazars_params());
  Driver pt(law, kSpacing);
  // Isotropic stretch e in each direction: Mazars strain sqrt(3) e.
  const double e = 2.5e-4;
  pt.strain_step(e * Mat3::Identity(), 1.0);
  const double d = law.sdel_damage(std::sqrt(3.0) * e, kSpacing);
  EXPECT_NEAR(pt.state().tensile_strain_max, std::sqrt(3.0) * e, 1e-15);
  EXPECT_DOUBLE_EQ(pt.state().d_plus, d);
  EXPECT_GT(d, 0.3);
  EXPECT_LT(d, 0.99);
  EXPECT_NEAR(pressure_of(pt.state().stress), -law.params().Tmax_Pa * (1 - d), 1e-12 * law.params().Tmax_Pa);
}

TEST(AfcHydrostat, CrushingDissipationIsTheAreaOfTheCycle) {
  const AfcMaterial law(paper_params());
  const AfcHydrostat& h = law.hydrostat();
  Driver pt(law, kSpacing);
  // Load to mu = 0.08 and unload to zero pressure, adding up the work of the pressure per reference
  // volume, P dmu / (1 + mu)^2 (trapezoid), independently of the law's own bookkeeping.
  double work = 0.0, mu_prev = 0.0, P_prev = 0.0;
  const auto go = [&](double mu) {
    pt.volumetric_step_to(mu, 1.0);
    const double P = pressure_of(pt.state().stress);
    work += 0.5 * (P_prev / ((1 + mu_prev) * (1 + mu_prev)) + P / ((1 + mu) * (1 + mu))) * (mu - mu_prev);
    mu_prev = mu, P_prev = P;
  };
  const int n = 20000;
  for (int i = 1; i <= n; ++i) go(0.08 * i / n);
  const double mu_p = h.crushing_strain(0.08);
  for (int i = 1; i <= n; ++i) go(0.08 + (mu_p - 0.08) * i / n);
  EXPECT_NEAR(pressure_of(pt.state().stress), 0.0, 1e-3);
  EXPECT_GT(work, 1e6);  // J/m^3
  EXPECT_NEAR((law.dissipation(pt.state()).plastic + law.dissipation(pt.state()).crushing), work, 1e-6 * work);
}

TEST(AfcHydrostat, WaveSpeedUsesTheCurrentTangent) {
  AfcParams p = paper_params();
  const AfcMaterial law(p);
  const double G = p.shear_modulus_Pa, rho0 = p.density_kg_m3, Ke = p.C6_Pa / p.C7;
  AfcMaterial::State s;
  EXPECT_DOUBLE_EQ(law.wave_speed(s, 1.0), std::sqrt((Ke + 4.0 / 3.0 * G) / rho0));
  // On the crushing curve: K = rho dP/drho = (1 + mu) dP/dmu.
  const double mu = 0.03, slope = law.hydrostat().loading_slope(mu);
  s.mu = s.mu_max = mu;
  const double c = std::sqrt(((1 + mu) * slope + 4.0 / 3.0 * G) / (rho0 * (1 + mu)));
  EXPECT_NEAR(law.wave_speed(s, 1 + mu), c, 1e-12 * c);
  EXPECT_LT(slope, Ke);
  // Below mu_max: the unloading modulus.
  const double Ku = law.hydrostat().unloading_modulus(mu), m2 = 0.02;
  EXPECT_NEAR(law.wave_speed(s, 1 + m2), std::sqrt(((1 + m2) * Ku + 4.0 / 3.0 * G) / (rho0 * (1 + m2))), 1e-9);
  // The moduli are the tangent: the crushing slope on the curve, K_u below it.
  EXPECT_NEAR(law.moduli(s).bulk_Pa, (1 + mu) * slope, 1e-6);
  AfcMaterial::State below = s;
  below.mu = m2;
  EXPECT_NEAR(law.moduli(below).bulk_Pa, (1 + m2) * Ku, 1e-6);
  EXPECT_EQ(law.moduli(s).shear_Pa, G);
  p.options.wave_speed_from_unloading_modulus = true;
  EXPECT_NEAR(AfcMaterial(p).wave_speed(s, 1 + mu), std::sqrt(((1 + mu) * Ku + 4.0 / 3.0 * G) / (rho0 * (1 + mu))), 1e-9);
}

TEST(AfcHydrostat, AnOpenFullyFailedPointHasTheWaveSpeedOfTheClosedMaterial) {
  // The hydrostat of rho / rho0 (the permanent opening's case is in test_macro_afc_failed.cpp).
  AfcParams p = paper_params();
  p.options.opened_volume = OpenedVolume::Recoverable;
  const AfcMaterial law(p);
  const double c0 = std::sqrt((p.C6_Pa / p.C7 + 4.0 / 3.0 * p.shear_modulus_Pa) / p.density_kg_m3);
  AfcMaterial::State s;
  s.d_plus = 0.5;  // not failed: the speed at the current (lower) density is higher
  EXPECT_GT(law.wave_speed(s, 0.5), 1.1 * c0);
  s.d_plus = 1.0;  // failed and open (stress-free): it resists nothing until it closes back to rho0
  EXPECT_DOUBLE_EQ(law.wave_speed(s, 0.5), c0);
  EXPECT_DOUBLE_EQ(law.wave_speed(s, 1e-3), c0);  // an ejected fragment at 1e3 V0
  const double mu = 0.01;                          // closed again: the current tangent
  EXPECT_DOUBLE_EQ(law.wave_speed(s, 1 + mu), law.wave_speed(AfcMaterial::State{}, 1 + mu));
}

// ---------------------------------------------------------------------------------------------------
// Strength surfaces and rate factor

TEST(AfcStrength, BranchesMeetAtZeroPressureAndTheTensileStrengthVanishesAtFullDamage) {
  const AfcParams p = paper_params();
  const double dC = p.C1_Pa - p.C2_Pa;
  EXPECT_NEAR(afc_strength(0.0, 0.0, 0.0, 1.0, p), dC, 1e-6);
  EXPECT_NEAR(afc_strength(-1e-9, 0.0, 0.0, 1.0, p), dC, 1e-3);
  EXPECT_NEAR(afc_strength(-0.5 * p.Tmax_Pa, 0.0, 0.0, 1.0, p), 0.5 * dC, 1e-6);
  EXPECT_NEAR(afc_strength(-0.25 * p.Tmax_Pa, 0.5, 0.5, 1.0, p), 0.5 * dC * 0.5, 1e-6);
  EXPECT_EQ(afc_strength(-p.Tmax_Pa, 0.0, 0.0, 1.0, p), 0.0);
  // d+ -> 1: the 0/0 of eq. 35 is guarded: finite and zero (or the limit of the ratio in [0, 1]).
  for (double dp : {1.0, 1.0 - 1e-17, 1.0 - 1e-14}) {
    const double s = afc_strength(-1e-30, 0.0, dp, 1.0, p);
    EXPECT_TRUE(std::isfinite(s)) << dp;
    EXPECT_GE(s, 0.0);
    EXPECT_LE(s, dC);
  }
  EXPECT_EQ(afc_strength(-1.0, 0.0, 1.0, 1.0, p), 0.0);
  // Compression: eq. 33 with d-.
  const double P = 100 * MPa;
  EXPECT_NEAR(afc_strength(P, 0.3, 0.9, 1.0, p),
              p.C1_Pa - (p.C2_Pa + dC * 0.3) * std::exp(-p.An_1_Pa * P) + p.C4 * P, 1e-6);
}

TEST(AfcStrength, C5CapsTheStrengthOnlyWhenAskedTo) {
  AfcParams p = paper_params();
  const double P = 2000 * MPa;  // eq. 33 is about 955 MPa here, above C5 = 792.88 MPa
  EXPECT_GT(afc_strength(P, 0, 0, 1.0, p), p.C5_Pa);
  p.options.cap_strength_with_c5 = true;
  EXPECT_DOUBLE_EQ(afc_strength(P, 0, 0, 1.0, p), p.C5_Pa);
  EXPECT_DOUBLE_EQ(afc_strength(P, 0, 0, 1.2, p), 1.2 * p.C5_Pa);
  EXPECT_NEAR(afc_strength(10 * MPa, 0, 0, 1.0, p), afc_strength(10 * MPa, 0, 0, 1.0, paper_params()), 1e-9);
}

TEST(AfcStrength, RateFactorIsEq34WithAFloorOfOne) {
  AfcParams p = paper_params();
  EXPECT_DOUBLE_EQ(afc_rate_factor(1e-4, p), 1.0);
  EXPECT_DOUBLE_EQ(afc_rate_factor(1e-7, p), 1.0);
  EXPECT_DOUBLE_EQ(afc_rate_factor(0.0, p), 1.0);
  EXPECT_NEAR(afc_rate_factor(100.0, p), 1.0 + 0.01 * std::log(1e6), 1e-14);
  p.options.rate_factor_floor = 0.0;
  EXPECT_NEAR(afc_rate_factor(1e-7, p), 1.0 + 0.01 * std::log(1e-3), 1e-14);
  EXPECT_EQ(afc_rate_factor(0.0, p), 0.0);
  // Effective deviatoric rate of simple shear: gamma_dot / sqrt(3).
  EXPECT_NEAR(effective_deviatoric_rate(simple_shear(2e-3), 1e-3), 2.0 / std::sqrt(3.0), 1e-14);
  EXPECT_EQ(effective_deviatoric_rate(1e-3 * Mat3::Identity(), 1e-3), 0.0);
}

TEST(AfcStrength, ShearAtZeroPressureYieldsAtTheRateScaledStrength) {
  const AfcParams p = paper_params();
  const double dC = p.C1_Pa - p.C2_Pa;
  for (double gamma_dot : {1e-5, 1.0, 1e3}) {
    Driver pt(AfcMaterial(p), kSpacing);
    const double dg = 1e-5, dt = dg / gamma_dot;
    for (int i = 0; i < 600; ++i) pt.strain_step(simple_shear(dg), dt);
    const double F = std::max(1.0, 1.0 + p.C3 * std::log(gamma_dot / std::sqrt(3.0) / p.reference_strain_rate_1_s));
    EXPECT_GT(pt.state().plastic_strain, 0.0);
    // The strength surfaces bound the effective stress (with the split, the solver gets less tension).
    EXPECT_NEAR(von_mises(pt.state().effective_stress), F * dC, 1e-9 * dC) << gamma_dot;
    EXPECT_EQ(pt.state().d_minus, 0.0);  // P = 0: eq. 36 does not accumulate
  }
}

// ---------------------------------------------------------------------------------------------------
// Uniaxial stress paths

TEST(AfcUniaxial, CompressionIsElasticWithE43300ThenPeaksAndSoftens) {
  const AfcParams p = paper_params();
  Driver pt(AfcMaterial(p), kSpacing);
  const double de = -2e-6, dt = 2e-6 / 1e-4;  // axial rate 1e-4 1/s
  const double K = p.C6_Pa / p.C7, G = p.shear_modulus_Pa, E = 9 * K * G / (3 * K + G);
  pt.uniaxial_stress_step(de, dt);
  pt.uniaxial_stress_step(de, dt);
  EXPECT_NEAR(pt.state().stress(0, 0) / pt.total_strain()(0, 0), E, 2e-4 * E);
  double peak = 0.0;
  for (int i = 0; i < 4000; ++i) {
    pt.uniaxial_stress_step(de, dt);
    peak = std::max(peak, -pt.state().stress(0, 0));
    ASSERT_LE(std::abs(pt.state().stress(1, 1)), 1e-3);
    ASSERT_LE(std::abs(pt.state().stress(2, 2)), 1e-3);
  }
  EXPECT_GT(peak, 190 * MPa);
  EXPECT_LT(-pt.state().stress(0, 0), 0.95 * peak);  // softening by d-
  EXPECT_GT(pt.state().d_minus, 0.0);
  EXPECT_GT(pt.state().plastic_strain, 0.0);
}

TEST(AfcUniaxial, TensionWithTheCutoffCouplingPeaksWhereTheElasticLineMeetsTheDamagedStrength) {
  const AfcParams p = cutoff_mazars_params();
  const AfcMaterial law(p);
  Driver pt(law, kSpacing);
  const double de = 1e-7, dt = de / 1e-4;
  double peak = 0.0, d_prev = 0.0;
  for (int i = 0; i < 6000; ++i) {
    pt.uniaxial_stress_step(de, dt);
    peak = std::max(peak, pt.state().stress(0, 0));
    ASSERT_GE(pt.state().d_plus, d_prev);
    d_prev = pt.state().d_plus;
    // Mazars strain in uniaxial tension is the axial strain; d+ is the SDEL of its history maximum.
    ASSERT_NEAR(pt.state().tensile_strain_max, pt.total_strain()(0, 0), 1e-15);
    ASSERT_NEAR(pt.state().d_plus, law.sdel_damage(pt.total_strain()(0, 0), kSpacing), 1e-12);
  }
  // Independent: uniaxial tension yields at q = 3 T dC / (3 T + dC) (eq. 35 with P = -q/3), T = Tmax (1 - d+(e));
  // the peak is where the elastic line E e meets it.
  const double K = p.C6_Pa / p.C7, G = p.shear_modulus_Pa, E = 9 * K * G / (3 * K + G), dC = p.C1_Pa - p.C2_Pa;
  const auto strength = [&](double e) {
    const double T = p.Tmax_Pa * (1 - law.sdel_damage(e, kSpacing));
    return 3 * T * dC / (3 * T + dC);
  };
  double lo = 0.0, hi = 1e-3;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (E * mid < strength(mid) ? lo : hi) = mid;
  }
  const double expected = E * lo;
  EXPECT_LT(expected, 15.0 * MPa);  // the SDEL damages the point before eq. 35's 15.9 MPa
  EXPECT_NEAR(peak, expected, 0.01 * MPa);
  EXPECT_GT(pt.state().d_plus, 0.9);
}

// Uniaxial tension to full damage, then compression with the lateral strains held (uniaxial strain; in
// uniaxial stress a cracked point's lateral strains are not unique): d+ and the history strain keep
// their maxima, the cracked point carries compression again once its volume is back (the crack closes),
// and a triaxial stretch at d+ = 1 meets no tension at all.
void tension_to_full_damage_and_back(const AfcParams& p) {
  const AfcMaterial law(p);
  Driver pt(law, kSpacing);
  const double dt = 1.0;
  for (int i = 0; i < 400; ++i) pt.uniaxial_stress_step(5e-6, dt);  // to 2e-3
  EXPECT_EQ(pt.state().d_plus, 1.0);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) EXPECT_TRUE(std::isfinite(pt.state().stress(r, c)));
  EXPECT_NEAR(pt.state().stress(0, 0), 0.0, 1e-3);
  const double kappa = pt.state().tensile_strain_max;
  Mat3 closing = Mat3::Zero();
  closing(0, 0) = -5e-6;
  for (int i = 0; i < 100; ++i) pt.strain_step(closing, dt);
  EXPECT_GT(pt.state().mu, 0.0);
  EXPECT_EQ(pt.state().d_plus, 1.0);
  EXPECT_EQ(pt.state().tensile_strain_max, kappa);
  // Compression is carried again, elastically: in uniaxial strain sigma_xx = -(K_e + 4G/3) mu to first
  // order in mu, K_e = C6/C7 (-23.33 and -23.32 MPa measured for both parameter sets at mu = 4.99e-4,
  // against 23.31 MPa; 1 % admits the hydrostat's second order). The bound was -10 MPa and then -5 MPa with
  // no reason given; this asserts the value the closed crack must carry.
  const double uniaxial_modulus = p.C6_Pa / p.C7 + 4.0 / 3.0 * p.shear_modulus_Pa;
  const double closed = -uniaxial_modulus * pt.state().mu;
  std::printf("closed again: sigma_xx %.4f MPa, -(K_e + 4G/3) mu = %.4f MPa (mu %.3e)\n",
              pt.state().stress(0, 0) / MPa, closed / MPa, pt.state().mu);
  EXPECT_NEAR(pt.state().stress(0, 0), closed, 0.01 * std::abs(closed));
  EXPECT_LT(pt.state().stress(0, 0), -20 * MPa);
  for (int i = 0; i < 600; ++i) {
    pt.strain_step(Mat3::Identity() * 5e-6, dt);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) ASSERT_TRUE(std::isfinite(pt.state().stress(r, c)));
  }
  EXPECT_GE(pressure_of(pt.state().stress), 0.0);
  EXPECT_LT(von_mises(pt.state().stress), 1e-3);
  EXPECT_TRUE(law.stress_free(pt.state(), pt.density_ratio()));
}

TEST(AfcUniaxial, TensionToFullDamageStaysFiniteAndDamageNeverHeals) {
  tension_to_full_damage_and_back(paper_params());
  tension_to_full_damage_and_back(cutoff_mazars_params());
}

TEST(AfcDamage, SdelDependsOnTheParticleSpacing) {
  const AfcParams p = paper_params();
  const AfcMaterial law(p);
  for (double h : {0.003, 0.0065}) {
    Driver pt(law, h);
    pt.strain_step(Mat3::Identity() * 0.0, 1.0);
    Mat3 de = Mat3::Zero();
    de(0, 0) = 3e-4;
    pt.strain_step(de, 1.0);
    EXPECT_DOUBLE_EQ(pt.state().d_plus, uhpc::sdel_damage(h / p.l_mac_m, pt.state().tensile_strain_max, p.sdel)) << h;
    // Uniaxial strain is all tensile, so the effective measure is the strain itself, up to the
    // hydrostat's finite volumetric strain mu = rho/rho0 - 1 (second order in the strain).
    EXPECT_NEAR(pt.state().tensile_strain_max, 3e-4, 3e-4 * 3e-4) << h;
  }
  // The zero-anchored option starts at 0.
  AfcParams z = p;
  z.options.sdel_zero_anchored = true;
  Driver pt(AfcMaterial(z), 0.003);
  pt.strain_step(Mat3::Zero(), 1.0);
  EXPECT_EQ(pt.state().d_plus, 0.0);
  Driver paper(law, 0.003);
  paper.strain_step(Mat3::Zero(), 1.0);
  EXPECT_GT(paper.state().d_plus, 0.0);
  EXPECT_LT(paper.state().d_plus, 1e-4);
  Driver no_spacing(law, 0.0);  // the SDEL needs h_I > 0
  EXPECT_THROW(no_spacing.strain_step(Mat3::Zero(), 1.0), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------------
// Compressive damage (eq. 36)

// Pre-compress to mu (hydrostatic, elastic), then simple shear at constant volume: P stays fixed, the
// strength follows eq. 33 with the d- of the step's start, and d- = eps_p / max(P D1, eps_min).
double shear_at_pressure(double mu, int steps) {
  const AfcParams p = paper_params();
  Driver pt(AfcMaterial(p), kSpacing);
  pt.volumetric_step_to(mu, 1.0);
  const double P = pressure_of(pt.state().stress);
  for (int i = 0; i < steps; ++i) {
    const double S = afc_strength(P, pt.state().d_minus, pt.state().d_plus, 1.0, p);
    const double ep_before = pt.state().plastic_strain;
    pt.strain_step(simple_shear(4e-5), 1.0);
    if (pt.state().plastic_strain > ep_before) {
      EXPECT_NEAR(von_mises(pt.state().effective_stress), S, 1e-9 * S);
    }
  }
  EXPECT_NEAR(pressure_of(pt.state().effective_stress), P, 1e-9 * P);
  EXPECT_GT(pt.state().plastic_strain, 0.0);
  const double expected = pt.state().plastic_strain / std::max(P * p.D1_1_Pa, p.options.damage_eps_min);
  EXPECT_NEAR(pt.state().d_minus, std::min(1.0, expected), 1e-12);
  return pt.state().d_minus;
}

TEST(AfcDamage, CompressiveDamageFollowsEq36WithThePressureTerm) {
  const AfcParams p = paper_params();
  // mu = 0.004: P = 88 MPa, P D1 = 0.036 > eps_min.
  ASSERT_GT(p.C6_Pa / p.C7 * 0.004 * p.D1_1_Pa, p.options.damage_eps_min);
  const double d = shear_at_pressure(0.004, 300);
  EXPECT_GT(d, 0.05);
  EXPECT_LT(d, 1.0);
}

TEST(AfcDamage, CompressiveDamageUsesEpsMinAtLowPressureAndIsClippedAtOne) {
  const AfcParams p = paper_params();
  // mu = 0.001: P = 22 MPa, P D1 = 0.009 < eps_min = 0.01.
  ASSERT_LT(p.C6_Pa / p.C7 * 0.001 * p.D1_1_Pa, p.options.damage_eps_min);
  EXPECT_GT(shear_at_pressure(0.001, 300), 0.05);
  EXPECT_EQ(shear_at_pressure(0.001, 1500), 1.0);
}

TEST(AfcDamage, CrushingAddsItsPlasticVolumetricStrain) {
  const AfcMaterial law(paper_params());
  const AfcParams& p = law.params();
  Driver pt(law, kSpacing);
  for (int i = 1; i <= 200; ++i) pt.volumetric_step_to(0.05 * i / 200.0, 1.0);
  const double mu_p = law.hydrostat().crushing_strain(0.05);
  EXPECT_GT(mu_p, 0.0);
  EXPECT_NEAR(pt.state().d_minus, mu_p / (1.5 * p.C9), 1e-12);
  pt.volumetric_step_to(0.03, 1.0);  // unloading does not add any
  EXPECT_NEAR(pt.state().d_minus, mu_p / (1.5 * p.C9), 1e-12);
}

TEST(AfcDamage, NoCompressiveDamageInTension) {
  AfcParams p = paper_params();
  p.options.tensile_damage = TensileDamage::Off;
  Driver pt(AfcMaterial(p), kSpacing);
  for (int i = 0; i < 300; ++i) pt.uniaxial_stress_step(2e-6, 1.0);
  EXPECT_GT(pt.state().plastic_strain, 0.0);
  EXPECT_EQ(pt.state().d_minus, 0.0);
}

// ---------------------------------------------------------------------------------------------------
// Options and interface

TEST(AfcOptions, TheCutoffCouplingHandsTheSolverTheAfcStressItself) {
  Driver pt(AfcMaterial(cutoff_mazars_params()), kSpacing);
  for (int i = 0; i < 200; ++i) pt.uniaxial_stress_step(3e-6, 1.0);
  EXPECT_GT(pt.state().d_plus, 0.9);
  EXPECT_EQ(pt.state().stress, pt.state().effective_stress);
}

TEST(AfcOptions, OutputFieldsMatchTheState) {
  const AfcMaterial law(paper_params());
  Driver pt(law, kSpacing);
  for (int i = 0; i < 200; ++i) pt.uniaxial_stress_step(-3e-5, 1.0);
  const auto names = AfcMaterial::output_fields();
  ASSERT_EQ(names.size(), 4u);  // the pressure is the solver's generic field
  EXPECT_EQ(names[0], "damage_tension");
  EXPECT_EQ(names[3], "tensile_strain_max");
  double out[4];
  law.output_values(pt.state(), out);
  EXPECT_EQ(out[0], pt.state().d_plus);
  EXPECT_EQ(out[1], pt.state().d_minus);
  EXPECT_EQ(out[2], pt.state().plastic_strain);
  EXPECT_EQ(out[3], pt.state().tensile_strain_max);
  EXPECT_GT(out[1], 0.0);
  EXPECT_GT((law.dissipation(pt.state()).plastic + law.dissipation(pt.state()).crushing), 0.0);
}

TEST(AfcOptions, InconsistentConstantsAreRejected) {
  const AfcParams p = paper_params();
  auto bad = [&](auto&& change) {
    AfcParams q = p;
    change(q);
    return q;
  };
  EXPECT_THROW(AfcMaterial(bad([](AfcParams& q) { q.C2_Pa = q.C1_Pa; })), std::invalid_argument);
  EXPECT_THROW(AfcMaterial(bad([](AfcParams& q) { q.C9 = q.C7; })), std::invalid_argument);
  EXPECT_THROW(AfcMaterial(bad([](AfcParams& q) { q.K2_Pa = -2e11; })), std::invalid_argument);
  EXPECT_THROW(AfcMaterial(bad([](AfcParams& q) { q.C8_Pa = 1e10; })), std::invalid_argument);
  EXPECT_THROW(AfcMaterial(bad([](AfcParams& q) { q.options.damage_eps_min = 0; })), std::invalid_argument);
  EXPECT_NO_THROW(AfcMaterial{p});
}

}  // namespace
}  // namespace uhpc::macro
