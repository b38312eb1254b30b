// Building the AFC law from the shipped files, and the input errors (file, key, reason) for bad ones.
#include <gtest/gtest.h>

#include <string>

#include "materials/afc.hpp"
#include "materials/afc_config.hpp"
#include "test_support.hpp"
#include "uhpc/errors.hpp"

namespace uhpc::macro {
namespace {

const std::string kAfc = UHPC_DATA_DIR "/afc_uhpc.json";
const std::string kSdel = UHPC_DATA_DIR "/sdel_paper.json";

std::string error_with(const std::vector<std::string>& overrides) {
  return uhpc::test::error_of<uhpc::InputError>([&] { load_afc_params(kAfc, kSdel, overrides); });
}

TEST(AfcConfig, ShippedFilesGiveTable6AndTheHandoff) {
  const AfcParams p = load_afc_params(kAfc, kSdel);
  EXPECT_EQ(p.density_kg_m3, 2555.7);
  EXPECT_EQ(p.C1_Pa, 9.578e8);
  EXPECT_EQ(p.C9, 0.10094);
  EXPECT_EQ(p.Tmax_Pa, 6.89e6);
  EXPECT_EQ(p.reference_strain_rate_1_s, 1e-4);
  EXPECT_EQ(p.sdel.chi, 4.1e6);
  EXPECT_EQ(p.l_mac_m, 0.4064);
  EXPECT_EQ(p.strain_measure, TensileStrainMeasure::EffectiveTensile);
  // The defaults of every option.
  EXPECT_EQ(p.options.rate_factor_floor, 1.0);
  EXPECT_FALSE(p.options.cap_strength_with_c5);
  EXPECT_EQ(p.options.damage_eps_min, 0.01);
  EXPECT_EQ(p.options.tensile_degradation, TensileDegradation::Cutoff);
  EXPECT_EQ(p.options.lode, LodeDependence::Off);
  EXPECT_EQ(p.options.principal_stress_limit, PrincipalStressLimit::Off);
  EXPECT_EQ(p.options.opened_volume, OpenedVolume::Permanent);
  EXPECT_EQ(p.options.tensile_rate, TensileRate::Off);
  EXPECT_FALSE(p.options.sdel_zero_anchored);
  EXPECT_EQ(p.options.sdel_regularization, SdelRegularization::Lambda);
  EXPECT_EQ(p.options.crack_band_reference_size_m, 0.0065);
  EXPECT_EQ(p.options.crack_band_width_spacings, 1.0);
  EXPECT_FALSE(p.options.crack_band_strength_reduction);
  EXPECT_EQ(p.options.tensile_damage, TensileDamage::Sdel);
  EXPECT_FALSE(p.options.wave_speed_from_unloading_modulus);
  EXPECT_NO_THROW(AfcMaterial{p});
}

TEST(AfcConfig, OptionsBlockIsRead) {
  const AfcParams p = load_afc_params(
      kAfc, kSdel,
      {"options.rate_factor_floor=0", "options.cap_strength_with_c5=true", "options.damage_eps_min=0.02",
       "options.tensile_degradation=split", "options.lode=willam_warnke", "options.opened_volume=recoverable",
       "options.tensile_rate=fib_model_code_2010", "options.sdel_zero_anchored=true", "options.tensile_damage=off",
       "options.wave_speed_from_unloading_modulus=true", "options.sdel_regularization=crack_band",
       "options.crack_band_reference_size_m=0.003", "options.crack_band_width_spacings=3"});
  EXPECT_EQ(p.options.rate_factor_floor, 0.0);
  EXPECT_TRUE(p.options.cap_strength_with_c5);
  EXPECT_EQ(p.options.damage_eps_min, 0.02);
  EXPECT_EQ(p.options.tensile_degradation, TensileDegradation::Split);
  EXPECT_EQ(p.options.lode, LodeDependence::WillamWarnke);
  EXPECT_EQ(p.options.opened_volume, OpenedVolume::Recoverable);
  EXPECT_EQ(p.options.tensile_rate, TensileRate::FibModelCode2010);
  EXPECT_TRUE(p.options.sdel_zero_anchored);
  EXPECT_EQ(p.options.tensile_damage, TensileDamage::Off);
  EXPECT_TRUE(p.options.wave_speed_from_unloading_modulus);
  EXPECT_EQ(p.options.sdel_regularization, SdelRegularization::CrackBand);
  EXPECT_EQ(p.options.crack_band_reference_size_m, 0.003);
  EXPECT_EQ(p.options.crack_band_width_spacings, 3.0);
  EXPECT_EQ(load_afc_params(kAfc, kSdel, {"options.sdel_regularization=lambda"}).options.sdel_regularization,
            SdelRegularization::Lambda);
  for (const auto& [text, limit] : {std::pair{"tmax", PrincipalStressLimit::Tmax},
                                    std::pair{"uniaxial_tensile_strength", PrincipalStressLimit::UniaxialTensileStrength}})
    EXPECT_EQ(load_afc_params(kAfc, kSdel, {std::string("options.principal_stress_limit=") + text})
                  .options.principal_stress_limit,
              limit);
}

TEST(AfcConfig, OptionsOverrideABaseKeyByKey) {
  // A case's material.options over the constants file's options: absent keys keep the base's values.
  AfcOptions base;
  base.lode = LodeDependence::WillamWarnke;
  base.damage_eps_min = 0.05;
  const uhpc::Config cfg = uhpc::Config::from_json(nlohmann::json{{"tensile_degradation", "split"}}, "case.json");
  const AfcOptions o = afc_options_from_config(cfg, base);
  EXPECT_EQ(o.tensile_degradation, TensileDegradation::Split);
  EXPECT_EQ(o.lode, LodeDependence::WillamWarnke);
  EXPECT_EQ(o.damage_eps_min, 0.05);
}

TEST(AfcConfig, BadInputNamesFileKeyAndReason) {
  EXPECT_EQ(error_with({"C7=-1"}), kAfc + ": key 'C7': value -1 is out of range, must be in (0, 1)");
  EXPECT_EQ(error_with({"C10_Pa=1"}).rfind(kAfc + ": key 'C10_Pa': unknown key", 0), 0u);
  EXPECT_EQ(error_with({"options.tensile_damage=maybe"}),
            kAfc + ": key 'options.tensile_damage': value 'maybe' is not one of: sdel, off");
  EXPECT_EQ(error_with({"options.typo=1"}).rfind(kAfc + ": key 'options.typo': unknown key", 0), 0u);
  EXPECT_EQ(error_with({"options.sdel_regularization=bazant"}),
            kAfc + ": key 'options.sdel_regularization': value 'bazant' is not one of: lambda, crack_band");
  EXPECT_EQ(error_with({"options.crack_band_reference_size_m=0"}).rfind(
                kAfc + ": key 'options.crack_band_reference_size_m': value 0 is out of range", 0),
            0u);
  EXPECT_EQ(error_with({"options.crack_band_width_spacings=9"}).rfind(
                kAfc + ": key 'options.crack_band_width_spacings': value 9 is out of range", 0),
            0u);
  EXPECT_EQ(error_with({"options.crack_band_width_spacings=0.5"}).rfind(
                kAfc + ": key 'options.crack_band_width_spacings': value 0.5 is out of range", 0),
            0u);
  EXPECT_TRUE(load_afc_params(kAfc, kSdel, {"options.sdel_regularization=crack_band", "options.crack_band_strength_reduction=true"})
                  .options.crack_band_strength_reduction);
  EXPECT_EQ(error_with({"options.crack_band_strength_reduction=true"}),
            kAfc + ": key 'options.crack_band_strength_reduction': needs sdel_regularization 'crack_band' with "
                   "tensile_degradation 'cutoff' (it lowers the strength of a band too wide to hold)");
  EXPECT_EQ(error_with({"options.lode=mohr"}),
            kAfc + ": key 'options.lode': value 'mohr' is not one of: off, willam_warnke");
  EXPECT_EQ(error_with({"options.tensile_degradation=split", "options.principal_stress_limit=tmax"}),
            kAfc + ": key 'options.principal_stress_limit': needs tensile_degradation 'cutoff' (with the split the "
                   "tension is already degraded by 1 - d+)");
  EXPECT_EQ(error_with({"C2_Pa=1e9"}), kAfc + ": key 'C2_Pa': value 1000000000 must be < C1_Pa = 957800000");
  EXPECT_EQ(error_with({"C9=0.005"}), kAfc + ": key 'C9': value 0.005 must be > C7 = 0.00781");
  EXPECT_NE(error_with({"C8_Pa=1e10"}).find("key 'C8_Pa': value 1e+10 must be >= K_e"), std::string::npos);
  EXPECT_NE(error_with({"K2_Pa=-2e11"}).find("key 'K2_Pa': AfcMaterial: the crushing curve"), std::string::npos);
  EXPECT_EQ(error_with({"Tmax_Pa=\"high\""}), kAfc + ": key 'Tmax_Pa': expected a number, got a string");
  // A missing key and a bad handoff.
  EXPECT_NE(uhpc::test::error_of<uhpc::InputError>([] { load_afc_params(kAfc, "/nonexistent/sdel.json"); }), "");
  const std::string missing = uhpc::test::error_of<uhpc::InputError>([] {
    const uhpc::Config cfg = uhpc::Config::from_json(nlohmann::json{{"density_kg_m3", 2500.0}}, "mem.json");
    afc_params_from_config(cfg, uhpc::read_sdel_handoff(kSdel));
  });
  EXPECT_EQ(missing, "mem.json: key 'shear_modulus_Pa': required key is missing");
}

}  // namespace
}  // namespace uhpc::macro
