// uhpc-compare-shots' computation (macro/app/shot_comparison.hpp): the known answer (the paper's own
// Table 8 residual velocities as the "simulation" against Table 5 give docs/specification.md's RMS 35.6 m/s and the
// paper's printed % error columns), the pairing of shots with experiments, rebounds and stopped spheres,
// result.json validation, the CSV and Markdown tables and the spread of one shot over several runs.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "shot_comparison.hpp"
#include "test_support.hpp"
#include "uhpc/config.hpp"
#include "uhpc/csv.hpp"
#include "uhpc/errors.hpp"

using namespace uhpc::macro;
using uhpc::test::error_of;

namespace {

const std::string kData = UHPC_DATA_DIR;

std::vector<Experiment> table5() {
  return experiments_from_table(uhpc::CsvTable::read(kData + "/table5_ballistic_experiments.csv"));
}
std::vector<PaperSimulation> table8() {
  return paper_simulations_from_table(uhpc::CsvTable::read(kData + "/table8_paper_simulations.csv"));
}
ProjectileMasses masses() {
  return projectile_masses_from_json(uhpc::Config::load(kData + "/projectile.json").json(), "projectile.json");
}

// A uhpc-macro result.json as the program writes it (the keys the comparison reads).
nlohmann::json result(double v0, bool perforated, bool rebounded, nlohmann::json vr, double mass_kg = 9.071e-3) {
  return {{"impact_velocity_m_s", v0},
          {"perforated", perforated},
          {"rebounded", rebounded},
          {"residual_velocity_m_s", vr},
          {"final_velocity_m_s", vr.is_number() ? vr.get<double>() : 12.0},
          {"end_time_s", 1.5e-4},
          {"wall_time_s", 600.0},
          {"particle_count", 150000},
          {"steps", 4000},
          {"energy",
           {{"balance_error", 2e-3}, {"worst_balance_error", 3e-3}, {"initial_kinetic_J", 0.5 * mass_kg * v0 * v0}}},
          {"momentum", {{"balance_error", 1e-12}, {"worst_balance_error", 2e-12}}}};
}
ShotResult shot(double v0, bool perforated, bool rebounded, nlohmann::json vr, const std::string& label = "run") {
  return shot_from_result_json(result(v0, perforated, rebounded, vr), label + "/result.json", label);
}

// The paper's Table 8 as our "simulation", paired with Table 5 by order (Table 8's impact velocities are
// the 10 m/s grid points nearest the experiments, so they do not pair within 1 m/s).
nlohmann::json paper_as_simulation() {
  ShotComparisonInput in;
  in.experiments = table5();
  in.paper = table8();
  in.masses = masses();
  for (const auto& p : in.paper) in.shots.push_back(shot(p.impact_velocity_m_s, true, false, p.residual_velocity_m_s));
  return compare_shots(in);
}

}  // namespace

TEST(ShotComparison, PaperTable8AgainstTable5GivesTheSpecRms) {
  const nlohmann::json c = paper_as_simulation();
  const auto& s = c.at("summary").at("simulation");
  EXPECT_EQ(s.at("shots").get<int>(), 7);
  EXPECT_EQ(s.at("perforated").get<int>(), 7);
  // docs/specification.md: "RMS error of the paper's residual velocities against the experiments: 35.6 m/s" (35.59).
  EXPECT_NEAR(s.at("rms_residual_velocity_error_m_s").get<double>(), 35.59, 0.005);
  EXPECT_NEAR(c.at("summary").at("paper").at("rms_residual_velocity_error_m_s").get<double>(), 35.59, 0.005);
  // Mean of (100-53, 100-72, 160-170, 271-236, 340-330, 413-456, 505-556) = 16/7.
  EXPECT_NEAR(s.at("mean_residual_velocity_error_m_s").get<double>(), 16.0 / 7.0, 1e-9);
  EXPECT_NEAR(s.at("max_abs_residual_velocity_error_m_s").get<double>(), 51.0, 1e-9);
  // docs/specification.md: velocity-reduction errors within -9 .. +8 %, kinetic-energy reduction errors within -5 .. +2 %.
  EXPECT_EQ(std::lround(s.at("velocity_reduction_error_min_percent").get<double>()), -9);
  EXPECT_EQ(std::lround(s.at("velocity_reduction_error_max_percent").get<double>()), 8);
  EXPECT_EQ(std::lround(s.at("ke_reduction_error_min_percent").get<double>()), -5);
  EXPECT_EQ(std::lround(s.at("ke_reduction_error_max_percent").get<double>()), 2);
}

