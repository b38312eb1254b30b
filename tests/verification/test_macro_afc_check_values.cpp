// docs/specification.md's AFC check values (Table 6) reproduced by the law itself at a single material point, built
// from the shipped files: P(C7) = 172.37 MPa, P(C9) = 807.7 MPa, dilatational wave speed at rest
// 4274 m/s, E = 43 300 MPa, unconfined compressive strength 193.6 MPa (eq. 33, reference rate) and
// uniaxial tensile strength 15.9 MPa (eq. 35, d+ = 0). Printed figures are met to their last digit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "materials/afc.hpp"
#include "materials/afc_config.hpp"
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

}  // namespace
}  // namespace uhpc::macro
