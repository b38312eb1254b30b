// The cohesive law of the matrix cracks (micro/analysis/cohesive_law.hpp, Table 2): the envelope,
// G_f as the area under it, secant unloading and reloading with the history maximum, the consistent
// tangent against central finite differences (loading and unloading, Mode I and mixed mode), and the
// no-interpenetration penalty.
#include <array>
#include <cmath>

#include <gtest/gtest.h>

#include "cohesive_law.hpp"

namespace uhpc::micro {
namespace {

// Without the residual spring (tested on its own below), so the envelope's values come out exactly.
CohesiveLaw table2(CohesiveMode mode = CohesiveMode::ModeI) {
  CohesiveLaw law;
  law.tensile_strength_Pa = 22.7e6;
  law.fracture_energy_J_m2 = 35.0;
  law.mode = mode;
  law.residual_stiffness_ratio = 0.0;
  return law;
}

TEST(microCohesiveLaw, EnvelopeMatchesTable2) {
  const CohesiveLaw law = table2();
  EXPECT_NEAR(law.critical_opening(), 2.0 * 35.0 / 22.7e6, 1e-20);
  EXPECT_NEAR(law.critical_opening(), 3.084e-6, 1e-9);  // docs/specification.md: w_c = 3.08 um
  const double wc = law.critical_opening(), w0 = law.activation_opening();
  EXPECT_DOUBLE_EQ(law.envelope(w0), 22.7e6);  // peak exactly f_t
  EXPECT_DOUBLE_EQ(law.envelope(wc), 0.0);
  EXPECT_DOUBLE_EQ(law.envelope(2.0 * wc), 0.0);
  // On the softening line within 0.1 % f_t of t = f_t (1 - w/w_c).
  for (double f : {0.1, 0.3, 0.5, 0.9})
    EXPECT_NEAR(law.envelope(f * wc), 22.7e6 * (1.0 - f), 1e-3 * 22.7e6);
  // Area under the envelope (numerical) = G_f, and the dissipation at w_c is G_f.
  double area = 0.0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double a = wc * i / n, b = wc * (i + 1) / n;
    area += 0.5 * (law.envelope(a) + law.envelope(b)) * (b - a);
  }
  EXPECT_NEAR(area, 35.0, 35.0 * 1e-6);
  EXPECT_NEAR(law.dissipated(wc), 35.0, 1e-9);
  EXPECT_NEAR(law.dissipated(3.0 * wc), 35.0, 1e-9);
  EXPECT_DOUBLE_EQ(law.dissipated(w0), 0.0);
}

TEST(microCohesiveLaw, SecantUnloadingAndReloadingKeepTheHistory) {
  const CohesiveLaw law = table2();
  const double wc = law.critical_opening();
  // Load to 0.4 w_c.
  CohesiveResponse r = cohesive_response(law, 0.4 * wc, 0.0, law.activation_opening());
  EXPECT_DOUBLE_EQ(r.kappa, 0.4 * wc);
  const double t_peak = r.t[0];
  EXPECT_NEAR(t_peak, law.envelope(0.4 * wc), 1e-6);
  // Unload to half: traction halves (secant to the origin), history unchanged.
  CohesiveResponse u = cohesive_response(law, 0.2 * wc, 0.0, r.kappa);
  EXPECT_DOUBLE_EQ(u.kappa, r.kappa);
  EXPECT_NEAR(u.t[0], 0.5 * t_peak, 1e-6 * t_peak);
  EXPECT_NEAR(u.tangent[0], t_peak / (0.4 * wc), 1e-6 * t_peak / wc);
  // Fully closed: zero traction.
  EXPECT_DOUBLE_EQ(cohesive_response(law, 0.0, 0.0, r.kappa).t[0], 0.0);
  // Reloading past the history rejoins the envelope.
  CohesiveResponse v = cohesive_response(law, 0.6 * wc, 0.0, r.kappa);
  EXPECT_DOUBLE_EQ(v.kappa, 0.6 * wc);
  EXPECT_NEAR(v.t[0], law.envelope(0.6 * wc), 1e-6);
  // Beyond w_c nothing is transmitted in opening.
  EXPECT_DOUBLE_EQ(cohesive_response(law, 1.5 * wc, 0.0, v.kappa).t[0], 0.0);
}

TEST(microCohesiveLaw, NoInterpenetration) {
  const CohesiveLaw law = table2();
  const double wc = law.critical_opening();
  const double Kp = law.contact_penalty_ratio * law.initial_stiffness();
  for (double kappa : {law.activation_opening(), 0.5 * wc, 2.0 * wc}) {  // intact, softened, fully open
    const CohesiveResponse r = cohesive_response(law, -1e-3 * wc, 0.0, kappa);
    EXPECT_LT(r.t[0], 0.0);
    EXPECT_DOUBLE_EQ(r.t[0], -1e-3 * wc * Kp);
    EXPECT_DOUBLE_EQ(r.tangent[0], Kp);
    EXPECT_DOUBLE_EQ(r.kappa, kappa);  // compression does not damage in Mode I
  }
}

void check_tangent(const CohesiveLaw& law, double wn, double wt, double kappa) {
  const CohesiveResponse r = cohesive_response(law, wn, wt, kappa);
  const double h = 1e-7 * law.critical_opening();
  for (int b = 0; b < 2; ++b) {
    const double dw[2] = {b == 0 ? h : 0.0, b == 1 ? h : 0.0};
    const CohesiveResponse p = cohesive_response(law, wn + dw[0], wt + dw[1], kappa);
    const CohesiveResponse m = cohesive_response(law, wn - dw[0], wt - dw[1], kappa);
    for (int a = 0; a < 2; ++a) {
      const double fd = (p.t[a] - m.t[a]) / (2.0 * h);
      EXPECT_NEAR(r.tangent[2 * a + b], fd, 1e-5 * law.initial_stiffness() + 1e-5 * std::abs(fd))
          << "entry " << a << b << " at w = (" << wn << ", " << wt << "), kappa " << kappa;
    }
  }
}

TEST(microCohesiveLaw, TangentMatchesFiniteDifferences) {
  for (CohesiveMode mode : {CohesiveMode::ModeI, CohesiveMode::MixedMode}) {
    const CohesiveLaw law = table2(mode);
    const double wc = law.critical_opening(), w0 = law.activation_opening();
    check_tangent(law, 0.5 * w0, 0.1 * w0, w0);              // activation branch
    check_tangent(law, 0.3 * wc, 0.05 * wc, w0);             // softening, loading
    check_tangent(law, 0.7 * wc, -0.1 * wc, 0.2 * wc);       // softening, loading from a history
    check_tangent(law, 0.2 * wc, 0.05 * wc, 0.6 * wc);       // unloading (secant)
    check_tangent(law, -0.01 * wc, 0.02 * wc, 0.6 * wc);     // contact
  }
  // The softening tangent is negative in pure opening.
  const CohesiveLaw law = table2();
  EXPECT_LT(cohesive_response(law, 0.5 * law.critical_opening(), 0.0, law.activation_opening()).tangent[0], 0.0);
}

TEST(microCohesiveLaw, ResidualSpringIsElasticAndParallel) {
  // t = law + K_r w in both directions, tangent + K_r, history and dissipation untouched: a point opened
  // past w_c keeps K_r in opening and in sliding (also in contact), so a fragment cut loose has stiffness.
  for (CohesiveMode mode : {CohesiveMode::ModeI, CohesiveMode::MixedMode}) {
    CohesiveLaw plain = table2(mode);
    CohesiveLaw law = plain;
    law.residual_stiffness_ratio = 1e-8;
    EXPECT_DOUBLE_EQ(CohesiveLaw{}.residual_stiffness_ratio, 1e-8);  // the default
    const double Kr = 1e-8 * law.initial_stiffness(), wc = law.critical_opening();
    for (const auto& w : {std::array<double, 3>{0.3 * wc, 0.1 * wc, 0.01 * wc}, std::array<double, 3>{2.0 * wc, 0.5 * wc, 2.0 * wc},
                          std::array<double, 3>{-0.01 * wc, 3.0 * wc, 1.5 * wc}, std::array<double, 3>{0.2 * wc, 0.0, 0.6 * wc}}) {
      const CohesiveResponse a = cohesive_response(plain, w[0], w[1], w[2]), b = cohesive_response(law, w[0], w[1], w[2]);
      EXPECT_DOUBLE_EQ(b.kappa, a.kappa);
      EXPECT_NEAR(b.t[0], a.t[0] + Kr * w[0], 1e-9 * std::abs(a.t[0]) + 1e-12);
      EXPECT_NEAR(b.t[1], a.t[1] + Kr * w[1], 1e-9 * std::abs(a.t[1]) + 1e-12);
      EXPECT_DOUBLE_EQ(b.tangent[0], a.tangent[0] + Kr);
      EXPECT_DOUBLE_EQ(b.tangent[3], a.tangent[3] + Kr);
      EXPECT_DOUBLE_EQ(b.tangent[1], a.tangent[1]);
      EXPECT_DOUBLE_EQ(b.tangent[2], a.tangent[2]);
    }
    // Fully open: only the spring, 1e-5 f_t at w_c.
    EXPECT_NEAR(cohesive_response(law, wc, 0.0, 2.0 * wc).t[0], 1e-5 * law.tensile_strength_Pa, 1e-12 * law.tensile_strength_Pa);
    EXPECT_DOUBLE_EQ(law.dissipated(2.0 * wc), plain.dissipated(2.0 * wc));
    check_tangent(law, 0.3 * wc, 0.05 * wc, law.activation_opening());
    check_tangent(law, 0.5 * wc, 2.0 * wc, 1.5 * wc);
  }
}

TEST(microCohesiveLaw, MixedModeUsesTheEffectiveOpening) {
  const CohesiveLaw law = table2(CohesiveMode::MixedMode);
  const double wc = law.critical_opening();
  const CohesiveResponse r = cohesive_response(law, 0.3 * wc, 0.4 * wc, law.activation_opening());
  EXPECT_NEAR(r.kappa, 0.5 * wc, 1e-18);
  const double S = law.envelope(0.5 * wc) / (0.5 * wc);
  EXPECT_NEAR(r.t[0], S * 0.3 * wc, 1e-6);
  EXPECT_NEAR(r.t[1], S * 0.4 * wc, 1e-6);
  // Pure sliding past w_c transmits nothing.
  EXPECT_DOUBLE_EQ(cohesive_response(law, 0.0, 1.2 * wc, 0.5 * wc).t[1], 0.0);
}

}  // namespace
}  // namespace uhpc::micro