TEST(ShotComparison, PaperTable8ErrorColumnsReproducedToRounding) {
  const nlohmann::json c = paper_as_simulation();
  const auto printed = table8();
  const auto table7 = uhpc::CsvTable::read(kData + "/table7_experimental_reductions.csv");
  const auto ke7 = table7.column("ke_reduction");
  const auto dv7 = table7.column("velocity_reduction");
  ASSERT_EQ(c.at("shots").size(), printed.size());
  for (std::size_t i = 0; i < printed.size(); ++i) {
    SCOPED_TRACE("row " + std::to_string(i + 1));
    const auto& sim = c.at("shots")[i].at("simulation");
    const auto& exp = c.at("shots")[i].at("experiment");
    const auto& paper = c.at("shots")[i].at("paper");
    EXPECT_EQ(std::lround(sim.at("velocity_reduction_error_percent").get<double>()),
              std::lround(printed[i].velocity_reduction_error_percent));
    EXPECT_EQ(std::lround(sim.at("ke_reduction_error_percent").get<double>()),
              std::lround(printed[i].ke_reduction_error_percent));
    EXPECT_DOUBLE_EQ(paper.at("velocity_reduction_error_percent").get<double>(),
                     sim.at("velocity_reduction_error_percent").get<double>());
    EXPECT_DOUBLE_EQ(paper.at("velocity_reduction_error_printed_percent").get<double>(),
                     printed[i].velocity_reduction_error_percent);
    // Velocity reductions in m/s as printed in Tables 7 and 8.
    EXPECT_DOUBLE_EQ(exp.at("velocity_reduction_m_s").get<double>(), dv7[i]);
    EXPECT_DOUBLE_EQ(sim.at("velocity_reduction_m_s").get<double>(), printed[i].velocity_reduction_m_s);
    // The printed joules are those of the solid sphere (8.42 g), to their rounding (data/README.md).
    EXPECT_NEAR(exp.at("ke_reduction_paper_mass_J").get<double>(), ke7[i], 6e-4 * ke7[i]);
    EXPECT_NEAR(sim.at("ke_reduction_paper_mass_J").get<double>(), printed[i].ke_reduction_J, 6e-4 * ke7[i]);
    // ... and not those of the stated 9.071 g.
    EXPECT_GT(std::abs(exp.at("ke_reduction_J").get<double>() - ke7[i]), 0.05 * ke7[i]);
  }
  EXPECT_NEAR(c.at("projectile").at("paper_ke_mass_kg").get<double>(), 8.42e-3, 0.005e-3);
  EXPECT_DOUBLE_EQ(c.at("projectile").at("mass_kg").get<double>(), 9.071e-3);
}

TEST(ShotComparison, PairsShotsWithExperimentsByImpactVelocity) {
  const auto e = table5();
  std::vector<ShotResult> shots;
  for (double v : {1112.0, 610.4, 903.0, 689.0, 992.0, 612.2, 817.0})
    shots.push_back(shot(v, true, false, 100.0, std::to_string(v)));
  const auto order = pair_shots_with_experiments(e, "t5.csv", shots, 1.0);
  const std::vector<std::size_t> expected = {1, 5, 3, 6, 2, 4, 0};
  EXPECT_EQ(order, expected);
}

