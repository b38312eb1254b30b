#include "shot_comparison.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "uhpc/errors.hpp"

namespace uhpc::macro {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kPi = 3.14159265358979323846;

// NaN (an undefined ratio, a missing value) becomes null in the JSON.
nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }
double get_or_nan(const nlohmann::json& j, const char* key) {
  return j.contains(key) && j.at(key).is_number() ? j.at(key).get<double>() : kNaN;
}

double percent_error(double experiment, double simulation) {
  return experiment != 0.0 ? (experiment - simulation) / experiment * 100.0 : kNaN;
}
double ke_reduction(double mass_kg, double v0, double vr) { return 0.5 * mass_kg * (v0 * v0 - vr * vr); }

std::vector<double> positive_column(const CsvTable& t, const std::string& name, bool allow_zero) {
  std::vector<double> c = t.column(name);
  for (std::size_t i = 0; i < c.size(); ++i) {
    if (c[i] < 0.0 || (!allow_zero && c[i] == 0.0)) {
      throw_input_error(t.source(), "",
                        fmt::format("column '{}', row {}: value {} is out of range, must be {}", name, i + 1, c[i],
                                    allow_zero ? ">= 0" : "> 0"));
    }
  }
  return c;
}

const nlohmann::json& member(const nlohmann::json& j, const std::string& source, const std::string& path,
                             const char* key) {
  const std::string full = path.empty() ? key : path + "." + key;
  if (!j.is_object() || !j.contains(key)) throw_input_error(source, full, "required key is missing");
  return j.at(key);
}
double required_number(const nlohmann::json& j, const std::string& source, const std::string& path, const char* key) {
  const nlohmann::json& v = member(j, source, path, key);
  const std::string full = path.empty() ? key : path + "." + key;
  if (!v.is_number()) throw_input_error(source, full, "expected a number, got " + v.dump());
  const double x = v.get<double>();
  if (!std::isfinite(x)) throw_input_error(source, full, "value is not finite");
  return x;
}
bool required_bool(const nlohmann::json& j, const std::string& source, const char* key) {
  const nlohmann::json& v = member(j, source, "", key);
  if (!v.is_boolean()) throw_input_error(source, key, "expected true or false, got " + v.dump());
  return v.get<bool>();
}

struct ErrorStats {
  int n = 0;
  double sum = 0.0, sum_sq = 0.0, max_abs = 0.0;
  double vr_min = kNaN, vr_max = kNaN, ke_min = kNaN, ke_max = kNaN;
  void add_residual(double error) {
    ++n;
    sum += error;
    sum_sq += error * error;
    max_abs = std::max(max_abs, std::abs(error));
  }
  static void extend(double& lo, double& hi, double v) {
    if (!std::isfinite(v)) return;
    lo = std::isfinite(lo) ? std::min(lo, v) : v;
    hi = std::isfinite(hi) ? std::max(hi, v) : v;
  }
  nlohmann::json to_json() const {
    return {{"shots", n},
            {"rms_residual_velocity_error_m_s", number(n > 0 ? std::sqrt(sum_sq / n) : kNaN)},
            {"mean_residual_velocity_error_m_s", number(n > 0 ? sum / n : kNaN)},
            {"max_abs_residual_velocity_error_m_s", number(n > 0 ? max_abs : kNaN)},
            {"velocity_reduction_error_min_percent", number(vr_min)},
            {"velocity_reduction_error_max_percent", number(vr_max)},
            {"ke_reduction_error_min_percent", number(ke_min)},
            {"ke_reduction_error_max_percent", number(ke_max)}};
  }
};

// Text of a JSON number for the tables: "" for null.
std::string cell(const nlohmann::json& v, int decimals) {
  if (v.is_null()) return "";
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number_integer()) return std::to_string(v.get<long long>());
  return fmt::format("{:.{}f}", v.get<double>(), decimals);
}
std::string csv_cell(const nlohmann::json& v) {
  if (v.is_null()) return "";
  if (v.is_number_float()) return fmt::format("{:.10g}", v.get<double>());
  std::string s = cell(v, 0);
  if (s.find_first_of(",\"") != std::string::npos) {
    std::string q = "\"";
    for (char c : s) q += (c == '"') ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
  }
  return s;
}

}  // namespace

const char* to_string(ShotOutcome outcome) {
  switch (outcome) {
    case ShotOutcome::Perforated:
      return "perforated";
    case ShotOutcome::Rebounded:
      return "rebounded";
    case ShotOutcome::NotPerforated:
      return "not_perforated";
  }
  return "?";
}

