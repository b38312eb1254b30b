#pragma once
// The comparison of uhpc-macro shots with the paper's experiments (Table 5) and with the paper's own
// simulations (Table 8), and the spread of a set of runs of one shot (the spacing study). Pure
// computation: the inputs arrive as parsed tables and JSON, the outputs are JSON and text; reading and
// writing files is uhpc-compare-shots' business (compare_shots_main.cpp).
//
// Conventions (those of the paper's Tables 7 and 8, data/README.md):
//   velocity reduction        v0 - vr                              [m/s]
//   kinetic-energy reduction  1/2 m (v0^2 - vr^2)                  [J]
//   % error                   (experiment - simulation) / experiment x 100, so a positive value means
//                             the simulation under-predicts the reduction (the paper's sign)
//   residual-velocity error   simulation - experiment              [m/s], positive = sphere too fast
//   RMS                       sqrt(mean((vr_sim - vr_exp)^2)) over the shots
// A shot whose sphere did not perforate (stopped in the target, rebounded, or still inside when the run
// ended) counts with residual velocity 0 in every column above; its outcome says which it was.
//
// The kinetic-energy reductions printed in Tables 7 and 8 imply m = 8.42 g (the 12.7 mm sphere at
// 7850 kg/m3), not the stated 9.071 g that the runs use (data/README.md). The joules are given with both
// masses; the % errors do not depend on the mass as long as experiment and simulation use the same one.
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "uhpc/csv.hpp"

namespace uhpc::macro {

// One row of data/table5_ballistic_experiments.csv.
struct Experiment {
  double thickness_mm = 0.0;
  double target_mass_kg = 0.0;
  double impact_velocity_m_s = 0.0;
  double residual_velocity_m_s = 0.0;
};

// One row of data/table8_paper_simulations.csv (rows pair with Table 5 by order).
struct PaperSimulation {
  double impact_velocity_m_s = 0.0;
  double residual_velocity_m_s = 0.0;
  double velocity_reduction_m_s = 0.0;            // as printed
  double velocity_reduction_error_percent = 0.0;  // as printed
  double ke_reduction_J = 0.0;                    // as printed (8.42 g)
  double ke_reduction_error_percent = 0.0;        // as printed
};

// The projectile masses of data/projectile.json: the stated mass the runs use, and the mass of a solid
// sphere of the stated diameter and density (the mass the paper's KE columns imply).
struct ProjectileMasses {
  double stated_kg = 0.0;
  double solid_sphere_kg = 0.0;
};

enum class ShotOutcome { Perforated, Rebounded, NotPerforated };
const char* to_string(ShotOutcome outcome);

// What the comparison needs of one uhpc-macro result.json.
struct ShotResult {
  std::string source;  // the result file, for messages and the tables
  std::string label;   // the run directory's name, e.g. "v817"
  double impact_velocity_m_s = 0.0;
  ShotOutcome outcome = ShotOutcome::NotPerforated;
  double raw_residual_velocity_m_s = 0.0;  // result.json's value (negative for a rebound); 0 when null
  double final_velocity_m_s = 0.0;         // axial sphere velocity at the end of the run (NaN if absent)
  double end_time_s = 0.0;                 // NaN if absent
  double initial_kinetic_J = 0.0;          // NaN if absent (used to check the run's projectile mass)
  double energy_balance_error = 0.0;
  double energy_worst_balance_error = 0.0;  // NaN if absent
  double momentum_balance_error = 0.0;
  double momentum_worst_balance_error = 0.0;  // NaN if absent
  double wall_time_s = 0.0;
  std::string run_outcome;  // result.json's "outcome" (perforated, embedded, rebounded, undecided); "" if absent
  long long particle_count = 0;
  long long steps = 0;

  // The residual velocity the reductions use: result.json's value for a perforation, else 0.
  double counted_residual_velocity_m_s() const {
    return outcome == ShotOutcome::Perforated ? raw_residual_velocity_m_s : 0.0;
  }
};

// Table parsers (InputError naming the table's source, the column and the reason).
std::vector<Experiment> experiments_from_table(const CsvTable& table);
std::vector<PaperSimulation> paper_simulations_from_table(const CsvTable& table);
// data/projectile.json: mass_kg, diameter_m, density_kg_m3 (all > 0).
ProjectileMasses projectile_masses_from_json(const nlohmann::json& j, const std::string& source);
// A uhpc-macro result.json. `source` names it in messages, `label` goes into the tables.
ShotResult shot_from_result_json(const nlohmann::json& j, const std::string& source, const std::string& label);

// The value of ShotComparisonInput::experiment_of for a shot that matches no experiment.
inline constexpr std::size_t kNoExperiment = static_cast<std::size_t>(-1);

// For each shot (in the order given), the index of the experiment whose impact velocity is within
// `tolerance_m_s` of the shot's, or kNoExperiment when none is. A shot within the tolerance of two
// experiments, and two shots matching one experiment, are InputErrors naming the shot's file; shots
// without an experiment and experiments without a shot are not.
std::vector<std::size_t> match_shots_to_experiments(const std::vector<Experiment>& experiments,
                                                    const std::string& experiments_source,
                                                    const std::vector<ShotResult>& shots, double tolerance_m_s);

// The strict pairing (uhpc-compare-shots --require-experiments): for each experiment (in table order),
// the index of the shot whose impact velocity is within `tolerance_m_s` of the experiment's. Every
// experiment must be matched by exactly one shot and every shot must match exactly one experiment;
// otherwise InputError naming the file (experiments_source or the shot's source) and the reason.
std::vector<std::size_t> pair_shots_with_experiments(const std::vector<Experiment>& experiments,
                                                     const std::string& experiments_source,
                                                     const std::vector<ShotResult>& shots, double tolerance_m_s);

struct ShotComparisonInput {
  std::vector<Experiment> experiments;
  std::vector<PaperSimulation> paper;  // empty, or one row per experiment (same order)
  std::vector<ShotResult> shots;
  // For each shot, the index of its experiment, or kNoExperiment (match_shots_to_experiments). Empty:
  // shots[i] pairs with experiments[i], as many shots as experiments.
  std::vector<std::size_t> experiment_of;
  ProjectileMasses masses;
};

// The full comparison as JSON (units in every key): "shots" (one object per shot, in the order given;
// a shot without an experiment has "matched": false, its experiment and paper values and its errors
// null), "summary" (ours and, with Table 8, the paper's: RMS and mean residual-velocity error, error
// ranges, over the shots with an experiment only; outcome counts and wall time over every shot),
// "experiments_without_shot", "notes". InputError when the sizes do not match.
nlohmann::json compare_shots(const ShotComparisonInput& input);

// The per-shot rows of compare_shots() as CSV ("name [unit]" headers) and as a Markdown table with the
// summary lines below it.
std::string comparison_csv(const nlohmann::json& comparison);
std::string comparison_markdown(const nlohmann::json& comparison);

// The spread of one shot over several runs (e.g. the spacing study: the same shot at different particle
// spacings): per run the outcome, counted residual velocity, velocity reduction and particle count; the
// mean, the spread (max - min) and each run's difference from the reference run (index `reference`).
nlohmann::json shot_spread(const std::vector<ShotResult>& runs, std::size_t reference);
std::string shot_spread_markdown(const nlohmann::json& spread);

}  // namespace uhpc::macro
