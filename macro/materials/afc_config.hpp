#pragma once
// Building the AFC law from the shipped data: the constants (data/afc_uhpc.json, Table 6 in SI) through
// uhpc::Config and the SDEL constants from the micro-to-macro handoff (data/sdel_paper.json or a
// calibrated sdel.json) through uhpc::read_sdel_handoff. Every problem is an InputError
// "<file>: key '<key>': <reason>".
//
// Keys of the constants document (all required unless marked):
//   density_kg_m3, shear_modulus_Pa, C1_Pa, C2_Pa, C3, C4, C5_Pa, C6_Pa, C7, C8_Pa, C9, K1_Pa, K2_Pa,
//   K3_Pa, D1_1_Pa, An_1_Pa, Tmax_Pa, reference_strain_rate_1_s; "source" (optional text);
//   "options" (optional object, every key optional, defaults of AfcOptions):
//     rate_factor_floor (>= 0), cap_strength_with_c5 (bool), damage_eps_min (> 0),
//     tensile_degradation ("cutoff" | "split"), lode ("off" | "willam_warnke"), principal_stress_limit
//     ("off" | "uniaxial_tensile_strength" | "tmax"; needs "cutoff"), opened_volume ("recoverable" |
//     "permanent"), tensile_rate ("off" | "fib_model_code_2010"), sdel_zero_anchored (bool),
//     sdel_regularization ("lambda" | "crack_band"), crack_band_reference_size_m (> 0),
//     tensile_damage ("sdel" | "off"),
//     wave_speed_from_unloading_modulus (bool).
// A case file's material.options block (macro/app/material_factory.cpp) takes the same keys and
// overrides the constants file's, key by key.
#include <string>
#include <vector>

#include "materials/afc_params.hpp"
#include "uhpc/config.hpp"
#include "uhpc/sdel_handoff.hpp"

namespace uhpc::macro {

// The options block (a section named e.g. "options"); absent keys keep their values in `base`.
AfcOptions afc_options_from_config(const uhpc::Config& options, AfcOptions base = {});

// The constants from `cfg` (its root is the constants object; an "options" section is read when
// present) and the SDEL from `sdel`. Does not call cfg.finish(): the caller may embed the constants in
// a larger document. Cross-checks (C1 > C2, C9 > C7, C8 >= C6/C7, a rising crushing curve) fail with
// the key concerned.
AfcParams afc_params_from_config(const uhpc::Config& cfg, const uhpc::SdelHandoff& sdel);

// Reads `afc_path` (with "--set"-style overrides; unknown keys are errors) and the handoff at
// `sdel_path`.
AfcParams load_afc_params(const std::string& afc_path, const std::string& sdel_path,
                          const std::vector<std::string>& overrides = {});

}  // namespace uhpc::macro