std::vector<Experiment> experiments_from_table(const CsvTable& table) {
  const auto t = positive_column(table, "thickness", false);
  const auto m = positive_column(table, "target_mass", false);
  const auto v0 = positive_column(table, "impact_velocity", false);
  const auto vr = positive_column(table, "residual_velocity", true);
  if (t.empty()) throw_input_error(table.source(), "", "no experiment rows");
  std::vector<Experiment> e(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (vr[i] >= v0[i]) {
      throw_input_error(
          table.source(), "",
          fmt::format("row {}: residual velocity {} m/s is not below the impact velocity {} m/s", i + 1, vr[i], v0[i]));
    }
    e[i] = {t[i], m[i], v0[i], vr[i]};
  }
  return e;
}

std::vector<PaperSimulation> paper_simulations_from_table(const CsvTable& table) {
  const auto v0 = positive_column(table, "impact_velocity", false);
  const auto vr = positive_column(table, "residual_velocity", true);
  const auto dv = table.column("velocity_reduction");
  const auto dv_err = table.column("velocity_reduction_error");
  const auto ke = table.column("ke_reduction");
  const auto ke_err = table.column("ke_reduction_error");
  if (v0.empty()) throw_input_error(table.source(), "", "no simulation rows");
  std::vector<PaperSimulation> p(v0.size());
  for (std::size_t i = 0; i < v0.size(); ++i) p[i] = {v0[i], vr[i], dv[i], dv_err[i], ke[i], ke_err[i]};
  return p;
}

ProjectileMasses projectile_masses_from_json(const nlohmann::json& j, const std::string& source) {
  ProjectileMasses m;
  m.stated_kg = required_number(j, source, "", "mass_kg");
  const double d = required_number(j, source, "", "diameter_m");
  const double rho = required_number(j, source, "", "density_kg_m3");
  if (m.stated_kg <= 0)
    throw_input_error(source, "mass_kg", fmt::format("value {} is out of range, must be > 0", m.stated_kg));
  if (d <= 0) throw_input_error(source, "diameter_m", fmt::format("value {} is out of range, must be > 0", d));
  if (rho <= 0) throw_input_error(source, "density_kg_m3", fmt::format("value {} is out of range, must be > 0", rho));
  m.solid_sphere_kg = kPi / 6.0 * d * d * d * rho;
  return m;
}

ShotResult shot_from_result_json(const nlohmann::json& j, const std::string& source, const std::string& label) {
  if (!j.is_object()) throw_input_error(source, "", "expected a JSON object (a uhpc-macro result.json)");
  ShotResult s;
  s.source = source;
  s.label = label;
  s.impact_velocity_m_s = required_number(j, source, "", "impact_velocity_m_s");
  if (s.impact_velocity_m_s <= 0) {
    throw_input_error(source, "impact_velocity_m_s",
                      fmt::format("value {} is out of range, must be > 0", s.impact_velocity_m_s));
  }
  const bool perforated = required_bool(j, source, "perforated");
  const bool rebounded = required_bool(j, source, "rebounded");
  if (perforated && rebounded) throw_input_error(source, "rebounded", "a shot cannot both perforate and rebound");
  s.outcome = perforated ? ShotOutcome::Perforated : rebounded ? ShotOutcome::Rebounded : ShotOutcome::NotPerforated;
  const nlohmann::json& vr = member(j, source, "", "residual_velocity_m_s");
  if (perforated || rebounded) {
    s.raw_residual_velocity_m_s = required_number(j, source, "", "residual_velocity_m_s");
    if (perforated && s.raw_residual_velocity_m_s < 0) {
      throw_input_error(source, "residual_velocity_m_s",
                        fmt::format("value {} is negative although the shot perforated", s.raw_residual_velocity_m_s));
    }
  } else if (!vr.is_null() && !vr.is_number()) {
    throw_input_error(source, "residual_velocity_m_s", "expected a number or null, got " + vr.dump());
  }
  s.final_velocity_m_s = get_or_nan(j, "final_velocity_m_s");
  s.end_time_s = get_or_nan(j, "end_time_s");
  s.wall_time_s = required_number(j, source, "", "wall_time_s");
  if (j.contains("outcome") && j.at("outcome").is_string()) s.run_outcome = j.at("outcome").get<std::string>();
  s.particle_count = static_cast<long long>(required_number(j, source, "", "particle_count"));
  s.steps = static_cast<long long>(required_number(j, source, "", "steps"));
  const nlohmann::json& energy = member(j, source, "", "energy");
  const nlohmann::json& momentum = member(j, source, "", "momentum");
  s.energy_balance_error = required_number(energy, source, "energy", "balance_error");
  s.momentum_balance_error = required_number(momentum, source, "momentum", "balance_error");
  s.energy_worst_balance_error = get_or_nan(energy, "worst_balance_error");
  s.momentum_worst_balance_error = get_or_nan(momentum, "worst_balance_error");
  s.initial_kinetic_J = get_or_nan(energy, "initial_kinetic_J");
  return s;
}

