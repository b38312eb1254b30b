#pragma once
// What a run read, for its record (config.json, and result.json's "inputs"): the case document after
// --set, every file the case named and the SDEL handoff, each file with the hash of its bytes. The
// provenance's config hash covers all of them, so two runs that read different handoffs or constants
// never share one.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "material_factory.hpp"
#include "uhpc/config.hpp"

namespace uhpc::macro {

struct RunInputs {
  nlohmann::json record;     // config.json
  std::string hash;          // fnv1a64 of the effective case document and of every other file read
  std::string restart_hash;  // the same without the keys a restart may change (kRestartMayChange)
  std::string former_hash;   // `hash` in the scheme before 2026-12-06 (the case's notes hashed too), only
                             // to recognise a finished run recorded then as one of these inputs
};

// The keys of `run` a restart may change: when the run ends, its step budget and how often it writes;
// nothing that the state it resumes depends on. Changed in the case file or by --set alike.
inline constexpr const char* kRestartMayChange[] = {"end_time_s", "max_steps", "output_interval_steps",
                                                    "checkpoint_interval_steps"};

// "run.end_time_s, run.max_steps, ..." for messages.
std::string restart_may_change_list();

// `case_file` and `overrides` as given; `sdel_path` the --sdel argument ("" without).
RunInputs run_inputs(const Config& cfg, const std::string& case_file, const std::vector<std::string>& overrides,
                     const std::string& sdel_path, const MaterialInputs& material);

// The part of the record result.json carries: the files and the handoff's constants, the target and
// the projectile (without the rest of the case document).
nlohmann::json inputs_summary(const RunInputs& inputs);

}  // namespace uhpc::macro