// The settings of the cohesive-crack analysis (cell_analysis_settings.hpp): defaults when a key is
// absent, values when present, and one InputError "<file>: key 'k': reason" per bad key.
#include <nlohmann/json.hpp>

#include "cell_analysis_settings.hpp"
#include "test_support.hpp"
#include "uhpc/errors.hpp"

namespace uhpc::micro {
namespace {

CellAnalysisOptions read(const std::string& text) {
  const Config c = Config::from_json(nlohmann::json::parse(text), "run.json");
  const CellAnalysisOptions o = read_cell_analysis_options(c.section("analysis"));
  c.finish();
  return o;
}

std::string error(const std::string& text) {
  return test::error_of<InputError>([&] { read(text); });
}

TEST(microCellAnalysisSettings, DefaultsValuesAndErrors) {
  const CellAnalysisOptions d = read(R"({"analysis": {}})");
  EXPECT_EQ(d.control, PathControl::CrackOpening);
  EXPECT_EQ(d.mode, CohesiveMode::ModeI);
  EXPECT_DOUBLE_EQ(d.separation_fraction, 0.01);
  EXPECT_DOUBLE_EQ(d.residual_stiffness_ratio, 1e-8);
  EXPECT_DOUBLE_EQ(read(R"({"analysis": {"cohesive": {"residual_stiffness_ratio": 1e-6}}})").residual_stiffness_ratio, 1e-6);
  EXPECT_EQ(error(R"({"analysis": {"cohesive": {"residual_stiffness_ratio": 0}}})"),
            "run.json: key 'analysis.cohesive.residual_stiffness_ratio': value 0 is out of range, must be in (0, 0.001]");
  const CellAnalysisOptions o = read(R"({"analysis": {"path": {"control": "displacement", "separation_fraction": 0.05},
      "cohesive": {"mode": "mixed", "activation_ratio": 0.002}, "growth": {"increment_spacings": 1.5},
      "quadrature": {"crack_points": 3, "correction": "none"}, "newton": {"max_iterations": 30}}})");
  EXPECT_EQ(o.control, PathControl::Displacement);
  EXPECT_DOUBLE_EQ(o.separation_fraction, 0.05);
  EXPECT_EQ(o.mode, CohesiveMode::MixedMode);
  EXPECT_DOUBLE_EQ(o.activation_ratio, 0.002);
  EXPECT_DOUBLE_EQ(o.growth.increment_spacings, 1.5);
  EXPECT_EQ(o.enrichment.crack_points, 3);
  EXPECT_EQ(o.rk.correction, IntegrationCorrection::None);
  EXPECT_EQ(o.max_iterations, 30);