namespace {

// The experiment within `tolerance_m_s` of shot s, kNoExperiment when none; InputError when two are.
std::size_t experiment_within(const std::vector<Experiment>& experiments, const std::string& experiments_source,
                              const ShotResult& shot, double tolerance_m_s) {
  std::size_t match = kNoExperiment;
  for (std::size_t e = 0; e < experiments.size(); ++e) {
    if (std::abs(shot.impact_velocity_m_s - experiments[e].impact_velocity_m_s) > tolerance_m_s) continue;
    if (match != kNoExperiment) {
      throw_input_error(shot.source, "",
                        fmt::format("impact velocity {} m/s matches two experiments of {} ({} and {} m/s) within {} m/s",
                                    shot.impact_velocity_m_s, experiments_source,
                                    experiments[match].impact_velocity_m_s, experiments[e].impact_velocity_m_s,
                                    tolerance_m_s));
    }
    match = e;
  }
  return match;
}

}  // namespace

std::vector<std::size_t> match_shots_to_experiments(const std::vector<Experiment>& experiments,
                                                    const std::string& experiments_source,
                                                    const std::vector<ShotResult>& shots, double tolerance_m_s) {
  std::vector<std::size_t> experiment_of(shots.size(), kNoExperiment);
  std::vector<std::size_t> shot_of(experiments.size(), kNoExperiment);
  for (std::size_t s = 0; s < shots.size(); ++s) {
    const std::size_t match = experiment_within(experiments, experiments_source, shots[s], tolerance_m_s);
    if (match == kNoExperiment) continue;
    if (shot_of[match] != kNoExperiment) {
      throw_input_error(
          shots[s].source, "",
          fmt::format("impact velocity {} m/s pairs with the {} m/s experiment that {} already pairs with",
                      shots[s].impact_velocity_m_s, experiments[match].impact_velocity_m_s,
                      shots[shot_of[match]].source));
    }
    shot_of[match] = s;
    experiment_of[s] = match;
  }
  return experiment_of;
}

std::vector<std::size_t> pair_shots_with_experiments(const std::vector<Experiment>& experiments,
                                                     const std::string& experiments_source,
                                                     const std::vector<ShotResult>& shots, double tolerance_m_s) {
  // Every shot must match: the first one that does not is named (before any duplicate further on).
  for (const auto& shot : shots) {
    if (experiment_within(experiments, experiments_source, shot, tolerance_m_s) == kNoExperiment) {
      throw_input_error(shot.source, "",
                        fmt::format("impact velocity {} m/s matches no experiment of {} (within {} m/s)",
                                    shot.impact_velocity_m_s, experiments_source, tolerance_m_s));
    }
  }
  const std::vector<std::size_t> experiment_of =
      match_shots_to_experiments(experiments, experiments_source, shots, tolerance_m_s);
  std::vector<std::size_t> shot_of(experiments.size(), kNoExperiment);
  for (std::size_t s = 0; s < shots.size(); ++s) shot_of[experiment_of[s]] = s;
  for (std::size_t e = 0; e < experiments.size(); ++e) {
    if (shot_of[e] == kNoExperiment) {
      throw_input_error(
          experiments_source, "",
          fmt::format("row {} (impact velocity {} m/s) has no shot among the {} result(s) given (within {} m/s)", e + 1,
                      experiments[e].impact_velocity_m_s, shots.size(), tolerance_m_s));
    }
  }
  return shot_of;
}

