#pragma once
// sdel.json, the micro-to-macro handoff (docs/architecture.md section 2): the four SDEL constants, l_mac,
// the strain measure the law is driven by, the cell sizes it was fitted on, fit quality and origin.
//
//   {
//     "format": "uhpc-sdel/1",                              required, exactly this string
//     "law": "d = 1 / (1 + nu exp(-lambda chi (e - e_i))), ...",  optional, informative only
//     "constants": {"a": 1.0, "A": 0.0002, "nu": 120.5, "chi": 4.1e6},   required, each > 0
//     "l_mac_m": 0.4064,                                    required, > 0
//     "strain_measure": "effective_tensile_strain",         optional, one of the kSdelStrain* below
//     "cell_sizes_m": [0.003, 0.0045, 0.005, 0.0065],       required, each > 0
//     "source": "...",                                      required, where the constants came from
//     "fit": {...},                                         optional object, free-form
//     "provenance": {...}                                   optional, see provenance.hpp
//   }
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "uhpc/provenance.hpp"
#include "uhpc/sdel.hpp"

namespace uhpc {

inline constexpr std::string_view kSdelFormat = "uhpc-sdel/1";

// The equivalent tensile strain the law is driven by.
//   effective_tensile_strain (default): sqrt(sum of squared positive principal strains) of the elastic
//     strain produced by the positive principal effective stresses, C^-1 : <sigma_bar>+ (the conjugate
//     of the tensile free energy of eqs. 21-23; zero in uniaxial compression);
//   mazars_equivalent_tensile: sqrt(sum of squared positive principal strains) of the total strain
//     (counts Poisson and plastic lateral expansion under compression as tension);
//   max_principal_tensile: the largest principal total strain, taken as 0 when negative.
// All three equal the axial strain in the microcells' uniaxial tension.
inline constexpr std::string_view kSdelStrainEffectiveTensile = "effective_tensile_strain";
inline constexpr std::string_view kSdelStrainMazars = "mazars_equivalent_tensile";
inline constexpr std::string_view kSdelStrainMaxPrincipal = "max_principal_tensile";

// The human-readable law written into every handoff ("law" key).
inline constexpr std::string_view kSdelLawText =
    "d = 1 / (1 + nu * exp(-lambda * chi * (e - e_i))), e_i = A / sqrt(1 + a * lambda), "
    "lambda = l_mic / l_mac, e = history maximum of the equivalent tensile strain";

struct SdelHandoff {
  SdelConstants<double> constants{};
  double l_mac_m = 0.4064;
  std::string strain_measure{kSdelStrainEffectiveTensile};
  std::vector<double> cell_sizes_m;
  nlohmann::json fit = nlohmann::json::object();  // rms per size, covariance, ... or notes
  std::string source;
  std::optional<Provenance> provenance;
};

// Reads and validates `path`. Throws InputError "<path>: key '<key>': <reason>" for a missing file,
// invalid JSON, a missing or unknown key, a wrong type, a non-positive constant or length, an unknown
// strain measure or a wrong "format".
SdelHandoff read_sdel_handoff(const std::string& path);

// The same validation for an in-memory document; `source_name` names it in error messages.
SdelHandoff sdel_handoff_from_json(const nlohmann::json& document, const std::string& source_name);

// The document write_sdel_handoff writes (with "format" and "law").
nlohmann::json sdel_handoff_to_json(const SdelHandoff& handoff);

// Validates `handoff` (std::invalid_argument with the reader's message if it would not read back)
// and writes it atomically, pretty-printed, doubles in round-trip precision.
void write_sdel_handoff(const std::string& path, const SdelHandoff& handoff);

}  // namespace uhpc