  EXPECT_EQ(error(R"({"analysis": {"path": {"control": "arc"}}})"),
            "run.json: key 'analysis.path.control': value 'arc' is not one of: crack_opening, displacement");
  EXPECT_EQ(error(R"({"analysis": {"path": {"separation_fraction": 1.5}}})"),
            "run.json: key 'analysis.path.separation_fraction': value 1.5 is out of range, must be in (0, 1)");
  EXPECT_EQ(error(R"({"analysis": {"quadrature": {"triangle_points": 5}}})"),
            "run.json: key 'analysis.quadrature.triangle_points': value 5 is not one of: 1, 3, 6, 7, 12");
  EXPECT_EQ(error(R"({"analysis": {"newton": {"tolerance": "small"}}})"),
            "run.json: key 'analysis.newton.tolerance': expected a number, got a string");
  EXPECT_NE(error(R"({"analysis": {"path": {"contol": "displacement"}}})").find("unknown key"), std::string::npos);
  EXPECT_EQ(error(R"({"analysis": {"path": {"opening_increment": 0.1}}})"),
            "run.json: key 'analysis.path.max_opening_increment': must not be below path.opening_increment");
  // A count beyond int's range is refused, not wrapped (4294967296 steps became 0 and the run "finished").
  EXPECT_EQ(error(R"({"analysis": {"path": {"max_steps": 4294967296}}})"),
            "run.json: key 'analysis.path.max_steps': value 4294967296 is out of range, must be in [1, 2147483647]");
}