nlohmann::json compare_shots(const ShotComparisonInput& in) {
  const std::size_t n_exp = in.experiments.size();
  std::vector<std::size_t> experiment_of = in.experiment_of;
  if (experiment_of.empty()) {  // positional pairing: shots[i] with experiments[i]
    if (in.shots.size() != n_exp) {
      throw InputError(fmt::format("{} shot results for {} experiments", in.shots.size(), n_exp));
    }
    for (std::size_t i = 0; i < n_exp; ++i) experiment_of.push_back(i);
  } else if (experiment_of.size() != in.shots.size()) {
    throw InputError(fmt::format("{} experiment indices for {} shot results", experiment_of.size(), in.shots.size()));
  }
  for (std::size_t k : experiment_of) {
    if (k != kNoExperiment && k >= n_exp) {
      throw InputError(fmt::format("experiment index {} of {} experiments", k + 1, n_exp));
    }
  }
  if (!in.paper.empty() && in.paper.size() != n_exp) {
    throw InputError(fmt::format("{} rows of the paper's simulations for {} experiments (rows pair by order)",
                                 in.paper.size(), n_exp));
  }
  const double m = in.masses.stated_kg, m_paper = in.masses.solid_sphere_kg;
  nlohmann::json shots = nlohmann::json::array(), notes = nlohmann::json::array();
  ErrorStats ours, paper;
  int perforated = 0, rebounded = 0, not_perforated = 0, unmatched = 0;
  double wall = 0.0, worst_energy = 0.0, worst_momentum = 0.0;
  std::vector<bool> has_shot(n_exp, false);
  // Every value of a block null: the columns of a shot without an experiment.
  auto nulls = [](const nlohmann::json& block) {
    nlohmann::json j = block;
    for (auto& v : j) v = nullptr;
    return j;
  };
  // A stand-in experiment for the key layout of the null blocks.
  const Experiment layout{1.0, 1.0, 1.0, 0.0};
  for (std::size_t i = 0; i < in.shots.size(); ++i) {
    const bool matched = experiment_of[i] != kNoExperiment;
    const Experiment& e = matched ? in.experiments[experiment_of[i]] : layout;
    const ShotResult& s = in.shots[i];
    if (matched) has_shot[experiment_of[i]] = true;
    const double dv_exp = e.impact_velocity_m_s - e.residual_velocity_m_s;
    const double ke_exp = ke_reduction(m, e.impact_velocity_m_s, e.residual_velocity_m_s);
    const double vr = s.counted_residual_velocity_m_s();
    const double dv = s.impact_velocity_m_s - vr;
    const double ke = ke_reduction(m, s.impact_velocity_m_s, vr);
    const double dv_err = matched ? percent_error(dv_exp, dv) : kNaN;
    const double ke_err = matched ? percent_error(ke_exp, ke) : kNaN;
    const double vr_err = matched ? vr - e.residual_velocity_m_s : kNaN;
    if (matched) {
      ours.add_residual(vr_err);
      ErrorStats::extend(ours.vr_min, ours.vr_max, dv_err);
      ErrorStats::extend(ours.ke_min, ours.ke_max, ke_err);
    } else {
      ++unmatched;
    }
    (s.outcome == ShotOutcome::Perforated  ? perforated
     : s.outcome == ShotOutcome::Rebounded ? rebounded
                                           : not_perforated)++;
    wall += s.wall_time_s;
    worst_energy = std::max(worst_energy, std::abs(s.energy_balance_error));
    worst_momentum = std::max(worst_momentum, std::abs(s.momentum_balance_error));

    nlohmann::json experiment = {
        {"thickness_mm", e.thickness_mm},
        {"target_mass_kg", e.target_mass_kg},
        {"impact_velocity_m_s", e.impact_velocity_m_s},
        {"residual_velocity_m_s", e.residual_velocity_m_s},
        {"velocity_reduction_m_s", dv_exp},
        {"ke_reduction_J", ke_exp},
        {"ke_reduction_paper_mass_J", ke_reduction(m_paper, e.impact_velocity_m_s, e.residual_velocity_m_s)}};
    nlohmann::json row = {
        {"experiment_row", matched ? nlohmann::json(experiment_of[i] + 1) : nlohmann::json(nullptr)},
        {"matched", matched},
        {"label", s.label},
        {"result_file", s.source},
        {"experiment", matched ? experiment : nulls(experiment)},
        {"simulation",
         {{"impact_velocity_m_s", s.impact_velocity_m_s},
          {"outcome", to_string(s.outcome)},
          {"run_outcome", s.run_outcome.empty() ? nlohmann::json(nullptr) : nlohmann::json(s.run_outcome)},
          {"residual_velocity_m_s", vr},
          {"result_residual_velocity_m_s", s.outcome == ShotOutcome::NotPerforated
                                               ? nlohmann::json(nullptr)
                                               : nlohmann::json(s.raw_residual_velocity_m_s)},
          {"final_velocity_m_s", number(s.final_velocity_m_s)},
          {"end_time_s", number(s.end_time_s)},
          {"residual_velocity_error_m_s", number(vr_err)},
          {"velocity_reduction_m_s", dv},
          {"velocity_reduction_error_percent", number(dv_err)},
          {"ke_reduction_J", ke},
          {"ke_reduction_paper_mass_J", ke_reduction(m_paper, s.impact_velocity_m_s, vr)},
          {"ke_reduction_error_percent", number(ke_err)},
          {"energy_balance_error_fraction", s.energy_balance_error},
          {"energy_worst_balance_error_fraction", number(s.energy_worst_balance_error)},
          {"momentum_balance_error_fraction", s.momentum_balance_error},
          {"momentum_worst_balance_error_fraction", number(s.momentum_worst_balance_error)},
          {"wall_time_s", s.wall_time_s},
          {"particle_count", s.particle_count},
          {"steps", s.steps}}}};
    if (!in.paper.empty()) {
      const PaperSimulation& p = matched ? in.paper[experiment_of[i]] : PaperSimulation{1.0, 0.0, 0, 0, 0, 0};
      const double dv_p = p.impact_velocity_m_s - p.residual_velocity_m_s;
      const double ke_p = ke_reduction(m, p.impact_velocity_m_s, p.residual_velocity_m_s);
      const double dv_p_err = percent_error(dv_exp, dv_p), ke_p_err = percent_error(ke_exp, ke_p);
      if (matched) {
        paper.add_residual(p.residual_velocity_m_s - e.residual_velocity_m_s);
        ErrorStats::extend(paper.vr_min, paper.vr_max, dv_p_err);
        ErrorStats::extend(paper.ke_min, paper.ke_max, ke_p_err);
      }
      const nlohmann::json block = {
          {"impact_velocity_m_s", p.impact_velocity_m_s},
          {"residual_velocity_m_s", p.residual_velocity_m_s},
          {"residual_velocity_error_m_s", p.residual_velocity_m_s - e.residual_velocity_m_s},
          {"velocity_reduction_m_s", dv_p},
          {"velocity_reduction_error_percent", number(dv_p_err)},
          {"velocity_reduction_error_printed_percent", p.velocity_reduction_error_percent},
          {"ke_reduction_J", ke_p},
          {"ke_reduction_paper_mass_J", ke_reduction(m_paper, p.impact_velocity_m_s, p.residual_velocity_m_s)},
          {"ke_reduction_printed_J", p.ke_reduction_J},
          {"ke_reduction_error_percent", number(ke_p_err)},
          {"ke_reduction_error_printed_percent", p.ke_reduction_error_percent}};
      row["paper"] = matched ? block : nulls(block);
    }
    shots.push_back(std::move(row));

    // What a reader must know about this shot.
    if (s.outcome == ShotOutcome::Rebounded) {
      notes.push_back(
          fmt::format("{}: the sphere rebounded (result.json residual velocity {:.1f} m/s); counted as "
                      "residual velocity 0 in the reductions and errors",
                      s.label, s.raw_residual_velocity_m_s));
    } else if (s.outcome == ShotOutcome::NotPerforated) {
      if (std::isfinite(s.final_velocity_m_s) && s.final_velocity_m_s > 1.0) {
        notes.push_back(
            fmt::format("{}: the run ended (t = {:.3g} s) with the sphere still in the target moving at "
                        "{:.1f} m/s: not finished (extend run.end_time_s); counted as residual velocity 0",
                        s.label, s.end_time_s, s.final_velocity_m_s));
      } else {
        notes.push_back(
            fmt::format("{}: the sphere did not perforate (final axial velocity {:.1f} m/s); counted as "
                        "residual velocity 0",
                        s.label, s.final_velocity_m_s));
      }
    }
    if (std::isfinite(s.initial_kinetic_J)) {
      const double run_mass = 2.0 * s.initial_kinetic_J / (s.impact_velocity_m_s * s.impact_velocity_m_s);
      if (std::abs(run_mass - m) > 1e-3 * m) {
        notes.push_back(
            fmt::format("{}: the run's projectile mass (2 x initial kinetic energy / v0^2) is {:.4g} g, not "
                        "the {:.4g} g of the comparison: its joules are not comparable",
                        s.label, run_mass * 1e3, m * 1e3));
      }
    }
  }
  nlohmann::json without_shot = nlohmann::json::array();
  std::string without_text;
  for (std::size_t e = 0; e < n_exp; ++e) {
    if (has_shot[e]) continue;
    without_shot.push_back({{"experiment_row", e + 1},
                            {"impact_velocity_m_s", in.experiments[e].impact_velocity_m_s},
                            {"thickness_mm", in.experiments[e].thickness_mm}});
    without_text += fmt::format("{}row {} ({} m/s)", without_text.empty() ? "" : ", ", e + 1,
                                in.experiments[e].impact_velocity_m_s);
  }
  if (unmatched > 0) {
    notes.push_back(fmt::format(
        "{} of the {} shots have no experiment within the pairing tolerance: listed with their residual velocity, "
        "not in the RMS and the error ranges, which are over the {} shots with an experiment",
        unmatched, in.shots.size(), ours.n));
  }
  if (!without_text.empty()) {
    notes.push_back("experiments without a shot (not compared): " + without_text);
  }
  notes.push_back(
      fmt::format("kinetic-energy reductions in J use the stated projectile mass {:.4g} g; the paper's printed joules "
                  "imply the solid "
                  "sphere's {:.4g} g (*_paper_mass_J); the % errors do not depend on the mass",
                  m * 1e3, m_paper * 1e3));

  nlohmann::json summary_ours = ours.to_json();
  summary_ours["shots_total"] = in.shots.size();
  summary_ours["shots_without_experiment"] = unmatched;
  summary_ours["perforated"] = perforated;
  summary_ours["rebounded"] = rebounded;
  summary_ours["not_perforated"] = not_perforated;
  summary_ours["total_wall_time_s"] = wall;
  summary_ours["worst_final_energy_balance_error_fraction"] = worst_energy;
  summary_ours["worst_final_momentum_balance_error_fraction"] = worst_momentum;
  nlohmann::json summary = {{"simulation", summary_ours}};
  if (!in.paper.empty()) summary["paper"] = paper.to_json();
  return {{"conventions",
           {{"velocity_reduction_m_s", "v0 - vr"},
            {"ke_reduction_J", "1/2 m (v0^2 - vr^2)"},
            {"error_percent",
             "(experiment - simulation) / experiment x 100 (Tables 7-8; positive = reduction under-predicted)"},
            {"residual_velocity_error_m_s", "simulation - experiment (positive = sphere too fast)"},
            {"rms_residual_velocity_error_m_s", "sqrt(mean((vr_sim - vr_exp)^2))"},
            {"residual_velocity_m_s", "0 when the sphere did not perforate (rebounded or stopped)"},
            {"paper_pairing", "Table 8 rows pair with Table 5 rows by order"},
            {"statistics",
             "RMS, mean and ranges of the errors over the shots with an experiment only (summary.*.shots); "
             "outcome counts, wall time and balance errors over every shot (shots_total)"}}},
          {"projectile", {{"mass_kg", m}, {"paper_ke_mass_kg", m_paper}}},
          {"shots", shots},
          {"summary", summary},
          {"experiments_without_shot", without_shot},
          {"notes", notes}};
}

