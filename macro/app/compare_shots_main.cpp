// uhpc-compare-shots: uhpc-macro shots against the paper's experiments (Table 5) and the paper's own
// simulations (Table 8), or the spread of one shot over several runs (the spacing study).
//
//   uhpc-compare-shots --results DIR... --out OUTDIR [--experiments data/table5_ballistic_experiments.csv]
//                      [--paper data/table8_paper_simulations.csv] [--no-paper]
//                      [--projectile data/projectile.json] [--tolerance-m-s 1] [--require-experiments]
//   uhpc-compare-shots --spread --results DIR... --out OUTDIR [--reference NAME]
//
// Each DIR is a uhpc-macro output directory (or its result.json). In the first form a shot pairs with the
// experiment whose impact velocity is within the tolerance and is compared with it; a shot without one is
// listed with its residual velocity and empty experiment columns, outside the statistics (RMS, ranges).
// Two shots for one experiment, or a shot within the tolerance of two, are bad input. With
// --require-experiments every shot must match an experiment and every experiment a shot. Shots are listed
// by impact velocity. Writes OUTDIR/comparison.json, comparison.csv and comparison.md (a Markdown table); with --spread,
// OUTDIR/spread.json and spread.md. Bad input: one line naming the file and the reason, exit code 2.
// The computation is in shot_comparison.hpp.
#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "shot_comparison.hpp"
#include "uhpc/atomic_file.hpp"
#include "uhpc/cli.hpp"
#include "uhpc/config.hpp"
#include "uhpc/csv.hpp"
#include "uhpc/data_dir.hpp"
#include "uhpc/errors.hpp"
#include "uhpc/hash.hpp"
#include "uhpc/output_lock.hpp"
#include "uhpc/provenance.hpp"

namespace fs = std::filesystem;

