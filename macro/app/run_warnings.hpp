#pragma once
// Guard-rails: what a run says when its numbers may be dominated by numerics rather than by the model
// (a target too few particles thick, contact and stabilization taking most of the sphere's energy,
// stabilization giving energy back, the energy check switched off, a crack band past its limit). Each
// warning is logged and listed in result.json's `warnings` with a code, so a study can filter on it;
// none of them stops a run.
#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "case_config.hpp"
#include "solver/energy.hpp"
#include "solver/material_set.hpp"

namespace uhpc::macro {

// The thresholds, stated once (macro/README.md, "Warnings").
inline constexpr double kMinParticlesThroughThickness = 5.0;  // thickness / spacing at the impact point
inline constexpr double kMaxNumericalShare = 0.5;  // contact + stabilization share of the sphere's lost energy
inline constexpr double kNegativeStabilizationShare = -1e-3;  // below it, not round-off
inline constexpr double kLongRunSeconds = 3600.0;  // an estimated wall time beyond it warns (long_run)
// The AFC shot's measured throughput per thread (macro/README.md's benchmark of the disc, 3.6e5 on one
// thread), the basis of the estimate below.
inline constexpr double kParticleStepsPerThreadPerSecond = 3.6e5;

struct RunWarning {
  std::string code;     // e.g. "thin_target"
  std::string message;  // one sentence with the figures
};

// Known before the run: the target's resolution through its thickness, the energy check.
std::vector<RunWarning> warnings_before_run(const CaseSettings& settings);

// The crack band's limit (AfcOptions::crack_band_width_spacings): past a band n_b h of this many l_ref a
// point's elastic energy at its peak nearly fills its share and it snaps back, dissipating more than
// G_ref (cutoff coupling: +1.3 % at 1.38 l_ref, +11 % at 1.54; the split's falls past l_ref).
inline constexpr double kCrackBandLimitCutoff = 1.4;
inline constexpr double kCrackBandLimitSplit = 1.0;

// The target's spacing where the sphere strikes.
double impact_point_spacing(const CaseSettings& settings);

// Known from the law: a crack band wider than its limit at the impact point's spacing.
std::vector<RunWarning> warnings_for_material(const MaterialSet& material, const CaseSettings& settings);

// Known at the end: where the sphere's lost energy went.
std::vector<RunWarning> warnings_after_run(const EnergyLedger& ledger);

// The wall time a run will take, said before it starts (a 500 mm slab once ran 8 minutes with nothing
// said up front; the progress line's ETA follows the real rate once the run is going): the steps left
// at the first stable step times the particles, at kParticleStepsPerThreadPerSecond a thread, up to the
// end time: a shot decided earlier stops 10 us after its outcome (ten times sooner for a fast
// perforation); the step shrinking as the target is crushed, or two threads giving less than twice one,
// make it longer.
struct WallTimeEstimate {
  double seconds = 0.0;
  std::string message;  // the estimate with what it is made of
};
WallTimeEstimate estimate_wall_time(std::size_t particles, double remaining_s, double first_step_s, int threads);

nlohmann::json warnings_json(const std::vector<RunWarning>& warnings);

}  // namespace uhpc::macro