std::string comparison_csv(const nlohmann::json& c) {
  // The header cells are "<block>_<key>" with the unit moved into brackets: e.g. "simulation_wall_time [s]".
  static const std::vector<std::pair<std::string, std::string>> kUnits = {
      {"_m_s", "m/s"}, {"_percent", "%"}, {"_J", "J"}, {"_mm", "mm"}, {"_kg", "kg"}, {"_s", "s"}, {"_fraction", "1"}};
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  for (const auto& shot : c.at("shots")) {
    std::vector<std::string> names, values;
    auto add = [&](const std::string& name, const nlohmann::json& v) {
      names.push_back(name);
      values.push_back(csv_cell(v));
    };
    add("experiment_row", shot.at("experiment_row"));
    add("label", shot.at("label"));
    add("result_file", shot.at("result_file"));
    for (const char* block : {"experiment", "simulation", "paper"}) {
      if (!shot.contains(block)) continue;
      for (const auto& [key, v] : shot.at(block).items()) add(std::string(block) + "_" + key, v);
    }
    if (header.empty()) header = names;
    rows.push_back(values);
  }
  std::string out;
  for (std::size_t k = 0; k < header.size(); ++k) {
    std::string h = header[k];
    for (const auto& [suffix, unit] : kUnits) {
      if (h.size() > suffix.size() && h.compare(h.size() - suffix.size(), suffix.size(), suffix) == 0) {
        h = h.substr(0, h.size() - suffix.size()) + " [" + unit + "]";
        break;
      }
    }
    out += (k ? "," : "") + h;
  }
  out += "\n";
  for (const auto& r : rows) {
    for (std::size_t k = 0; k < r.size(); ++k) out += (k ? "," : "") + r[k];
    out += "\n";
  }
  return out;
}

