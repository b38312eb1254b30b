#include "materials/afc_config.hpp"

#include <sstream>
#include <stdexcept>

#include "materials/afc.hpp"
#include "uhpc/errors.hpp"

namespace uhpc::macro {

namespace {

std::string number_text(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

}  // namespace

AfcOptions afc_options_from_config(const uhpc::Config& c, AfcOptions o) {
  if (c.has("rate_factor_floor")) o.rate_factor_floor = c.number("rate_factor_floor", Range::non_negative());
  if (c.has("cap_strength_with_c5")) o.cap_strength_with_c5 = c.flag("cap_strength_with_c5");
  if (c.has("damage_eps_min")) o.damage_eps_min = c.number("damage_eps_min", Range::positive());
  if (c.has("tensile_degradation"))
    o.tensile_degradation = c.choice("tensile_degradation", {"cutoff", "split"}) == "split" ? TensileDegradation::Split
                                                                                             : TensileDegradation::Cutoff;
  if (c.has("lode"))
    o.lode = c.choice("lode", {"off", "willam_warnke"}) == "off" ? LodeDependence::Off : LodeDependence::WillamWarnke;
  if (c.has("principal_stress_limit")) {
    const std::string v = c.choice("principal_stress_limit", {"off", "uniaxial_tensile_strength", "tmax"});
    o.principal_stress_limit = v == "off"    ? PrincipalStressLimit::Off
                               : v == "tmax" ? PrincipalStressLimit::Tmax
                                             : PrincipalStressLimit::UniaxialTensileStrength;
  }
  if (c.has("opened_volume"))
    o.opened_volume = c.choice("opened_volume", {"recoverable", "permanent"}) == "permanent" ? OpenedVolume::Permanent
                                                                                          : OpenedVolume::Recoverable;
  if (c.has("tensile_rate"))
    o.tensile_rate = c.choice("tensile_rate", {"off", "fib_model_code_2010"}) == "off" ? TensileRate::Off
                                                                                       : TensileRate::FibModelCode2010;
  if (c.has("sdel_zero_anchored")) o.sdel_zero_anchored = c.flag("sdel_zero_anchored");
  if (c.has("sdel_regularization"))
    o.sdel_regularization = c.choice("sdel_regularization", {"lambda", "crack_band"}) == "lambda"
                                ? SdelRegularization::Lambda
                                : SdelRegularization::CrackBand;
  if (c.has("crack_band_reference_size_m"))
    o.crack_band_reference_size_m = c.number("crack_band_reference_size_m", Range::positive());
  if (c.has("crack_band_width_spacings"))
    o.crack_band_width_spacings = c.number("crack_band_width_spacings", Range::closed(1.0, 8.0));
  if (c.has("crack_band_strength_reduction")) o.crack_band_strength_reduction = c.flag("crack_band_strength_reduction");
  if (o.crack_band_strength_reduction &&
      (o.sdel_regularization != SdelRegularization::CrackBand || o.tensile_degradation != TensileDegradation::Cutoff))
    c.fail("crack_band_strength_reduction",
           "needs sdel_regularization 'crack_band' with tensile_degradation 'cutoff' (it lowers the strength of a band too wide to hold)");
  if (c.has("tensile_damage"))
    o.tensile_damage = c.choice("tensile_damage", {"sdel", "off"}) == "off" ? TensileDamage::Off : TensileDamage::Sdel;
  if (c.has("wave_speed_from_unloading_modulus"))
    o.wave_speed_from_unloading_modulus = c.flag("wave_speed_from_unloading_modulus");
  // The conflict is named by the key of this block that made it (a case's options may meet a constants
  // file's): the limit when it is set here, else the coupling.
  if (o.principal_stress_limit != PrincipalStressLimit::Off && o.tensile_degradation != TensileDegradation::Cutoff) {
    if (c.has("principal_stress_limit") || !c.has("tensile_degradation"))
      c.fail("principal_stress_limit",
             "needs tensile_degradation 'cutoff' (with the split the tension is already degraded by 1 - d+)");
    c.fail("tensile_degradation", "'split' cannot go with the principal_stress_limit set in the constants file's options");
  }
  return o;
}

AfcParams afc_params_from_config(const uhpc::Config& c, const uhpc::SdelHandoff& sdel) {
  const Range pos = Range::positive(), nonneg = Range::non_negative();
  AfcParams p;
  if (c.has("source")) (void)c.text("source");
  p.density_kg_m3 = c.number("density_kg_m3", pos);
  p.shear_modulus_Pa = c.number("shear_modulus_Pa", pos);
  p.C1_Pa = c.number("C1_Pa", pos);
  p.C2_Pa = c.number("C2_Pa", pos);
  p.C3 = c.number("C3", nonneg);
  p.C4 = c.number("C4", nonneg);
  p.C5_Pa = c.number("C5_Pa", pos);
  p.C6_Pa = c.number("C6_Pa", pos);
  p.C7 = c.number("C7", Range::open(0.0, 1.0));
  p.C8_Pa = c.number("C8_Pa", pos);
  p.C9 = c.number("C9", Range::open(0.0, 1.0));
  p.K1_Pa = c.number("K1_Pa", pos);
  p.K2_Pa = c.number("K2_Pa");
  p.K3_Pa = c.number("K3_Pa");
  p.D1_1_Pa = c.number("D1_1_Pa", pos);
  p.An_1_Pa = c.number("An_1_Pa", pos);
  p.Tmax_Pa = c.number("Tmax_Pa", pos);
  p.reference_strain_rate_1_s = c.number("reference_strain_rate_1_s", pos);
  if (c.has("options")) p.options = afc_options_from_config(c.section("options"));

  if (!(p.C2_Pa < p.C1_Pa))
    c.fail("C2_Pa", "value " + number_text(p.C2_Pa) + " must be < C1_Pa = " + number_text(p.C1_Pa));
  if (!(p.C9 > p.C7)) c.fail("C9", "value " + number_text(p.C9) + " must be > C7 = " + number_text(p.C7));
  const double Ke = p.C6_Pa / p.C7;
  if (!(p.C8_Pa >= Ke))
    c.fail("C8_Pa", "value " + number_text(p.C8_Pa) + " must be >= K_e = C6_Pa / C7 = " + number_text(Ke));

  p.sdel = sdel.constants;
  p.l_mac_m = sdel.l_mac_m;
  p.strain_measure = sdel.strain_measure == kSdelStrainMaxPrincipal ? TensileStrainMeasure::MaxPrincipal
                     : sdel.strain_measure == kSdelStrainMazars    ? TensileStrainMeasure::Mazars
                                                                   : TensileStrainMeasure::EffectiveTensile;
  try {
    (void)AfcMaterial(p);  // the remaining consistency checks (crushing curve) live with the law
  } catch (const std::invalid_argument& e) {
    throw InputError(c.error_message("K2_Pa", e.what()));
  }
  return p;
}

AfcParams load_afc_params(const std::string& afc_path, const std::string& sdel_path,
                          const std::vector<std::string>& overrides) {
  const uhpc::SdelHandoff sdel = uhpc::read_sdel_handoff(sdel_path);
  const uhpc::Config cfg = uhpc::Config::load(afc_path, overrides);
  AfcParams p = afc_params_from_config(cfg, sdel);
  cfg.finish();
  return p;
}

}  // namespace uhpc::macro