TEST(microCellAnalysisSettings, PathEndFollowsTheStrainGridAndNeverStopsShortOfIt) {
  const auto with_end = [](const std::string& text, double end) {
    const Config c = Config::from_json(nlohmann::json::parse(text), "run.json");
    const CellAnalysisOptions o = read_cell_analysis_options(c.section("analysis"), end);
    c.finish();
    return o;
  };
  EXPECT_DOUBLE_EQ(read(R"({"analysis": {}})").max_strain, 0.01);  // the solver's own, without a grid
  EXPECT_DOUBLE_EQ(with_end(R"({"analysis": {}})", 1.5e-3).max_strain, 1.5e-3);
  EXPECT_DOUBLE_EQ(with_end(R"({"analysis": {"path": {"max_strain": 3e-3}}})", 1.5e-3).max_strain, 3e-3);
  EXPECT_EQ(test::error_of<InputError>([&] { with_end(R"({"analysis": {"path": {"max_strain": 1e-3}}})", 1.5e-3); }),
            "run.json: key 'analysis.path.max_strain': 0.001 is below the strain grid's end 0.0015: the curves "
            "would not cover the grid (leave it out to stop at the grid's end)");
}

TEST(microCellAnalysisSettings, GrowthFallbackLineSearchAndCrackedCorrection) {
  const CellAnalysisOptions d = read(R"({"analysis": {}})");
  EXPECT_EQ(d.growth_fallback, GrowthFallback::UnloadAndRegrow);
  EXPECT_EQ(d.line_search_halvings, 4);
  const CellAnalysisOptions o = read(R"({"analysis": {"growth": {"fallback": "fail"}, "newton": {"line_search_halvings": 0}}})");
  EXPECT_EQ(o.growth_fallback, GrowthFallback::Fail);
  EXPECT_EQ(o.line_search_halvings, 0);
  EXPECT_EQ(d.enrichment.cracked_correction, IntegrationCorrection::None);
  EXPECT_EQ(read(R"({"analysis": {"quadrature": {"cracked_correction": "vci"}}})").enrichment.cracked_correction,
            IntegrationCorrection::Vci);
  EXPECT_EQ(error(R"({"analysis": {"quadrature": {"cracked_correction": "off"}}})"),
            "run.json: key 'analysis.quadrature.cracked_correction': value 'off' is not one of: none, vci");
  EXPECT_EQ(error(R"({"analysis": {"growth": {"fallback": "retry"}}})"),
            "run.json: key 'analysis.growth.fallback': value 'retry' is not one of: unload_and_regrow, fail, relax");
  // The verification hook is not a config value.
  EXPECT_EQ(error(R"({"analysis": {"growth": {"fallback": "always_unload"}}})"),
            "run.json: key 'analysis.growth.fallback': value 'always_unload' is not one of: unload_and_regrow, fail, relax");
}

TEST(microCellAnalysisSettings, KrylovIterations) {
  EXPECT_EQ(read(R"({"analysis": {}})").krylov_iterations, 16);
  EXPECT_EQ(read(R"({"analysis": {"newton": {"krylov_iterations": 0}}})").krylov_iterations, 0);
  EXPECT_EQ(error(R"({"analysis": {"newton": {"krylov_iterations": -1}}})"),
            "run.json: key 'analysis.newton.krylov_iterations': value -1 is out of range, must be in [0, 200]");
}