std::string comparison_markdown(const nlohmann::json& c) {
  const bool with_paper = c.at("summary").contains("paper");
  std::string md;
  md += "| run | v0 run m/s | v0 exp m/s | t exp mm | vr exp m/s | vr ours m/s |";
  if (with_paper) md += " vr paper m/s |";
  md += " vr error ours m/s |";
  if (with_paper) md += " vr error paper m/s |";
  md += " dv error ours % |";
  if (with_paper) md += " dv error paper % |";
  md += " dKE error ours % |";
  if (with_paper) md += " dKE error paper % |";
  md += " energy balance | particles | wall min |\n|";
  const int cols = 12 + (with_paper ? 4 : 0);
  for (int k = 0; k < cols; ++k) md += "---|";
  md += "\n";
  for (const auto& shot : c.at("shots")) {
    const auto& e = shot.at("experiment");
    const auto& s = shot.at("simulation");
    std::string vr = cell(s.at("residual_velocity_m_s"), 0);
    const std::string outcome = s.at("outcome").get<std::string>();
    if (outcome == "rebounded") vr += " (rebound)";
    if (outcome == "not_perforated") {
      const auto& vf = s.at("final_velocity_m_s");
      vr += vf.is_number() && vf.get<double>() > 1.0 ? " (unfinished)" : " (stopped)";
    }
    md += fmt::format("| {} | {} | {} | {} | {} | {} |", shot.at("label").get<std::string>(),
                      cell(s.at("impact_velocity_m_s"), 0), cell(e.at("impact_velocity_m_s"), 0),
                      cell(e.at("thickness_mm"), 2), cell(e.at("residual_velocity_m_s"), 0), vr);
    if (with_paper) md += fmt::format(" {} |", cell(shot.at("paper").at("residual_velocity_m_s"), 0));
    md += fmt::format(" {} |", cell(s.at("residual_velocity_error_m_s"), 0));
    if (with_paper) md += fmt::format(" {} |", cell(shot.at("paper").at("residual_velocity_error_m_s"), 0));
    md += fmt::format(" {} |", cell(s.at("velocity_reduction_error_percent"), 1));
    if (with_paper) md += fmt::format(" {} |", cell(shot.at("paper").at("velocity_reduction_error_percent"), 1));
    md += fmt::format(" {} |", cell(s.at("ke_reduction_error_percent"), 1));
    if (with_paper) md += fmt::format(" {} |", cell(shot.at("paper").at("ke_reduction_error_percent"), 1));
    md += fmt::format(" {:.1e} | {} | {:.1f} |\n", s.at("energy_balance_error_fraction").get<double>(),
                      cell(s.at("particle_count"), 0), s.at("wall_time_s").get<double>() / 60.0);
  }
  const auto& so = c.at("summary").at("simulation");
  const int without = so.value("shots_without_experiment", 0);
  if (without > 0) {
    md += fmt::format(
        "\nStatistics over the {} shots with an experiment only ({} of the {} shots have none: their experiment "
        "and paper columns are empty).",
        so.at("shots").get<int>(), without, so.value("shots_total", 0));
  }
  md += fmt::format("\nRMS residual-velocity error over {} shots: ours {} m/s (mean {} m/s)", so.at("shots").get<int>(),
                    cell(so.at("rms_residual_velocity_error_m_s"), 1),
                    cell(so.at("mean_residual_velocity_error_m_s"), 1));
  if (with_paper) {
    const auto& sp = c.at("summary").at("paper");
    md += fmt::format(", the paper's {} m/s (mean {} m/s)", cell(sp.at("rms_residual_velocity_error_m_s"), 1),
                      cell(sp.at("mean_residual_velocity_error_m_s"), 1));
  }
  md +=
      fmt::format(". Velocity-reduction errors ours {} .. {} %", cell(so.at("velocity_reduction_error_min_percent"), 1),
                  cell(so.at("velocity_reduction_error_max_percent"), 1));
  if (with_paper) {
    const auto& sp = c.at("summary").at("paper");
    md += fmt::format(" (paper {} .. {} %)", cell(sp.at("velocity_reduction_error_min_percent"), 1),
                      cell(sp.at("velocity_reduction_error_max_percent"), 1));
  }
  md += fmt::format("; kinetic-energy-reduction errors ours {} .. {} %",
                    cell(so.at("ke_reduction_error_min_percent"), 1), cell(so.at("ke_reduction_error_max_percent"), 1));
  if (with_paper) {
    const auto& sp = c.at("summary").at("paper");
    md += fmt::format(" (paper {} .. {} %)", cell(sp.at("ke_reduction_error_min_percent"), 1),
                      cell(sp.at("ke_reduction_error_max_percent"), 1));
  }
  md += fmt::format(". Outcomes (every shot): {} perforated, {} rebounded, {} not perforated; total wall time {:.1f} min.\n",
                    so.at("perforated").get<int>(), so.at("rebounded").get<int>(), so.at("not_perforated").get<int>(),
                    so.at("total_wall_time_s").get<double>() / 60.0);
  md +=
      "\nErrors: % = (experiment - simulation) / experiment x 100 (the paper's Tables 7-8 sign); m/s = simulation - "
      "experiment. A shot that does not perforate counts with residual velocity 0.\n";
  for (const auto& note : c.at("notes")) md += "\n- " + note.get<std::string>();
  md += "\n";
  return md;
}

