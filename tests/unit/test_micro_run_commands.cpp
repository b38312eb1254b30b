// The drivers of `uhpc-micro run` and `uhpc-micro ensemble` (micro/app/run_commands.hpp) with test
// analyzers: the closed-form cohesive bar (tests/support/cohesive_bar.hpp) on real generated cells, one
// that throws and one that returns Failed. Files written, exit codes and messages, resume, failures
// recorded, ensemble.h5 readable by the calibrate reader.
#include <atomic>
#include <cstdlib>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cell_analysis_settings.hpp"
#include "cohesive_bar.hpp"
#include "run_commands.hpp"
#include "test_support.hpp"
#include "uhpc/cli.hpp"
#include "uhpc/ensemble_file.hpp"
#include "uhpc/errors.hpp"
#include "uhpc/hdf5_io.hpp"

namespace fs = std::filesystem;

namespace uhpc::micro {
namespace {

struct AnalyzerLog {
  std::atomic<int> calls{0};
  std::atomic<int> meshed{0};  // jobs that arrived with a mesh
  std::atomic<int> states{0};  // observer calls
};

// The bar of length = the cell size; f_t scattered by the seed so the cells differ. "throw_on",
// "fail_on" and "suspect_on" (an operator energy mismatch of 0.5) name one cell [size index,
// realization] ([-1, -1]: none).
CellAnalyzerFactory bar_factory(AnalyzerLog& log) {
  return [&log](const Config& a, double) -> CellAnalyzer {
    const double E = a.number("youngs_modulus_Pa", Range::positive());
    const double f_t = a.number("tensile_strength_Pa", Range::positive());
    const double G_f = a.number("fracture_energy_J_m2", Range::positive());
    const double scatter = a.number("strength_scatter", Range::closed(0.0, 0.5));
    const std::vector<double> throw_on = a.numbers("throw_on", Range::any(), 2);
    const std::vector<double> fail_on = a.numbers("fail_on", Range::any(), 2);
    const std::vector<double> suspect_on = a.numbers("suspect_on", Range::any(), 2);
    return [=, &log](const CellJob& job, const StateObserver& observe) {
      ++log.calls;
      if (job.mesh) ++log.meshed;
      const auto is = [&job](const std::vector<double>& cell) {
        return cell[0] == static_cast<double>(job.size_index) && cell[1] == static_cast<double>(job.realization);
      };
      if (is(throw_on)) throw std::runtime_error("boom");
      test::CohesiveBar bar;
      bar.E = E;
      bar.f_t = f_t * (1.0 + scatter * (static_cast<double>(job.seed % 1000) / 999.0 - 0.5));
      bar.G_f = G_f;
      bar.L = job.size_m;
      CellResponse r = bar.response(10, 100);
      r.porosity = job.cell->geometry.porosity();
      if (job.mesh) r.nodes = job.mesh->node_count();
      for (std::size_t i = 0; i < r.states.size(); ++i) {
        observe(i, r.states[i]);
        ++log.states;
      }
      if (is(suspect_on)) r.operator_energy_mismatch = 0.5;
      if (is(fail_on)) {
        r.states.resize(15);
        r.status = CellStatus::Failed;
        r.diagnostic = "Newton did not converge at step 15";
      }
      return r;
    };
  };
}

const nlohmann::json kAnalysis = {{"youngs_modulus_Pa", 4.4296e10}, {"tensile_strength_Pa", 2.27e7},
                                  {"fracture_energy_J_m2", 35.0},   {"strength_scatter", 0.1},
                                  {"throw_on", {-1, -1}},           {"fail_on", {-1, -1}},
                                  {"suspect_on", {-1, -1}}};
const nlohmann::json kPost = {{"bridging", {{"strain_control", "first_passage"}, {"damage_measure", "energy"}, {"tolerance", 0.01}}},
                              {"strain_grid", {{"max_strain", 1.5e-3}, {"points", 301}}}};

nlohmann::json read_json(const fs::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

class MicroRunCommands : public test::ScratchDirTest {
 protected:
  fs::path write_config(const std::string& name, nlohmann::json j) {
    j["cell_config"] = std::string(UHPC_DATA_DIR) + "/micro_cell.json";
    j.update(kPost);
    if (!j.contains("analysis")) j["analysis"] = kAnalysis;
    const fs::path p = dir_ / name;
    std::ofstream(p) << j.dump(2);
    return p;
  }
  fs::path run_config() { return write_config("run.json", nlohmann::json::object()); }
  fs::path ensemble_config(std::vector<double> sizes, int realizations) {
    return write_config("ensemble.json", {{"cell_sizes_m", sizes},
                                          {"realizations", realizations},
                                          {"base_seed", 7},
                                          {"retry_failed", true},
                                          {"max_operator_mismatch", 0.05}});
  }
  int run(const fs::path& config, const std::vector<std::string>& sets, const fs::path& out) {
    return run_main("uhpc-micro run", [&] { return run_cell_command(config.string(), sets, out, bar_factory(log_)); });
  }
  int ensemble(const fs::path& config, const std::vector<std::string>& sets, const fs::path& out, int jobs = 2,
               const EnsembleSelection& selection = {}) {
    return run_main("uhpc-micro ensemble", [&] {
      return run_ensemble_command(config.string(), sets, out, jobs, bar_factory(log_), selection);
    });
  }
  AnalyzerLog log_;
};

TEST_F(MicroRunCommands, RunWritesCurvesAndSummaryOfTheGeneratedCell) {
  const fs::path out = dir_ / "run";
  ASSERT_EQ(run(run_config(), {}, out), kExitOk);
  EXPECT_EQ(log_.calls, 1);
  EXPECT_EQ(log_.meshed, 1);  // the shipped cell config meshes: the analyzer gets the discretization
  EXPECT_EQ(log_.states, 111);
  ASSERT_TRUE(fs::exists(out / "cell.json"));
  const nlohmann::json s = read_json(out / "summary.json");
  EXPECT_EQ(s["format"], "uhpc-micro-run/2");
  EXPECT_EQ(s["status"], "separated");
  EXPECT_EQ(s["steps"], 110);
  EXPECT_EQ(s["cell"]["seed"], 1);  // data/micro_cell.json
  EXPECT_GT(s["nodes"].get<int>(), 1000);
  // The bar's known answers (f_t scattered by seed 1: factor 1 + 0.1 (1/999 - 0.5)).
  test::CohesiveBar bar;
  bar.f_t = 2.27e7 * (1.0 + 0.1 * (1.0 / 999.0 - 0.5));
  EXPECT_DOUBLE_EQ(s["peak_stress_Pa"].get<double>(), bar.f_t);
  EXPECT_DOUBLE_EQ(s["strain_at_peak"].get<double>(), bar.e_t());
  EXPECT_NEAR(s["strain_at_half_damage"].get<double>(), bar.strain_at_half_damage(), 2e-3 * bar.e_t());
  EXPECT_NEAR(s["dissipated_energy_J_m"].get<double>(), bar.G_f * bar.L, 1e-9);
  EXPECT_LT(s["bridging"]["max_abs_difference"].get<double>(), 1e-12);
  EXPECT_TRUE(s["bridging"]["within_tolerance"].get<bool>());
  EXPECT_NEAR(s["energy_balance_relative"].get<double>(), 0.0, 1e-14);
  EXPECT_EQ(s["snap_back"], false);
  EXPECT_EQ(s["jumps"], 0);  // the bar's path needs none
  EXPECT_EQ(s["jump_dissipated_J_m"], 0.0);
  EXPECT_EQ(s["provenance"]["program"], "uhpc-micro run");
  const H5Reader h5(out / "curves.h5");
  EXPECT_EQ(h5.units("states/sigma_bar"), "Pa");
  EXPECT_EQ(h5.units("states/bulk_energy"), "J/m");
  EXPECT_EQ(h5.units("states/jump_dissipated"), "J/m");
  EXPECT_EQ(h5.units("states/psi_bar"), "J/m^3");
  EXPECT_EQ(h5.units("states/d_energy"), "1");
  EXPECT_EQ(h5.read_doubles("states/strain").values.size(), 111u);
  const auto grid = h5.read_doubles("resampled/strain").values;
  const auto d = h5.read_doubles("resampled/damage").values;
  ASSERT_EQ(grid.size(), 301u);
  for (std::size_t j = 0; j < grid.size(); ++j) EXPECT_NEAR(d[j], bar.damage(grid[j]), 5e-3) << grid[j];
  EXPECT_EQ(h5.string_attribute("", "status"), "separated");
  EXPECT_EQ(h5.provenance().program, "uhpc-micro run");
}

TEST_F(MicroRunCommands, RunOfAFailedCellWritesItsDiagnosticAndExitsOne) {
  const fs::path out = dir_ / "run";
  testing::internal::CaptureStderr();
  const int code = run(run_config(), {"analysis.fail_on=[0,0]", "cell.discretization.mesh=false"}, out);
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_EQ(code, kExitNumerical);
  EXPECT_NE(err.find("numerical failure: cell 3.00 mm, seed 1: Newton did not converge at step 15"), std::string::npos)
      << err;
  const nlohmann::json s = read_json(out / "summary.json");
  EXPECT_EQ(s["status"], "failed");
  EXPECT_EQ(s["diagnostic"], "Newton did not converge at step 15");
  EXPECT_EQ(s["steps"], 14);
  EXPECT_EQ(H5Reader(out / "curves.h5").read_doubles("states/strain").values.size(), 15u);
}

TEST_F(MicroRunCommands, RunOfAThrowingAnalyzerRecordsTheMessage) {
  const fs::path out = dir_ / "run";
  testing::internal::CaptureStderr();
  EXPECT_EQ(run(run_config(), {"analysis.throw_on=[0,0]", "cell.discretization.mesh=false"}, out), kExitNumerical);
  testing::internal::GetCapturedStderr();
  const nlohmann::json s = read_json(out / "summary.json");
  EXPECT_EQ(s["status"], "failed");
  EXPECT_EQ(s["diagnostic"], "analyzer threw: boom");
  EXPECT_TRUE(s["peak_stress_Pa"].is_null());
}

TEST_F(MicroRunCommands, BadConfigExitsTwoWithOneLineNamingFileAndKey) {
  const fs::path config = run_config();
  const std::string file = config.string();
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"bridging.strain_control=maximum",
       file + ": key 'bridging.strain_control': value 'maximum' is not one of: first_passage, max_below"},
      {"strain_grid.points=1", file + ": key 'strain_grid.points': value 1 is out of range, must be in [2, 1000000]"},
      {"analysis.tensile_strength_Pa=-1",
       file + ": key 'analysis.tensile_strength_Pa': value -1 is out of range, must be > 0"},
      {"analysis.tensile_strength=1", file + ": key 'analysis.tensile_strength': unknown key (did you mean "
                                             "'tensile_strength_Pa'?)"},
  };
  for (const auto& [set, message] : cases) {
    testing::internal::CaptureStderr();
    const int code = run(config, {set}, dir_ / "bad");
    const std::string err = testing::internal::GetCapturedStderr();
    EXPECT_EQ(code, kExitBadInput) << set;
    EXPECT_EQ(err, "error: " + message + "\n") << set;
  }
  EXPECT_EQ(log_.calls, 0);
  EXPECT_FALSE(fs::exists(dir_ / "bad" / "summary.json"));
}

// The config's "cell_overrides" set cell config keys for the command's cells, exactly as --set cell.<key>
// would (same mesh, same cell hash); --set still wins; a misspelt key is an error naming the cell file.
TEST_F(MicroRunCommands, ConfigCellOverridesActLikeSetAndSetWins) {
  const nlohmann::json coarse = {{"discretization", {{"nominal_spacing_m", 2e-4}}}};
  const fs::path with = write_config("with.json", {{"cell_overrides", coarse}});
  const fs::path without = run_config();
  ASSERT_EQ(run(with, {}, dir_ / "a"), kExitOk);
  ASSERT_EQ(run(without, {"cell.discretization.nominal_spacing_m=2e-4"}, dir_ / "b"), kExitOk);
  ASSERT_EQ(run(without, {}, dir_ / "c"), kExitOk);
  ASSERT_EQ(run(with, {"cell.discretization.nominal_spacing_m=1.5e-4"}, dir_ / "d"), kExitOk);
  ASSERT_EQ(run(without, {"cell.discretization.nominal_spacing_m=1.5e-4"}, dir_ / "e"), kExitOk);
  const auto summary = [this](const char* d) { return read_json(dir_ / d / "summary.json"); };
  EXPECT_EQ(summary("a")["nodes"], summary("b")["nodes"]);
  EXPECT_EQ(summary("a")["cell_hash"], summary("b")["cell_hash"]);
  EXPECT_LT(summary("a")["nodes"].get<int>(), summary("c")["nodes"].get<int>());  // coarser than the shipped mesh
  EXPECT_EQ(summary("d")["cell_hash"], summary("e")["cell_hash"]);
  EXPECT_NE(summary("d")["cell_hash"], summary("a")["cell_hash"]);

  const fs::path bad = write_config("bad.json", {{"cell_overrides", {{"discretization", {{"nominal_spacing", 1e-4}}}}}});
  testing::internal::CaptureStderr();
  EXPECT_EQ(run(bad, {}, dir_ / "bad"), kExitBadInput);
  EXPECT_EQ(testing::internal::GetCapturedStderr(),
            "error: " + std::string(UHPC_DATA_DIR) +
                "/micro_cell.json: key 'discretization.nominal_spacing': unknown key (did you mean "
                "'nominal_spacing_m'?)\n");
}

// A cell whose discrete operator parts from its stored energy is left out of the mean and listed;
// a looser bound takes it back.
TEST_F(MicroRunCommands, EnsembleLeavesSuspectCellsOutOfTheMean) {
  const fs::path config = ensemble_config({0.003}, 2);
  const std::vector<std::string> sets = {"cell.discretization.mesh=false", "analysis.suspect_on=[0,1]"};
  testing::internal::CaptureStderr();
  ASSERT_EQ(ensemble(config, sets, dir_ / "ens"), kExitOk);
  testing::internal::GetCapturedStderr();
  const nlohmann::json s = read_json(dir_ / "ens" / "summary.json");
  EXPECT_EQ(s["cells_suspect"], 1);
  EXPECT_EQ(s["cells_failed"], 0);
  const nlohmann::json& s0 = s["sizes"][0];
  EXPECT_EQ(s0["cells_averaged"], 1);
  ASSERT_EQ(s0["suspects"].size(), 1u);
  EXPECT_EQ(s0["suspects"][0]["realization"], 1);
  EXPECT_EQ(s0["suspects"][0]["status"], "separated");
  EXPECT_DOUBLE_EQ(s0["suspects"][0]["operator_energy_mismatch"].get<double>(), 0.5);

  std::vector<std::string> loose = sets;
  loose.push_back("max_operator_mismatch=1");
  testing::internal::CaptureStderr();
  ASSERT_EQ(ensemble(config, loose, dir_ / "ens"), kExitOk);
  testing::internal::GetCapturedStderr();
  EXPECT_EQ(read_json(dir_ / "ens" / "summary.json")["sizes"][0]["cells_averaged"], 2);
}

TEST_F(MicroRunCommands, EnsembleRecordsFailuresResumesAndFeedsTheCalibrateReader) {
  const fs::path config = ensemble_config({0.003, 0.0065}, 3);
  const fs::path out = dir_ / "ens";
  const std::vector<std::string> sets = {"cell.discretization.mesh=false", "analysis.throw_on=[0,1]",
                                         "analysis.fail_on=[0,2]"};
  testing::internal::CaptureStderr();
  ASSERT_EQ(ensemble(config, sets, out), kExitOk);
  testing::internal::GetCapturedStderr();
  EXPECT_EQ(log_.calls, 6);
  nlohmann::json s = read_json(out / "summary.json");
  EXPECT_EQ(s["cells"], 6);
  EXPECT_EQ(s["cells_failed"], 2);
  EXPECT_EQ(s["cells_reloaded"], 0);
  const nlohmann::json& s0 = s["sizes"][0];
  EXPECT_EQ(s0["cells_failed"], 2);
  EXPECT_EQ(s0["cells_averaged"], 1);
  ASSERT_EQ(s0["failures"].size(), 2u);
  EXPECT_EQ(s0["failures"][0]["realization"], 1);
  EXPECT_EQ(s0["failures"][0]["diagnostic"], "analyzer threw: boom");
  EXPECT_EQ(s0["failures"][1]["diagnostic"], "Newton did not converge at step 15");
  EXPECT_EQ(s0["failures"][1]["directory"], "size_3.0mm/cell_02");
  EXPECT_EQ(read_json(out / "size_3.0mm" / "cell_01" / "summary.json")["status"], "failed");
  const nlohmann::json& s1 = s["sizes"][1];
  EXPECT_EQ(s1["cells_averaged"], 3);
  // 6.5 mm > 2 l_ch: every bar snaps back, so under strain control d jumps 0 -> 1 at e_t = f_t / E.
  double mean_e_t = 0.0;
  for (const auto& seed : s1["seeds"]) {
    mean_e_t += 2.27e7 * (1.0 + 0.1 * (static_cast<double>(seed.get<std::uint64_t>() % 1000) / 999.0 - 0.5)) /
                4.4296e10 / 3.0;
  }
  EXPECT_NEAR(s1["strain_at_half_damage"]["mean"].get<double>(), mean_e_t, 1e-15);
  EXPECT_GT(s1["peak_stress_Pa"]["std"].get<double>(), 0.0);

  const Ensemble e = read_ensemble(out / "ensemble.h5");  // the calibrate reader
  EXPECT_EQ(e.sizes_m, (std::vector<double>{0.003, 0.0065}));
  EXPECT_EQ(e.cells, (std::vector<std::int64_t>{1, 3}));
  EXPECT_EQ(e.strain_count(), 301u);
  EXPECT_NEAR(e.nominal_strength_Pa[0], s0["peak_stress_Pa"]["mean"].get<double>(), 0.02 * 2.27e7);
  EXPECT_EQ(e.damage_std[0][150], 0.0);  // one cell
  EXPECT_EQ(e.damage_mean[1].back(), 1.0);
  EXPECT_EQ(e.provenance->program, "uhpc-micro ensemble");

  // Rerun: the finished cells are reloaded, the failed ones run again (retry_failed) and fail again.
  testing::internal::CaptureStderr();
  ASSERT_EQ(ensemble(config, sets, out, 1), kExitOk);
  const std::string progress_lines = testing::internal::GetCapturedStderr();
  // The 4 reloaded cells leave the count before the first solve: the progress counts the 2 reruns only.
  // Both reruns are 3.0 mm cells, so half the cells left are half the work left.
  EXPECT_NE(progress_lines.find("cells: 1/2 (50.0% of the work)"), std::string::npos) << progress_lines;
  EXPECT_EQ(progress_lines.find("/6 "), std::string::npos) << progress_lines;
  EXPECT_EQ(log_.calls, 8);
  s = read_json(out / "summary.json");
  EXPECT_EQ(s["cells_reloaded"], 4);
  const Ensemble again = read_ensemble(out / "ensemble.h5");
  EXPECT_EQ(again.damage_mean, e.damage_mean);
  EXPECT_EQ(again.stress_std_Pa, e.stress_std_Pa);

  // Failed cells kept: nothing runs.
  std::vector<std::string> keep = sets;
  keep.push_back("retry_failed=false");
  testing::internal::CaptureStderr();
  ASSERT_EQ(ensemble(config, keep, out), kExitOk);
  testing::internal::GetCapturedStderr();
  EXPECT_EQ(log_.calls, 8);
  EXPECT_EQ(read_json(out / "summary.json")["cells_reloaded"], 6);

  // Other post-processing: nothing runs, the grid changes in ensemble.h5 and in the cells' files.
  std::vector<std::string> coarse = keep;
  coarse.push_back("strain_grid.points=51");
  testing::internal::CaptureStderr();
  ASSERT_EQ(ensemble(config, coarse, out), kExitOk);
  testing::internal::GetCapturedStderr();
  EXPECT_EQ(log_.calls, 8);
  EXPECT_EQ(read_ensemble(out / "ensemble.h5").strain_count(), 51u);
  EXPECT_EQ(H5Reader(out / "size_6.5mm" / "cell_00" / "curves.h5").read_doubles("resampled/strain").values.size(), 51u);

  // Another analysis: every cell runs again.
  std::vector<std::string> other = coarse;
  other.push_back("analysis.fracture_energy_J_m2=40");
  testing::internal::CaptureStderr();
  ASSERT_EQ(ensemble(config, other, out), kExitOk);
  testing::internal::GetCapturedStderr();
  EXPECT_EQ(log_.calls, 14);
}

// A finished cell whose files fail their checksums is computed again, with a warning naming it, and the
// ensemble is the same as before: one byte of a stress in curves.h5 flipped, then a digit of summary.json.
TEST_F(MicroRunCommands, EnsembleComputesAgainACorruptedFinishedCellWithAWarning) {
  const fs::path config = ensemble_config({0.003}, 2);
  const fs::path out = dir_ / "ens";
  const std::vector<std::string> sets = {"cell.discretization.mesh=false"};
  testing::internal::CaptureStderr();
  ASSERT_EQ(ensemble(config, sets, out), kExitOk);
  testing::internal::GetCapturedStderr();
  ASSERT_EQ(log_.calls, 2);
  const Ensemble before = read_ensemble(out / "ensemble.h5");
  const fs::path cell = out / "size_3.0mm" / "cell_01";

  const std::vector<double> sigma = H5Reader(cell / "curves.h5").read_doubles("states/sigma_bar").values;
  ASSERT_GT(sigma.size(), 4u);
  const double value = sigma[sigma.size() / 2];
  ASSERT_NE(value, 0.0);
  std::string bytes = test::read_file(cell / "curves.h5");
  const std::size_t at = bytes.find(std::string(reinterpret_cast<const char*>(&value), sizeof value));
  ASSERT_NE(at, std::string::npos);
  bytes[at + 3] ^= 0x01;
  std::ofstream(cell / "curves.h5", std::ios::binary | std::ios::trunc) << bytes;
  testing::internal::CaptureStderr();
  testing::internal::CaptureStdout();  // the log (spdlog's default logger writes to stdout here)
  ASSERT_EQ(ensemble(config, sets, out), kExitOk);
  std::string log = testing::internal::GetCapturedStdout();
  testing::internal::GetCapturedStderr();
  EXPECT_EQ(log_.calls, 3);
  EXPECT_NE(log.find(cell.string() + ": the finished cell does not read back (" + (cell / "curves.h5").string() +
                     ": dataset 'states/sigma_bar': "),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("it is computed again"), std::string::npos) << log;
  EXPECT_EQ(read_ensemble(out / "ensemble.h5").stress_mean_Pa, before.stress_mean_Pa);

  std::string summary = test::read_file(cell / "summary.json");
  const std::size_t digit = summary.find("\"dofs\": ") + 8;
  summary[digit] = summary[digit] == '7' ? '8' : '7';
  std::ofstream(cell / "summary.json", std::ios::trunc) << summary;
  testing::internal::CaptureStderr();
  testing::internal::CaptureStdout();
  ASSERT_EQ(ensemble(config, sets, out), kExitOk);
  log = testing::internal::GetCapturedStdout();
  testing::internal::GetCapturedStderr();
  EXPECT_EQ(log_.calls, 4);
  EXPECT_NE(log.find(cell.string() + ": the finished cell does not read back (summary.json: its values do not match "
                                     "'checksum_fnv1a64'): it is computed again"),
            std::string::npos)
      << log;
  EXPECT_EQ(read_ensemble(out / "ensemble.h5").stress_mean_Pa, before.stress_mean_Pa);
}

TEST_F(MicroRunCommands, EnsembleWithASizeWithoutUsableCellsExitsOneAndWritesTheRest) {
  const fs::path out = dir_ / "ens";
  testing::internal::CaptureStderr();
  const int code = ensemble(ensemble_config({0.003, 0.0045}, 1), {"cell.discretization.mesh=false", "analysis.throw_on=[0,0]"}, out);
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_EQ(code, kExitNumerical);
  EXPECT_NE(err.find("numerical failure: 1 of 2 sizes have no cell to average (ensemble.h5 holds the others)"),
            std::string::npos)
      << err;
  const nlohmann::json s = read_json(out / "summary.json");
  EXPECT_EQ(s["sizes_without_cells_m"], nlohmann::json::array({0.003}));
  EXPECT_TRUE(s["sizes"][0]["nominal_strength_Pa"].is_null());
  EXPECT_EQ(read_ensemble(out / "ensemble.h5").sizes_m, std::vector<double>{0.0045});
}

TEST_F(MicroRunCommands, EnsembleBadConfigExitsTwo) {
  const fs::path config = ensemble_config({0.0065, 0.003}, 2);
  testing::internal::CaptureStderr();
  const int code = ensemble(config, {}, dir_ / "ens");
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_EQ(code, kExitBadInput);
  EXPECT_EQ(err, "error: " + config.string() +
                     ": key 'cell_sizes_m': must be strictly ascending, but entry 1 (0.003) follows 0.0065\n");
  testing::internal::CaptureStderr();
  EXPECT_EQ(ensemble(ensemble_config({0.003}, 2), {"realizations=0"}, dir_ / "ens"), kExitBadInput);
  EXPECT_EQ(testing::internal::GetCapturedStderr(),
            "error: " + config.string() + ": key 'realizations': value 0 is out of range, must be in [1, 10000]\n");
  EXPECT_EQ(log_.calls, 0);
}

// One batch job per cell or per size (--only-cell, --only-size), then --assemble-only: the same
// ensemble.h5 as one run over every cell, no cell analysed twice, a failed cell kept by the assembly.
TEST_F(MicroRunCommands, EnsembleSelectionRunsPartsThenAssemblesTheSameEnsemble) {
  const fs::path config = ensemble_config({0.003, 0.0065}, 2);
  const fs::path out = dir_ / "parts";
  const std::vector<std::string> sets = {"cell.discretization.mesh=false", "analysis.fail_on=[0,1]"};
  EnsembleSelection cell0;
  cell0.only_cell = 0;
  testing::internal::CaptureStderr();
  ASSERT_EQ(ensemble(config, sets, out, 2, cell0), kExitOk);
  testing::internal::GetCapturedStderr();
  EXPECT_EQ(log_.calls, 2);  // realization 0 of both sizes
  EXPECT_TRUE(fs::exists(out / "size_3.0mm" / "cell_00" / "summary.json"));
  EXPECT_TRUE(fs::exists(out / "size_6.5mm" / "cell_00" / "summary.json"));
  EXPECT_FALSE(fs::exists(out / "size_3.0mm" / "cell_01"));
  EXPECT_FALSE(fs::exists(out / "ensemble.h5"));  // a part writes no ensemble file
  EXPECT_FALSE(fs::exists(out / "summary.json"));

  // Assembling before every cell is finished: bad input, nothing analysed.
  EnsembleSelection assemble;
  assemble.assemble_only = true;
  testing::internal::CaptureStderr();
  EXPECT_EQ(ensemble(config, sets, out, 2, assemble), kExitBadInput);
  EXPECT_EQ(testing::internal::GetCapturedStderr(),
            "error: --assemble-only: 2 of 4 cells in " + out.string() +
                " are not finished with this configuration (size_3.0mm/cell_01, size_6.5mm/cell_01): run them first "
                "(--only-cell, --only-size, or without --assemble-only)\n");
  EXPECT_EQ(log_.calls, 2);
  EXPECT_FALSE(fs::exists(out / "ensemble.h5"));

  EnsembleSelection big;
  big.only_size_mm = 6.5;
  testing::internal::CaptureStderr();
  ASSERT_EQ(ensemble(config, sets, out, 2, big), kExitOk);  // cell_00 reloaded, cell_01 analysed
  testing::internal::GetCapturedStderr();
  EXPECT_EQ(log_.calls, 3);
  EnsembleSelection failing;
  failing.only_size_mm = 3.0;
  failing.only_cell = 1;
  testing::internal::CaptureStderr();
  ASSERT_EQ(ensemble(config, sets, out, 2, failing), kExitOk);  // a failed cell is recorded, not an error
  testing::internal::GetCapturedStderr();
  EXPECT_EQ(log_.calls, 4);
  EXPECT_EQ(read_json(out / "size_3.0mm" / "cell_01" / "summary.json")["status"], "failed");
  EXPECT_FALSE(fs::exists(out / "ensemble.h5"));

  // The assembly analyses nothing, not even the failed cell that retry_failed would run again.
  testing::internal::CaptureStderr();
  ASSERT_EQ(ensemble(config, sets, out, 2, assemble), kExitOk);
  testing::internal::GetCapturedStderr();
  EXPECT_EQ(log_.calls, 4);
  const nlohmann::json s = read_json(out / "summary.json");
  EXPECT_EQ(s["cells_reloaded"], 4);
  EXPECT_EQ(s["cells_failed"], 1);

  // One run over every cell in another directory: the same ensemble, bit for bit.
  testing::internal::CaptureStderr();
  ASSERT_EQ(ensemble(config, sets, dir_ / "whole"), kExitOk);
  testing::internal::GetCapturedStderr();
  EXPECT_EQ(log_.calls, 8);
  const Ensemble parts = read_ensemble(out / "ensemble.h5"), whole = read_ensemble(dir_ / "whole" / "ensemble.h5");
  EXPECT_EQ(parts.cells, (std::vector<std::int64_t>{1, 2}));
  EXPECT_EQ(parts.cells, whole.cells);
  EXPECT_EQ(parts.damage_mean, whole.damage_mean);
  EXPECT_EQ(parts.damage_std, whole.damage_std);
  EXPECT_EQ(parts.stress_mean_Pa, whole.stress_mean_Pa);
  EXPECT_EQ(parts.stress_std_Pa, whole.stress_std_Pa);
  EXPECT_EQ(parts.nominal_strength_Pa, whole.nominal_strength_Pa);
  nlohmann::json sizes_parts = s["sizes"], sizes_whole = read_json(dir_ / "whole" / "summary.json")["sizes"];
  for (nlohmann::json* sizes : {&sizes_parts, &sizes_whole})
    for (auto& size : *sizes) {
      size.erase("cells_reloaded");  // every cell was reloaded by the assembly only
      size.erase("cell_wall_s");     // measured, as the runs' wall_s
    }
  EXPECT_EQ(sizes_parts, sizes_whole);
}

TEST_F(MicroRunCommands, EnsembleSelectionOutsideTheEnsembleExitsTwo) {
  const fs::path config = ensemble_config({0.003, 0.0045}, 2);
  const std::vector<std::string> sets = {"cell.discretization.mesh=false"};
  const auto message = [&](const EnsembleSelection& sel) {
    testing::internal::CaptureStderr();
    EXPECT_EQ(ensemble(config, sets, dir_ / "ens", 2, sel), kExitBadInput);
    return testing::internal::GetCapturedStderr();
  };
  EnsembleSelection size;
  size.only_size_mm = 4.0;
  EXPECT_EQ(message(size), "error: --only-size 4: not one of the ensemble's cell sizes (3, 4.5 mm)\n");
  EnsembleSelection cell;
  cell.only_cell = 2;
  EXPECT_EQ(message(cell), "error: --only-cell 2: out of range, the ensemble's realizations are 0 to 1\n");
  cell.only_cell = -1;
  EXPECT_EQ(message(cell), "error: --only-cell -1: out of range, the ensemble's realizations are 0 to 1\n");
  cell.assemble_only = true;
  cell.only_cell = 0;
  EXPECT_EQ(message(cell), "error: --assemble-only: cannot be combined with --only-size or --only-cell\n");
  EXPECT_EQ(log_.calls, 0);
  EXPECT_FALSE(fs::exists(dir_ / "ens"));
}

TEST_F(MicroRunCommands, ShippedConfigsAreValid) {
  // The data/ files parse and validate through the same readers (the probe reads the analysis
  // section with the fracture solver's reader); the first cell is generated and meshed, then the
  // probe stops it.
  int built = 0;
  const CellAnalyzerFactory probe = [&built](const Config& analysis, double curve_end_strain) -> CellAnalyzer {
    (void)read_cell_analysis_options(analysis, curve_end_strain);
    ++built;
    return [](const CellJob& job, const StateObserver&) -> CellResponse {
      EXPECT_TRUE(job.mesh);  // the shipped cell config meshes
      throw InputError("probe: stop after validation");
    };
  };
  testing::internal::CaptureStderr();
  EXPECT_EQ(run_main("t", [&] { return run_cell_command(std::string(UHPC_DATA_DIR) + "/micro_run.json", {}, dir_ / "a", probe); }),
            kExitBadInput);
  EXPECT_EQ(run_main("t", [&] {
              return run_ensemble_command(std::string(UHPC_DATA_DIR) + "/micro_analysis_ensemble.json", {}, dir_ / "b", 1,
                                          probe);
            }),
            kExitBadInput);
  const std::string err = testing::internal::GetCapturedStderr();  // progress lines go there too
  EXPECT_NE(err.find("error: probe: stop after validation\n"), err.rfind("error: probe: stop after validation\n")) << err;
  EXPECT_EQ(err.find("unknown key"), std::string::npos) << err;
  EXPECT_EQ(built, 2);
}

// Not a check: with UHPC_BAR_ENSEMBLE_OUT=DIR, runs the shipped ensemble config (4 sizes x 25 generated
// and meshed cells) with the closed-form bar as the analyzer into DIR, for timing the driver and for
// trying the chain into uhpc-calibrate (UHPC_BAR_ENSEMBLE_JOBS threads, default 2). Skipped otherwise.
TEST_F(MicroRunCommands, ShippedEnsembleWithTheBarAnalyzer) {
  const char* out = std::getenv("UHPC_BAR_ENSEMBLE_OUT");
  if (!out) GTEST_SKIP() << "set UHPC_BAR_ENSEMBLE_OUT=DIR to run";
  const char* jobs = std::getenv("UHPC_BAR_ENSEMBLE_JOBS");
  std::vector<std::string> sets;
  for (const auto& [key, value] : kAnalysis.items()) sets.push_back("analysis." + key + "=" + value.dump());
  EXPECT_EQ(run_main("uhpc-micro ensemble",
                     [&] {
                       return run_ensemble_command(std::string(UHPC_DATA_DIR) + "/micro_analysis_ensemble.json", sets,
                                                   out, jobs ? std::atoi(jobs) : 2, bar_factory(log_));
                     }),
            kExitOk);
}

}  // namespace
}  // namespace uhpc::micro