TEST(microCellAnalysisSettings, ProcessZoneControlAndEnergyTolerance) {
  EXPECT_EQ(read(R"({"analysis": {}})").zone_control, ZoneControl::Fallback);
  EXPECT_DOUBLE_EQ(read(R"({"analysis": {}})").energy_tolerance, 0.05);
  EXPECT_DOUBLE_EQ(read(R"({"analysis": {"path": {"energy_tolerance": 0.05}}})").energy_tolerance, 0.05);
  EXPECT_EQ(error(R"({"analysis": {"path": {"energy_tolerance": 0}}})"),
            "run.json: key 'analysis.path.energy_tolerance': value 0 is out of range, must be > 0");
  EXPECT_EQ(read(R"({"analysis": {"path": {"zone_control": "off"}}})").zone_control, ZoneControl::Off);
  EXPECT_EQ(error(R"({"analysis": {"path": {"zone_control": "always"}}})"),  // a verification hook, not a config value
            "run.json: key 'analysis.path.zone_control': value 'always' is not one of: fallback, off");
  EXPECT_EQ(error(R"({"analysis": {"path": {"zone_control": true}}})"),
            "run.json: key 'analysis.path.zone_control': expected a string, got a boolean");
}

TEST(microCellAnalysisSettings, DerivativesAndEnrichmentThreshold) {
  EXPECT_EQ(read(R"({"analysis": {}})").rk.derivatives, rk::Derivatives::Direct);
  EXPECT_DOUBLE_EQ(read(R"({"analysis": {}})").enrichment.min_enrichment_ratio, 1e-6);
  EXPECT_EQ(read(R"({"analysis": {"rk": {"derivatives": "implicit"}}})").rk.derivatives, rk::Derivatives::Implicit);
  EXPECT_EQ(error(R"({"analysis": {"rk": {"derivatives": "exact"}}})"),
            "run.json: key 'analysis.rk.derivatives': value 'exact' is not one of: implicit, direct");
}

TEST(microCellAnalysisSettings, JumpFallbackAndRelaxation) {
  const CellAnalysisOptions d = read(R"({"analysis": {}})");
  EXPECT_EQ(d.jump, JumpFallback::Relax);
  EXPECT_DOUBLE_EQ(d.relaxation_ratio, 2.0);
  EXPECT_EQ(d.max_relaxation_steps, 2000);
  const CellAnalysisOptions o =
      read(R"({"analysis": {"path": {"jump": "fail", "relaxation_ratio": 4, "max_relaxation_steps": 10}}})");
  EXPECT_EQ(o.jump, JumpFallback::Fail);
  EXPECT_DOUBLE_EQ(o.relaxation_ratio, 4.0);
  EXPECT_EQ(o.max_relaxation_steps, 10);
  EXPECT_EQ(error(R"({"analysis": {"path": {"jump": "dynamic"}}})"),
            "run.json: key 'analysis.path.jump': value 'dynamic' is not one of: relax, fail");
  EXPECT_EQ(error(R"({"analysis": {"path": {"relaxation_ratio": 1.0}}})"),
            "run.json: key 'analysis.path.relaxation_ratio': value 1 is out of range, must be in [1.1, 1000]");
}

TEST(microCellAnalysisSettings, MaterialOfTable2) {
  const Config c = Config::from_json(nlohmann::json::parse(R"({"matrix": {"youngs_modulus_Pa": 4.4296e10,
      "poissons_ratio": 0.2, "tensile_strength_Pa": 22.7e6, "fracture_energy_J_m2": 35.0}})"), "micro.json");
  const CellMaterial m = read_cell_material(c.section("matrix"));
  EXPECT_DOUBLE_EQ(m.tensile_strength_Pa, 22.7e6);
  EXPECT_DOUBLE_EQ(m.fracture_energy_J_m2, 35.0);
  EXPECT_DOUBLE_EQ(m.elastic.poissons_ratio, 0.2);
  const Config bad = Config::from_json(nlohmann::json::parse(R"({"matrix": {"youngs_modulus_Pa": 4.4296e10,
      "poissons_ratio": 0.2, "tensile_strength_Pa": -1, "fracture_energy_J_m2": 35.0}})"), "micro.json");
  EXPECT_EQ(test::error_of<InputError>([&] { read_cell_material(bad.section("matrix")); }),
            "micro.json: key 'matrix.tensile_strength_Pa': value -1 is out of range, must be > 0");
}

}  // namespace
}  // namespace uhpc::micro