nlohmann::json shot_spread(const std::vector<ShotResult>& runs, std::size_t reference) {
  if (runs.empty()) throw InputError("no runs to compare");
  if (reference >= runs.size())
    throw InputError(fmt::format("reference run {} of {} runs", reference + 1, runs.size()));
  const double v_ref = runs[reference].impact_velocity_m_s;
  for (const auto& r : runs) {
    if (std::abs(r.impact_velocity_m_s - v_ref) > 1.0) {
      throw_input_error(r.source, "",
                        fmt::format("impact velocity {} m/s differs from the reference run's {} m/s ({}): a spread "
                                    "compares runs of one shot",
                                    r.impact_velocity_m_s, v_ref, runs[reference].source));
    }
  }
  const double vr_ref = runs[reference].counted_residual_velocity_m_s();
  double sum = 0.0, lo = std::numeric_limits<double>::infinity(), hi = -lo, max_diff = 0.0;
  for (const auto& r : runs) {
    const double vr = r.counted_residual_velocity_m_s();
    sum += vr;
    lo = std::min(lo, vr);
    hi = std::max(hi, vr);
    max_diff = std::max(max_diff, std::abs(vr - vr_ref));
  }
  const double mean = sum / static_cast<double>(runs.size());
  double var = 0.0;
  for (const auto& r : runs)
    var += (r.counted_residual_velocity_m_s() - mean) * (r.counted_residual_velocity_m_s() - mean);
  const double sd = runs.size() > 1 ? std::sqrt(var / static_cast<double>(runs.size() - 1)) : 0.0;
  nlohmann::json list = nlohmann::json::array(), notes = nlohmann::json::array();
  for (const auto& r : runs) {
    const double vr = r.counted_residual_velocity_m_s();
    list.push_back({{"label", r.label},
                    {"result_file", r.source},
                    {"particle_count", r.particle_count},
                    {"impact_velocity_m_s", r.impact_velocity_m_s},
                    {"outcome", to_string(r.outcome)},
                    {"residual_velocity_m_s", vr},
                    {"velocity_reduction_m_s", r.impact_velocity_m_s - vr},
                    {"difference_from_reference_m_s", vr - vr_ref},
                    {"energy_balance_error_fraction", r.energy_balance_error},
                    {"wall_time_s", r.wall_time_s}});
    if (r.outcome != ShotOutcome::Perforated) {
      notes.push_back(
          fmt::format("{}: {} (final axial velocity {:.1f} m/s at t = {:.3g} s); counted as residual velocity 0",
                      r.label, to_string(r.outcome), r.final_velocity_m_s, r.end_time_s));
    }
  }
  return {{"reference", runs[reference].label},
          {"runs", list},
          {"summary",
           {{"runs", runs.size()},
            {"mean_residual_velocity_m_s", mean},
            {"min_residual_velocity_m_s", lo},
            {"max_residual_velocity_m_s", hi},
            {"spread_m_s", hi - lo},
            {"standard_deviation_m_s", sd},
            {"max_abs_difference_from_reference_m_s", max_diff},
            {"spread_percent_of_impact_velocity", (hi - lo) / v_ref * 100.0}}},
          {"notes", notes}};
}