TEST(ShotComparison, PairingErrorsNameTheFileAndReason) {
  const auto e = table5();
  auto seven = [](std::vector<double> v) {
    std::vector<ShotResult> s;
    for (std::size_t i = 0; i < v.size(); ++i) s.push_back(shot(v[i], true, false, 100.0, "v" + std::to_string(i)));
    return s;
  };
  // A missing shot: the experiment row is named.
  EXPECT_EQ(error_of<uhpc::InputError>([&] {
              pair_shots_with_experiments(e, "t5.csv", seven({610, 613, 817, 903, 992, 1112}), 1.0);
            }),
            "t5.csv: row 3 (impact velocity 689 m/s) has no shot among the 6 result(s) given (within 1 m/s)");
  // A shot off every experiment: the shot's file is named.
  EXPECT_EQ(error_of<uhpc::InputError>([&] {
              pair_shots_with_experiments(e, "t5.csv", seven({610, 613, 700, 817, 903, 992, 1112}), 1.0);
            }),
            "v2/result.json: impact velocity 700 m/s matches no experiment of t5.csv (within 1 m/s)");
  // Two shots for one experiment.
  EXPECT_EQ(error_of<uhpc::InputError>([&] {
              pair_shots_with_experiments(e, "t5.csv", seven({610, 610.5, 689, 817, 903, 992, 1112}), 1.0);
            }),
            "v1/result.json: impact velocity 610.5 m/s pairs with the 610 m/s experiment that v0/result.json already "
            "pairs with");
  // A tolerance wide enough to reach two experiments (610 and 613 m/s).
  EXPECT_EQ(
      error_of<uhpc::InputError>([&] { pair_shots_with_experiments(e, "t5.csv", seven({611.5}), 5.0); }),
      "v0/result.json: impact velocity 611.5 m/s matches two experiments of t5.csv (610 and 613 m/s) within 5 m/s");
}

TEST(ShotComparison, MatchesShotsWithoutRequiringEveryExperiment) {
  const auto e = table5();
  std::vector<ShotResult> shots;
  for (double v : {700.0, 610.4, 1200.0, 689.0}) shots.push_back(shot(v, true, false, 100.0, std::to_string(v)));
  const auto of = match_shots_to_experiments(e, "t5.csv", shots, 1.0);
  const std::vector<std::size_t> expected = {kNoExperiment, 0, kNoExperiment, 2};
  EXPECT_EQ(of, expected);
  // Two shots for one experiment, or a shot within the tolerance of two, stay bad input.
  shots.push_back(shot(610.0, true, false, 90.0, "again"));
  EXPECT_EQ(error_of<uhpc::InputError>([&] { match_shots_to_experiments(e, "t5.csv", shots, 1.0); }),
            "again/result.json: impact velocity 610 m/s pairs with the 610 m/s experiment that "
            "610.400000/result.json already pairs with");
  EXPECT_EQ(error_of<uhpc::InputError>([&] { match_shots_to_experiments(e, "t5.csv", {shot(611.5, true, false, 1.0, "w")}, 5.0); }),
            "w/result.json: impact velocity 611.5 m/s matches two experiments of t5.csv (610 and 613 m/s) within 5 m/s");
}

