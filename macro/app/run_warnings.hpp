#pragma once
// Guard-rails: what a run says when its numbers may be dominated by numerics rather than by the model
// (a target too few particles thick, contact and stabilization taking most of the sphere's energy,
// stabilization giving energy back, the energy check switched off). Each warning is logged and listed
// in result.json's `warnings` with a code, so a study can filter on it; none of them stops a run.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "case_config.hpp"
#include "solver/energy.hpp"

namespace uhpc::macro {

// The thresholds, stated once (macro/README.md, "Warnings").
inline constexpr double kMinParticlesThroughThickness = 5.0;  // thickness / spacing at the impact point
inline constexpr double kMaxNumericalShare = 0.5;  // contact + stabilization share of the sphere's lost energy
inline constexpr double kNegativeStabilizationShare = -1e-3;  // below it, not round-off

struct RunWarning {
  std::string code;     // e.g. "thin_target"
  std::string message;  // one sentence with the figures
};

// Known before the run: the target's resolution through its thickness, the energy check.
std::vector<RunWarning> warnings_before_run(const CaseSettings& settings);

// Known at the end: where the sphere's lost energy went.
std::vector<RunWarning> warnings_after_run(const EnergyLedger& ledger);

nlohmann::json warnings_json(const std::vector<RunWarning>& warnings);

}  // namespace uhpc::macro
