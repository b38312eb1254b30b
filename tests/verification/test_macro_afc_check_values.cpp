// docs/specification.md's AFC check values (Table 6) reproduced by the law itself at a single material point, built
// from the shipped files: P(C7) = 172.37 MPa, P(C9) = 807.7 MPa, dilatational wave speed at rest
// 4274 m/s, E = 43 300 MPa, unconfined compressive strength 193.6 MPa (eq. 33, reference rate) and
// uniaxial tensile strength 15.9 MPa (eq. 35, d+ = 0). Printed figures are met to their last digit; the
// same figures with each AFC option (what each option is meant to leave alone, and what it changes).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "materials/afc.hpp"
#include "materials/afc_config.hpp"
#include "materials/afc_strength.hpp"
#include "materials/point_driver.hpp"

namespace uhpc::macro {
namespace {

constexpr double MPa = 1e6;

AfcParams paper_params() {
  return load_afc_params(UHPC_DATA_DIR "/afc_uhpc.json", UHPC_DATA_DIR "/sdel_paper.json");
}

void expect_printed(double computed, double printed, int decimals, const char* what) {
  std::printf("%s: computed %.4f, printed %.*f\n", what, computed, decimals, printed);
  EXPECT_LE(std::abs(computed - printed), 0.5 * std::pow(10.0, -decimals) * (1.0 + 1e-12)) << what;
}

TEST(AfcCheckValues, HydrostatPressuresAndWaveSpeed) {
  const AfcMaterial law(paper_params());
  const AfcParams& p = law.params();
  PointDriver<AfcMaterial> pt(law, 0.003);
  pt.volumetric_step_to(p.C7, 1.0);
  expect_printed(pressure_of(pt.state().stress) / MPa, 172.37, 2, "P(C7) [MPa]");
  for (int i = 1; i <= 100; ++i) pt.volumetric_step_to(p.C7 + (p.C9 - p.C7) * i / 100.0, 1.0);
  expect_printed(pressure_of(pt.state().stress) / MPa, 807.7, 1, "P(C9) [MPa]");
  expect_printed(law.wave_speed(AfcMaterial::State{}, 1.0), 4274.0, 0, "wave speed at rest [m/s]");
}

TEST(AfcCheckValues, UnconfinedCompressionAtTheReferenceRate) {
  const AfcParams p = paper_params();
  PointDriver<AfcMaterial> pt(AfcMaterial(p), 0.003);
  const double de = -1e-6, dt = 1e-6 / p.reference_strain_rate_1_s;
  pt.uniaxial_stress_step(de, dt);
  // "43 300 MPa": three significant digits (computed 43 300.6 from K_e and G).
  EXPECT_NEAR(pt.state().stress(0, 0) / pt.total_strain()(0, 0) / MPa, 43300.0, 50.0);
  std::printf("E from the first step [MPa]: %.1f\n", pt.state().stress(0, 0) / pt.total_strain()(0, 0) / MPa);
  double peak = 0.0;
  for (int i = 0; i < 6000; ++i) {
    pt.uniaxial_stress_step(de, dt);
    peak = std::max(peak, -pt.state().stress(0, 0));
  }
  expect_printed(peak / MPa, 193.6, 1, "unconfined compressive strength [MPa]");
  EXPECT_LT(-pt.state().stress(0, 0), peak);  // past the peak
}

TEST(AfcCheckValues, UniaxialTensionWithoutTensileDamage) {
  AfcParams p = paper_params();
  p.options.tensile_damage = TensileDamage::Off;  // eq. 35 at d+ = 0, docs/specification.md's figure
  PointDriver<AfcMaterial> pt(AfcMaterial(p), 0.003);
  const double de = 1e-7, dt = de / p.reference_strain_rate_1_s;
  double peak = 0.0;
  for (int i = 0; i < 6000; ++i) {
    pt.uniaxial_stress_step(de, dt);
    peak = std::max(peak, pt.state().stress(0, 0));
  }
  expect_printed(peak / MPa, 15.9, 1, "uniaxial tensile strength [MPa]");
}

// The options of docs/physics.md section 4 against the same check values. Each is meant to leave the
// hydrostat (P(C9)) and the compressive meridian (f'c: uniaxial compression lies on it) alone; the
// Lode factor moves uniaxial tension onto the extension meridian (r = psi(0) there, so
// f't = psi a / (1 + psi a / (3 Tmax)), a = C1 - C2: 13.8 MPa), the Tmax form of the principal limit caps
// it at Tmax, the tensile DIF raises Tmax by DIF(1e-4 1/s) = 1.09, and the other options leave it.
struct OptionCase {
  const char* name;
  void (*set)(AfcOptions&);
};

double uniaxial_peak(const AfcParams& p, double de) {
  PointDriver<AfcMaterial> pt(AfcMaterial(p), 0.003);
  const double dt = std::abs(de) / p.reference_strain_rate_1_s;
  double peak = 0.0;
  for (int i = 0; i < 6000; ++i) {
    pt.uniaxial_stress_step(de, dt);
    peak = std::max(peak, std::abs(pt.state().stress(0, 0)));
  }
  return peak;
}

TEST(AfcCheckValues, TheOptionsLeaveWhatTheyAreMeantToLeave) {
  const OptionCase cases[] = {
      {"split", [](AfcOptions& o) { o.tensile_degradation = TensileDegradation::Split; }},
      {"lode", [](AfcOptions& o) { o.lode = LodeDependence::WillamWarnke; }},
      {"principal limit (f't)", [](AfcOptions& o) { o.principal_stress_limit = PrincipalStressLimit::UniaxialTensileStrength; }},
      {"principal limit (Tmax)", [](AfcOptions& o) { o.principal_stress_limit = PrincipalStressLimit::Tmax; }},
      {"recoverable opening", [](AfcOptions& o) { o.opened_volume = OpenedVolume::Recoverable; }},
      {"tensile DIF", [](AfcOptions& o) { o.tensile_rate = TensileRate::FibModelCode2010; }},
  };
  for (const OptionCase& c : cases) {
    AfcParams p = paper_params();
    c.set(p.options);
    p.options.tensile_damage = TensileDamage::Off;  // f't is eq. 35's at d+ = 0
    const AfcMaterial law(p);
    PointDriver<AfcMaterial> pt(law, 0.003);
    for (int i = 1; i <= 100; ++i) pt.volumetric_step_to(p.C9 * i / 100.0, 1.0);
    std::printf("[%s]\n", c.name);
    expect_printed(pressure_of(pt.state().stress) / MPa, 807.7, 1, "P(C9) [MPa]");
    expect_printed(uniaxial_peak(p, -1e-6) / MPa, 193.6, 1, "unconfined compressive strength [MPa]");
    const double ft = uniaxial_peak(p, 1e-7);
    if (p.options.tensile_rate != TensileRate::Off) {
      // At the reference rate 1e-4 1/s of the check: DIF = 100^0.018 on Tmax.
      const double dif = afc_tensile_dif(p.reference_strain_rate_1_s, p), a = p.C1_Pa - p.C2_Pa;
      const double expected = a / (1.0 + a / (3.0 * dif * p.Tmax_Pa));
      std::printf("uniaxial tensile strength [MPa]: %.4f (DIF %.4f: %.4f)\n", ft / MPa, dif, expected / MPa);
      EXPECT_NEAR(ft, expected, 1e-4 * expected);
    } else if (p.options.lode == LodeDependence::WillamWarnke) {
      const double psi = lode_psi(0.0, 0.0, 1.0, p), a = p.C1_Pa - p.C2_Pa;
      const double expected = psi * a / (1.0 + psi * a / (3.0 * p.Tmax_Pa));
      std::printf("uniaxial tensile strength [MPa]: %.4f (psi(0) = %.4f: %.4f)\n", ft / MPa, psi, expected / MPa);
      EXPECT_NEAR(ft, expected, 1e-4 * expected);
    } else if (p.options.principal_stress_limit == PrincipalStressLimit::Tmax) {
      std::printf("uniaxial tensile strength [MPa]: %.4f (Tmax %.2f)\n", ft / MPa, p.Tmax_Pa / MPa);
      EXPECT_NEAR(ft, p.Tmax_Pa, 1e-4 * p.Tmax_Pa);
    } else {
      expect_printed(ft / MPa, 15.9, 1, "uniaxial tensile strength [MPa]");
    }
  }
}

}  // namespace
}  // namespace uhpc::macro
