#pragma once
// The "material" block of a case -> the solver's MaterialSet. One branch per law:
//   {"model": "elastic", "density_kg_m3", "bulk_modulus_Pa", "shear_modulus_Pa"}
//   {"model": "j2", ... as elastic ..., "yield_stress_Pa", "hardening_modulus_Pa"}
//   {"model": "afc", "constants_file": "afc_uhpc.json", "sdel_file": "sdel_paper.json"} (paths relative
//     to the case file; --sdel replaces sdel_file)
// Adding a law is one more name in the choice and one more branch in make_material.
// The SDEL handoff (--sdel) is validated by the program before this is called; laws that do not use
// it ignore it (the program says so in its log).
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "solver/material_set.hpp"
#include "uhpc/config.hpp"
#include "uhpc/sdel_handoff.hpp"

namespace uhpc::macro {

// For the run's record: the files a law read (its constants file, the block's sdel_file when --sdel
// did not replace it), and the handoff it used (--sdel's or sdel_file's; handoff_path empty for --sdel).
struct MaterialInputs {
  std::vector<std::string> files_read;
  std::optional<SdelHandoff> handoff;
  std::string handoff_path;
};

struct MaterialChoice {
  MaterialSet set;
  std::string model;   // the block's "model"
  bool uses_sdel = false;  // the law took the handoff
  MaterialInputs inputs;
  // The inputs that set the law's wave speed (hence the stable step), with their values, for the
  // messages of the run's guards: "material.density_kg_m3 = 1e-300, material.bulk_modulus_Pa = ...".
  std::string wave_speed_inputs;
};

MaterialChoice make_material(const Config& block, std::size_t particles, const std::optional<SdelHandoff>& sdel);

// The names of the per-law output fields of `set` (Law::output_fields()).
std::vector<std::string> law_output_fields(const MaterialSet& set);
// Particle i's values of them (law_output_fields(set).size() doubles into out).
void law_output_values_at(const MaterialSet& set, std::size_t i, double* out);

}  // namespace uhpc::macro
