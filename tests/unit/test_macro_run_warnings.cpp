// The guard-rails of a run (macro/app/run_warnings.hpp): each warning where its threshold is crossed and
// not where it is not, on the shipped cases' settings and on ledgers built by hand.
#include <string>

#include <gtest/gtest.h>

#include "case_config.hpp"
#include "materials/afc_config.hpp"
#include "run_warnings.hpp"
#include "uhpc/config.hpp"

namespace uhpc::macro {
namespace {

CaseSettings settings_of(const std::string& case_file, const std::vector<std::string>& overrides = {}) {
  return read_case(Config::load(std::string(UHPC_DATA_DIR) + "/" + case_file, overrides));
}

std::vector<std::string> codes(const std::vector<RunWarning>& warnings) {
  std::vector<std::string> c;
  for (const RunWarning& w : warnings) c.push_back(w.code);
  return c;
}

TEST(MacroRunWarnings, ATargetFewerThanFiveParticlesThickIsFlagged) {
  using V = std::vector<std::string>;
  // The shipped disc: 31.75 mm at 3 mm (10.6 across); the coarse disc: 6 mm (5.3 across).
  EXPECT_EQ(codes(warnings_before_run(settings_of("macro_disc_afc.json"))), V{});
  EXPECT_EQ(codes(warnings_before_run(settings_of("macro_disc_afc_coarse.json"))), V{});
  // 20 mm at 6 mm: 3.3 across.
  const auto thin = warnings_before_run(settings_of("macro_disc_afc_coarse.json", {"target.thickness_m=0.02"}));
  ASSERT_EQ(codes(thin), V{"thin_target"});
  EXPECT_NE(thin[0].message.find("3.3 particles thick"), std::string::npos) << thin[0].message;
  // Off the axis of the graded disc the spacing grows: the coarse disc 70 mm out is 7.5 mm apart, 4.2 across.
  EXPECT_EQ(codes(warnings_before_run(settings_of("macro_disc_afc_coarse.json", {"projectile.offset_m=0.07"}))),
            V{"thin_target"});
  // A box: the elastic block, 16 mm at 4 mm (4 across); 20 mm (5 across) is enough.
  EXPECT_EQ(codes(warnings_before_run(settings_of("macro_elastic_block.json"))), V{"thin_target"});
  EXPECT_EQ(codes(warnings_before_run(settings_of("macro_elastic_block.json", {"target.size_m=[0.048, 0.048, 0.02]"}))),
            V{});
  EXPECT_EQ(codes(warnings_before_run(settings_of("macro_disc_afc.json", {"solver.energy_error_limit=0"}))),
            V{"energy_check_off"});
}

TEST(MacroRunWarnings, ACrackBandPastItsLimitAtTheImpactPointIsFlagged) {
  using V = std::vector<std::string>;
  const auto afc = [](const std::vector<std::string>& options) {
    return make_material_set(
        AfcMaterial(load_afc_params(UHPC_DATA_DIR "/afc_uhpc.json", UHPC_DATA_DIR "/sdel_paper.json", options)), 1);
  };
  const CaseSettings shipped = settings_of("macro_disc_afc.json");  // 3.0 mm at the axis
  // The paper's lambda law has no band; the one-spacing band at 3 mm and the three-spacing one (9 mm,
  // below 1.4 l_ref = 9.1 mm) are within the limit.
  EXPECT_EQ(codes(warnings_for_material(afc({}), shipped)), V{});
  EXPECT_EQ(codes(warnings_for_material(afc({"options.sdel_regularization=crack_band"}), shipped)), V{});
  const V band3 = codes(warnings_for_material(
      afc({"options.sdel_regularization=crack_band", "options.crack_band_width_spacings=3"}), shipped));
  EXPECT_EQ(band3, V{});
  // The coarse disc (6 mm): a band of 18 mm; the split's limit is l_ref itself (9 mm > 6.5 mm).
  const auto wide = warnings_for_material(
      afc({"options.sdel_regularization=crack_band", "options.crack_band_width_spacings=3"}),
      settings_of("macro_disc_afc_coarse.json"));
  ASSERT_EQ(codes(wide), V{"crack_band_too_wide"});
  EXPECT_NE(wide[0].message.find("18.00 mm wide"), std::string::npos) << wide[0].message;
  EXPECT_EQ(codes(warnings_for_material(afc({"options.sdel_regularization=crack_band", "options.crack_band_width_spacings=3",
                                             "options.tensile_degradation=split"}),
                                        shipped)),
            V{"crack_band_too_wide"});
  // With the strength reduction the wide band is held, up to the reduction's range (24 l_ref = 156 mm):
  // nothing to say for the coarse disc's 18 mm; a reference size of 0.5 mm puts 18 mm past it.
  EXPECT_EQ(codes(warnings_for_material(afc({"options.sdel_regularization=crack_band", "options.crack_band_width_spacings=3",
                                             "options.crack_band_strength_reduction=true"}),
                                        settings_of("macro_disc_afc_coarse.json"))),
            V{});
  EXPECT_EQ(codes(warnings_for_material(afc({"options.sdel_regularization=crack_band", "options.crack_band_width_spacings=3",
                                             "options.crack_band_strength_reduction=true",
                                             "options.crack_band_reference_size_m=0.0005"}),
                                        settings_of("macro_disc_afc_coarse.json"))),
            V{"crack_band_too_wide"});
  // No tensile damage at all (the verification switch): the band does nothing, nothing to say.
  EXPECT_EQ(codes(warnings_for_material(afc({"options.sdel_regularization=crack_band", "options.crack_band_width_spacings=3",
                                             "options.tensile_damage=off"}),
                                        settings_of("macro_disc_afc_coarse.json"))),
            V{});
  // Not an AFC law: nothing to say.
  EXPECT_EQ(codes(warnings_for_material(make_material_set(ElasticMaterial(ElasticParams{2500, 2e10, 1e10}), 1), shipped)),
            V{});
}

TEST(MacroRunWarnings, NumericalSharesAboveTheThresholdOrNegativeStabilizationAreFlagged) {
  using V = std::vector<std::string>;
  EnergyLedger e;
  e.kinetic_initial = 1000.0;
  e.kinetic_sphere = 0.0;  // the sphere lost 1000 J
  e.contact = 300.0;
  e.stabilization = 190.0;  // dissipated: stabilization - stored = 150 J
  e.stabilization_stored = 40.0;
  EXPECT_EQ(codes(warnings_after_run(e)), V{});  // 45 %
  e.stabilization = 290.0;                       // 55 %
  const auto high = warnings_after_run(e);
  ASSERT_EQ(codes(high), V{"numerical_dissipation"});
  EXPECT_NE(high[0].message.find("took 55 %"), std::string::npos) << high[0].message;
  e.stabilization = 39.5;  // -0.05 %: round-off
  EXPECT_EQ(codes(warnings_after_run(e)), V{});
  e.stabilization = 20.0;  // -2 %
  EXPECT_EQ(codes(warnings_after_run(e)), V{"negative_stabilization"});
  e.kinetic_sphere = e.kinetic_initial;  // nothing lost: nothing to share
  EXPECT_EQ(codes(warnings_after_run(e)), V{});
}

TEST(MacroRunWarnings, TheWallTimeEstimateIsParticleStepsOverTheThreadsThroughput) {
  // The shipped disc: 79 957 particles, 1 ms at a first step of 1.9e-7 s: 5263 steps, 4.2e8
  // particle-steps, 19.5 min on one thread at 3.6e5 a thread, half that on two.
  const WallTimeEstimate one = estimate_wall_time(79957, 1e-3, 1.9e-7, 1);
  EXPECT_NEAR(one.seconds, 79957.0 * (1e-3 / 1.9e-7) / kParticleStepsPerThreadPerSecond, 1e-9 * one.seconds);
  EXPECT_NEAR(estimate_wall_time(79957, 1e-3, 1.9e-7, 2).seconds, 0.5 * one.seconds, 1e-9 * one.seconds);
  EXPECT_NE(one.message.find("about 19 min"), std::string::npos) << one.message;
  EXPECT_LT(one.seconds, kLongRunSeconds);
  // Four times the particles for three times as long on one thread: beyond an hour, a long_run.
  EXPECT_GT(estimate_wall_time(4 * 79957, 3e-3, 1.9e-7, 1).seconds, kLongRunSeconds);
}

}  // namespace
}  // namespace uhpc::macro