std::string shot_spread_markdown(const nlohmann::json& spread) {
  std::string md =
      "| run | particles | outcome | vr m/s | dv m/s | vr - reference m/s | energy balance | wall min |\n"
      "|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : spread.at("runs")) {
    md += fmt::format("| {} | {} | {} | {:.1f} | {:.1f} | {:+.1f} | {:.1e} | {:.1f} |\n",
                      r.at("label").get<std::string>(), r.at("particle_count").get<long long>(),
                      r.at("outcome").get<std::string>(), r.at("residual_velocity_m_s").get<double>(),
                      r.at("velocity_reduction_m_s").get<double>(), r.at("difference_from_reference_m_s").get<double>(),
                      r.at("energy_balance_error_fraction").get<double>(), r.at("wall_time_s").get<double>() / 60.0);
  }
  const auto& s = spread.at("summary");
  md += fmt::format(
      "\nResidual velocity over {} runs: mean {:.1f} m/s, {:.1f} .. {:.1f} m/s (spread {:.1f} m/s, "
      "{:.2f} % of the impact velocity; standard deviation {:.1f} m/s); largest difference from the "
      "reference run ({}) {:.1f} m/s.\n",
      s.at("runs").get<int>(), s.at("mean_residual_velocity_m_s").get<double>(),
      s.at("min_residual_velocity_m_s").get<double>(), s.at("max_residual_velocity_m_s").get<double>(),
      s.at("spread_m_s").get<double>(), s.at("spread_percent_of_impact_velocity").get<double>(),
      s.at("standard_deviation_m_s").get<double>(), spread.at("reference").get<std::string>(),
      s.at("max_abs_difference_from_reference_m_s").get<double>());
  for (const auto& note : spread.at("notes")) md += "\n- " + note.get<std::string>();
  if (!spread.at("notes").empty()) md += "\n";
  return md;
}

}  // namespace uhpc::macro