TEST(ShotComparison, ShotsWithoutAnExperimentAreListedOutsideTheStatistics) {
  ShotComparisonInput in;
  in.experiments = table5();
  in.paper = table8();
  in.masses = masses();
  // 600 m/s (no experiment), 610 (row 1, 30 m/s too fast), 700 (none, rebounded), 817 (row 4, exact).
  in.shots = {shot(600, true, false, 20.0, "v600"), shot(610, true, false, 83.0, "v610"),
              shot(700, false, true, -5.0, "v700"), shot(817, true, false, 236.0, "v817")};
  in.experiment_of = {kNoExperiment, 0, kNoExperiment, 3};
  const nlohmann::json c = compare_shots(in);
  ASSERT_EQ(c.at("shots").size(), 4u);
  const auto& u = c.at("shots")[0];
  EXPECT_FALSE(u.at("matched").get<bool>());
  EXPECT_TRUE(u.at("experiment_row").is_null());
  EXPECT_TRUE(u.at("experiment").at("residual_velocity_m_s").is_null());
  EXPECT_TRUE(u.at("paper").at("residual_velocity_m_s").is_null());
  EXPECT_TRUE(u.at("simulation").at("residual_velocity_error_m_s").is_null());
  EXPECT_TRUE(u.at("simulation").at("velocity_reduction_error_percent").is_null());
  EXPECT_EQ(u.at("simulation").at("residual_velocity_m_s").get<double>(), 20.0);
  EXPECT_EQ(u.at("simulation").at("velocity_reduction_m_s").get<double>(), 580.0);
  EXPECT_EQ(c.at("shots")[2].at("simulation").at("residual_velocity_m_s").get<double>(), 0.0);  // rebound
  EXPECT_EQ(c.at("shots")[3].at("experiment_row").get<int>(), 4);
  EXPECT_TRUE(c.at("shots")[3].at("matched").get<bool>());
  // Statistics over the two matched shots only: errors +30 and 0 m/s.
  const auto& s = c.at("summary").at("simulation");
  EXPECT_EQ(s.at("shots").get<int>(), 2);
  EXPECT_EQ(s.at("shots_total").get<int>(), 4);
  EXPECT_EQ(s.at("shots_without_experiment").get<int>(), 2);
  EXPECT_NEAR(s.at("rms_residual_velocity_error_m_s").get<double>(), std::sqrt(30.0 * 30.0 / 2.0), 1e-12);
  EXPECT_NEAR(s.at("mean_residual_velocity_error_m_s").get<double>(), 15.0, 1e-12);
  EXPECT_EQ(s.at("perforated").get<int>(), 3);  // outcome counts over every shot
  EXPECT_EQ(s.at("rebounded").get<int>(), 1);
  // The paper's statistics over the same experiments (rows 1 and 4: 100 - 53, 271 - 236).
  EXPECT_NEAR(c.at("summary").at("paper").at("rms_residual_velocity_error_m_s").get<double>(),
              std::sqrt((47.0 * 47.0 + 35.0 * 35.0) / 2.0), 1e-12);
  ASSERT_EQ(c.at("experiments_without_shot").size(), 5u);
  EXPECT_EQ(c.at("experiments_without_shot")[0].at("experiment_row").get<int>(), 2);
  const std::string notes = c.at("notes").dump();
  EXPECT_NE(notes.find("2 of the 4 shots have no experiment"), std::string::npos) << notes;
  EXPECT_NE(notes.find("experiments without a shot (not compared): row 2 (613 m/s), row 3 (689 m/s)"),
            std::string::npos)
      << notes;
  // The tables: one CSV row per shot with empty experiment cells; the Markdown says what the RMS covers.
  const uhpc::CsvTable t = uhpc::CsvTable::parse(comparison_csv(c), "comparison.csv");
  EXPECT_EQ(t.rows(), 4u);
  EXPECT_EQ(t.column("simulation_residual_velocity")[0], 20.0);
  EXPECT_EQ(t.text_column("experiment_residual_velocity")[0], "");
  EXPECT_EQ(t.text_column("experiment_residual_velocity")[3], "236");
  const std::string md = comparison_markdown(c);
  EXPECT_NE(md.find("| v600 | 600 |  |  |  | 20 |"), std::string::npos) << md;
  EXPECT_NE(md.find("Statistics over the 2 shots with an experiment only (2 of the 4 shots have none"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("RMS residual-velocity error over 2 shots: ours 21.2 m/s"), std::string::npos) << md;
  // Indices that do not fit are an error, not a crash.
  in.experiment_of = {kNoExperiment, 0, 9, 3};
  EXPECT_EQ(error_of<uhpc::InputError>([&] { compare_shots(in); }), "experiment index 10 of 7 experiments");
  in.experiment_of = {0};
  EXPECT_EQ(error_of<uhpc::InputError>([&] { compare_shots(in); }), "1 experiment indices for 4 shot results");
}

TEST(ShotComparison, ReboundAndStoppedSphereCountAsResidualVelocityZero) {
  ShotComparisonInput in;
  in.experiments = table5();
  in.masses = masses();
  for (const auto& x : in.experiments)
    in.shots.push_back(shot(x.impact_velocity_m_s, true, false, x.residual_velocity_m_s));
  in.shots[0] = shot(610, false, true, -40.0, "v610");     // rebound: result.json has -40 m/s
  in.shots[1] = shot(613, false, false, nullptr, "v613");  // still in the target, moving at 12 m/s
  const nlohmann::json c = compare_shots(in);
  const auto& r0 = c.at("shots")[0].at("simulation");
  EXPECT_EQ(r0.at("outcome"), "rebounded");
  EXPECT_EQ(r0.at("residual_velocity_m_s").get<double>(), 0.0);
  EXPECT_EQ(r0.at("result_residual_velocity_m_s").get<double>(), -40.0);
  EXPECT_EQ(r0.at("velocity_reduction_m_s").get<double>(), 610.0);
  EXPECT_EQ(r0.at("residual_velocity_error_m_s").get<double>(), -53.0);
  EXPECT_NEAR(r0.at("velocity_reduction_error_percent").get<double>(), (557.0 - 610.0) / 557.0 * 100.0, 1e-12);
  EXPECT_NEAR(r0.at("ke_reduction_J").get<double>(), 0.5 * 9.071e-3 * 610.0 * 610.0, 1e-9);
  const auto& r1 = c.at("shots")[1].at("simulation");
  EXPECT_EQ(r1.at("outcome"), "not_perforated");
  EXPECT_TRUE(r1.at("result_residual_velocity_m_s").is_null());
  EXPECT_EQ(r1.at("residual_velocity_m_s").get<double>(), 0.0);
  // The other five reproduce the experiment exactly: RMS from the two zeros only.
  const auto& s = c.at("summary").at("simulation");
  EXPECT_NEAR(s.at("rms_residual_velocity_error_m_s").get<double>(), std::sqrt((53.0 * 53.0 + 72.0 * 72.0) / 7.0),
              1e-9);
  EXPECT_EQ(s.at("rebounded").get<int>(), 1);
  EXPECT_EQ(s.at("not_perforated").get<int>(), 1);
  EXPECT_EQ(s.at("perforated").get<int>(), 5);
  EXPECT_FALSE(c.at("summary").contains("paper"));
  const std::string notes = c.at("notes").dump();
  EXPECT_NE(notes.find("v610: the sphere rebounded"), std::string::npos) << notes;
  EXPECT_NE(notes.find("v613: the run ended"), std::string::npos) << notes;
  const std::string md = comparison_markdown(c);
  EXPECT_NE(md.find("0 (rebound)"), std::string::npos) << md;
  EXPECT_NE(md.find("0 (unfinished)"), std::string::npos) << md;  // still moving at 12 m/s
}

TEST(ShotComparison, FlagsARunWithAnotherProjectileMass) {
  ShotComparisonInput in;
  in.experiments = {table5()[3]};
  in.masses = masses();
  in.shots = {shot_from_result_json(result(817.0, true, false, 250.0, 8.42e-3), "v817/result.json", "v817")};
  const std::string notes = compare_shots(in).at("notes").dump();
  EXPECT_NE(notes.find("v817: the run's projectile mass (2 x initial kinetic energy / v0^2) is 8.42 g"),
            std::string::npos)
      << notes;
}

TEST(ShotComparison, ResultJsonValidation) {
  EXPECT_EQ(error_of<uhpc::InputError>([] { shot_from_result_json(result(817, true, false, nullptr), "r.json", "r"); }),
            "r.json: key 'residual_velocity_m_s': expected a number, got null");
  EXPECT_EQ(error_of<uhpc::InputError>([] { shot_from_result_json(result(817, true, true, 5.0), "r.json", "r"); }),
            "r.json: key 'rebounded': a shot cannot both perforate and rebound");
  EXPECT_EQ(error_of<uhpc::InputError>([] { shot_from_result_json(result(817, true, false, -5.0), "r.json", "r"); }),
            "r.json: key 'residual_velocity_m_s': value -5 is negative although the shot perforated");
  nlohmann::json j = result(817, true, false, 250.0);
  j["energy"].erase("balance_error");
  EXPECT_EQ(error_of<uhpc::InputError>([&] { shot_from_result_json(j, "r.json", "r"); }),
            "r.json: key 'energy.balance_error': required key is missing");
  j = result(817, true, false, 250.0);
  j["perforated"] = "yes";
  EXPECT_EQ(error_of<uhpc::InputError>([&] { shot_from_result_json(j, "r.json", "r"); }),
            "r.json: key 'perforated': expected true or false, got \"yes\"");
  EXPECT_EQ(error_of<uhpc::InputError>([] { shot_from_result_json(result(0, false, false, nullptr), "r.json", "r"); }),
            "r.json: key 'impact_velocity_m_s': value 0 is out of range, must be > 0");
}

TEST(ShotComparison, SizeMismatchIsAnInputError) {
  ShotComparisonInput in;
  in.experiments = table5();
  in.masses = masses();
  in.shots = {shot(610, true, false, 50.0)};
  EXPECT_EQ(error_of<uhpc::InputError>([&] { compare_shots(in); }), "1 shot results for 7 experiments");
}

TEST(ShotComparison, CsvHasUnitsInTheHeaderAndOneRowPerShot) {
  const nlohmann::json c = paper_as_simulation();
  const uhpc::CsvTable t = uhpc::CsvTable::parse(comparison_csv(c), "comparison.csv");
  EXPECT_EQ(t.rows(), 7u);
  EXPECT_EQ(t.unit("simulation_residual_velocity"), "m/s");
  EXPECT_EQ(t.unit("simulation_velocity_reduction_error"), "%");
  EXPECT_EQ(t.unit("experiment_ke_reduction_paper_mass"), "J");
  EXPECT_EQ(t.unit("simulation_wall_time"), "s");
  EXPECT_EQ(t.text_column("simulation_outcome")[2], "perforated");
  const auto vr = t.column("paper_residual_velocity");
  EXPECT_EQ(vr[3], 271.0);
  const std::string md = comparison_markdown(c);
  EXPECT_NE(md.find("ours 35.6 m/s"), std::string::npos) << md;
  EXPECT_NE(md.find("| 817 | 31.55 | 236 | 271 | 271 |"), std::string::npos) << md;
}

TEST(ShotComparison, SpreadOfOneShotOverRuns) {
  std::vector<ShotResult> runs = {shot(817, true, false, 250.0, "graded"),
                                  shot(817, true, false, 230.0, "uniform_3.0mm"),
                                  shot(817, false, true, -10.0, "uniform_4.5mm")};
  const nlohmann::json s = shot_spread(runs, 0);
  EXPECT_EQ(s.at("reference"), "graded");
  const auto& sum = s.at("summary");
  EXPECT_DOUBLE_EQ(sum.at("mean_residual_velocity_m_s").get<double>(), 160.0);
  EXPECT_DOUBLE_EQ(sum.at("spread_m_s").get<double>(), 250.0);
  EXPECT_DOUBLE_EQ(sum.at("max_abs_difference_from_reference_m_s").get<double>(), 250.0);
  EXPECT_NEAR(sum.at("standard_deviation_m_s").get<double>(), std::sqrt((90.0 * 90 + 70.0 * 70 + 160.0 * 160) / 2.0),
              1e-9);
  EXPECT_DOUBLE_EQ(s.at("runs")[1].at("difference_from_reference_m_s").get<double>(), -20.0);
  EXPECT_EQ(s.at("runs")[2].at("outcome"), "rebounded");
  EXPECT_DOUBLE_EQ(s.at("runs")[2].at("velocity_reduction_m_s").get<double>(), 817.0);
  const nlohmann::json s1 = shot_spread(runs, 1);
  EXPECT_DOUBLE_EQ(s1.at("summary").at("max_abs_difference_from_reference_m_s").get<double>(), 230.0);
  EXPECT_NE(shot_spread_markdown(s).find("spread 250.0 m/s"), std::string::npos);
  runs.push_back(shot(610, true, false, 50.0, "other"));
  EXPECT_EQ(
      error_of<uhpc::InputError>([&] { shot_spread(runs, 0); }),
      "other/result.json: impact velocity 610 m/s differs from the reference run's 817 m/s (graded/result.json): a "
      "spread compares runs of one shot");
}

TEST(ShotComparison, TableParsersRejectBadRows) {
  const auto bad = uhpc::CsvTable::parse(
      "thickness [mm],target_mass [kg],impact_velocity [m/s],residual_velocity [m/s]\n31,10,600,700\n", "t.csv");
  EXPECT_EQ(error_of<uhpc::InputError>([&] { experiments_from_table(bad); }),
            "t.csv: row 1: residual velocity 700 m/s is not below the impact velocity 600 m/s");
  const auto neg = uhpc::CsvTable::parse(
      "thickness [mm],target_mass [kg],impact_velocity [m/s],residual_velocity [m/s]\n31,10,-600,0\n", "t.csv");
  EXPECT_EQ(error_of<uhpc::InputError>([&] { experiments_from_table(neg); }),
            "t.csv: column 'impact_velocity', row 1: value -600 is out of range, must be > 0");
  EXPECT_EQ(error_of<uhpc::InputError>([] {
              projectile_masses_from_json({{"mass_kg", 0.009}, {"diameter_m", 0.0127}}, "p.json");
            }),
            "p.json: key 'density_kg_m3': required key is missing");
}