namespace {

// A default input from the shipped data (uhpc/data_dir.hpp) when the option was not given.
std::string shipped_or(const std::string& given, const char* name) {
  return given.empty() ? (uhpc::shipped_data_dir() / name).string() : given;
}

// DIR or DIR/result.json -> (result file, label = the run directory's name).
std::pair<std::string, std::string> result_file_of(const std::string& arg) {
  fs::path p(arg);
  if (p.filename().empty()) p = p.parent_path();  // "out/shots/v610/"
  fs::path file = p.extension() == ".json" ? p : p / "result.json";
  const fs::path dir = file.parent_path();
  if (!fs::exists(file)) {
    if (fs::exists(dir / "diagnostic.json")) {
      uhpc::throw_input_error(file.string(), "",
                              "missing: the run failed (see " + (dir / "diagnostic.json").string() + ")");
    }
    uhpc::throw_input_error(file.string(), "", "cannot open file (No such file or directory)");
  }
  std::string label = fs::absolute(dir).lexically_normal().filename().string();
  if (label.empty()) label = dir.string();
  return {file.string(), label};
}

nlohmann::json read_json(const std::string& path) { return uhpc::Config::load(path).json(); }

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Compares uhpc-macro shots with the paper's experiments (Table 5) and simulations (Table 8), or "
      "the spread of one shot over several runs (--spread).",
      "uhpc-compare-shots"};
  std::vector<std::string> results;
  std::string out, experiments_path, paper_path, projectile_path, reference;
  double tolerance = 1.0;
  bool spread = false, no_paper = false, require_experiments = false;
  app.add_option("--results", results, "uhpc-macro output directories (or their result.json)")->required();
  app.add_option("--out", out, "output directory")->required();
  app.add_option("--experiments", experiments_path, "the experiments (Table 5 CSV; default: the shipped data's)");
  app.add_option("--paper", paper_path,
                 "the paper's simulations (Table 8 CSV, rows pair with the experiments by order; default: the "
                 "shipped data's)");
  app.add_flag("--no-paper", no_paper, "leave out the paper's simulations");
  app.add_option("--projectile", projectile_path, "projectile (mass_kg, diameter_m, density_kg_m3; default: the shipped data's)");
  app.add_option("--tolerance-m-s", tolerance, "pairing tolerance on the impact velocity [m/s]")
      ->check(CLI::PositiveNumber);
  app.add_flag("--require-experiments", require_experiments,
               "every shot must match an experiment and every experiment a shot (exit 2 otherwise)");
  app.add_flag("--spread", spread, "spread of one shot over the runs instead of the comparison with experiments");
  app.add_option("--reference", reference, "--spread: the reference run's directory name (default: the first)");
  return uhpc::run_main(app, [&] {
    app.parse(argc, argv);
    experiments_path = shipped_or(experiments_path, "table5_ballistic_experiments.csv");
    paper_path = shipped_or(paper_path, "table8_paper_simulations.csv");
    projectile_path = shipped_or(projectile_path, "projectile.json");
    std::vector<uhpc::macro::ShotResult> shots;
    std::string hashed;
    for (const auto& r : results) {
      const auto [file, label] = result_file_of(r);
      const nlohmann::json j = read_json(file);
      hashed += j.dump();
      shots.push_back(uhpc::macro::shot_from_result_json(j, file, label));
    }
    const fs::path out_dir(out);
    const uhpc::OutputLock lock = uhpc::lock_output_directory(out_dir, "uhpc-compare-shots");

    if (spread) {
      std::size_t ref = 0;
      if (!reference.empty()) {
        ref = shots.size();
        for (std::size_t i = 0; i < shots.size(); ++i) {
          if (shots[i].label == reference) ref = i;
        }
        if (ref == shots.size())
          throw uhpc::InputError("--reference " + reference + ": no run directory of that name among --results");
      }
      nlohmann::json s = uhpc::macro::shot_spread(shots, ref);
      s["provenance"] = uhpc::Provenance::make("uhpc-compare-shots --spread", uhpc::fnv1a64_hex(hashed)).to_json();
      uhpc::write_text_atomic(out_dir / "spread.json", s.dump(2) + "\n");
      const std::string md = uhpc::macro::shot_spread_markdown(s);
      uhpc::write_text_atomic(out_dir / "spread.md", md);
      std::fputs(md.c_str(), stdout);
      std::printf("\nwritten: %s, %s\n", (out_dir / "spread.json").c_str(), (out_dir / "spread.md").c_str());
      return uhpc::kExitOk;
    }

    uhpc::macro::ShotComparisonInput in;
    const uhpc::CsvTable experiments = uhpc::CsvTable::read(experiments_path);
    in.experiments = uhpc::macro::experiments_from_table(experiments);
    if (!no_paper) {
      const uhpc::CsvTable paper = uhpc::CsvTable::read(paper_path);
      in.paper = uhpc::macro::paper_simulations_from_table(paper);
      if (in.paper.size() != in.experiments.size()) {
        uhpc::throw_input_error(paper_path, "",
                                fmt::format("{} rows, but {} has {} (rows pair by order)", in.paper.size(),
                                            experiments_path, in.experiments.size()));
      }
    }
    const nlohmann::json projectile = read_json(projectile_path);
    in.masses = uhpc::macro::projectile_masses_from_json(projectile, projectile_path);
    if (require_experiments) {
      (void)uhpc::macro::pair_shots_with_experiments(in.experiments, experiments_path, shots, tolerance);
    }
    const auto experiment_of =
        uhpc::macro::match_shots_to_experiments(in.experiments, experiments_path, shots, tolerance);
    // Listed by impact velocity (ties: in the order given).
    std::vector<std::size_t> order(shots.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return shots[a].impact_velocity_m_s < shots[b].impact_velocity_m_s;
    });
    for (std::size_t i : order) {
      in.shots.push_back(shots[i]);
      in.experiment_of.push_back(experiment_of[i]);
    }

    nlohmann::json c = uhpc::macro::compare_shots(in);
    hashed += projectile.dump() + experiments_path + paper_path;
    c["inputs"] = {{"experiments", experiments_path},
                   {"paper", no_paper ? nlohmann::json(nullptr) : nlohmann::json(paper_path)},
                   {"projectile", projectile_path},
                   {"pairing_tolerance_m_s", tolerance},
                   {"require_experiments", require_experiments}};
    c["provenance"] = uhpc::Provenance::make("uhpc-compare-shots", uhpc::fnv1a64_hex(hashed)).to_json();
    uhpc::write_text_atomic(out_dir / "comparison.json", c.dump(2) + "\n");
    uhpc::write_text_atomic(out_dir / "comparison.csv", uhpc::macro::comparison_csv(c));
    const std::string md = uhpc::macro::comparison_markdown(c);
    uhpc::write_text_atomic(out_dir / "comparison.md", md);
    std::fputs(md.c_str(), stdout);
    std::printf("\nwritten: %s, comparison.csv, comparison.md\n", (out_dir / "comparison.json").c_str());
    return uhpc::kExitOk;
  });
}
