#include "cell_results.hpp"

#include <chrono>
#include <cmath>
#include <fstream>
#include <mutex>
#include <stdexcept>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "cell_io.hpp"
#include "ensemble_curves.hpp"
#include "uhpc/atomic_file.hpp"
#include "uhpc/config.hpp"
#include "uhpc/errors.hpp"
#include "uhpc/hash.hpp"
#include "uhpc/hdf5_io.hpp"

namespace fs = std::filesystem;

namespace uhpc::micro {

PostOptions read_post_options(const Config& cfg) {
  PostOptions o;
  const Config b = cfg.section("bridging");
  o.bridging.strain_control = *strain_control_from_name(b.choice("strain_control", {"first_passage", "max_below"}));
  o.bridging.damage_measure = *damage_measure_from_name(b.choice("damage_measure", {"energy", "force"}));
  o.bridging_tolerance = b.number("tolerance", Range::open(0.0, 1.0));
  const Config g = cfg.section("strain_grid");
  o.grid_max_strain = g.number("max_strain", Range::open(0.0, 1.0));
  o.grid_points = static_cast<std::size_t>(g.integer("points", Range::closed(2, 1000000)));
  o.grid = strain_grid(o.grid_max_strain, o.grid_points);
  return o;
}

nlohmann::json post_options_json(const PostOptions& o) {
  return {{"strain_control", to_string(o.bridging.strain_control)},
          {"damage_measure", to_string(o.bridging.damage_measure)},
          {"bridging_tolerance", o.bridging_tolerance},
          {"strain_grid", {{"max_strain", o.grid_max_strain}, {"points", o.grid_points}}}};
}

std::string post_options_hash(const PostOptions& o) { return fnv1a64_hex(post_options_json(o).dump()); }

CellResult post_process(CellResponse response, const PostOptions& o) {
  CellResult r;
  r.response = std::move(response);
  try {
    r.path = bridge_energy(r.response);
    r.curve = strain_controlled_curve(r.response, r.path, o.bridging);
    r.resampled = resample(r.curve, o.grid, r.response.E0_bar_Pa);
    r.features = curve_features(r.response, r.path, r.curve);
    r.bridged = true;
  } catch (const std::invalid_argument& e) {
    r.bridging_error = e.what();
    if (r.response.status != CellStatus::Failed) {
      r.response.status = CellStatus::Failed;
      r.response.diagnostic = r.bridging_error;
    }
  }
  return r;
}

void prepare_cell(CellJob& job, const std::string& program) {
  static std::mutex gmsh_mutex;
  CellSettings settings = job.settings;
  settings.seed = job.seed;
  auto cell = std::make_shared<GeneratedCell>(generate_cell(settings.cell, job.seed));
  if (settings.mesh_enabled) {
    const std::lock_guard<std::mutex> lock(gmsh_mutex);
    job.mesh = std::make_shared<const CellDiscretization>(mesh_cell(cell->geometry, settings.mesh));
  }
  job.cell = cell;
  const Provenance provenance = Provenance::make(program, settings.config_hash, job.seed);
  write_text_atomic(job.out_dir / "cell.json", cell_json(*cell, settings, job.mesh.get(), provenance).dump(2) + "\n");
}

CellResponse run_analyzer(const CellAnalyzer& analyzer, const CellJob& job, const StateObserver& observe) {
  const auto t0 = std::chrono::steady_clock::now();
  CellResponse r;
  try {
    r = analyzer(job, observe);
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    r = CellResponse{};
    r.side_m = job.size_m;
    if (job.cell) r.porosity = job.cell->geometry.porosity();
    r.status = CellStatus::Failed;
    r.diagnostic = std::string(dynamic_cast<const NumericalError*>(&e) ? "numerical failure: " : "analyzer threw: ") +
                   e.what();
  }
  if (r.status == CellStatus::Failed && r.diagnostic.empty())
    r.diagnostic = "the analyzer returned status failed without a diagnostic";
  if (!(r.wall_s > 0.0)) r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

std::string cell_hash(const CellJob& job) {
  return fnv1a64_hex(fmt::format("{}|{:.17g}|{}|{}|{:.17g}|r{}", job.settings.config_hash, job.size_m, job.seed,
                                 without_notes(job.analysis).dump(), job.curve_end_strain, kFractureSolverRevision));
}

std::string former_cell_hash(const CellJob& job) {
  return fnv1a64_hex(fmt::format("{}|{:.17g}|{}|{}|{:.17g}|r{}", job.settings.config_hash_including_notes, job.size_m,
                                 job.seed, job.analysis.dump(), job.curve_end_strain, kFractureSolverRevision));
}

namespace {

template <typename F>
std::vector<double> column(const std::vector<CellState>& states, F f) {
  std::vector<double> v;
  v.reserve(states.size());
  for (const CellState& s : states) v.push_back(static_cast<double>(f(s)));
  return v;
}

template <typename F>
std::vector<std::int64_t> int_column(const std::vector<CellState>& states, F f) {
  std::vector<std::int64_t> v;
  v.reserve(states.size());
  for (const CellState& s : states) v.push_back(static_cast<std::int64_t>(f(s)));
  return v;
}

std::vector<double> as_doubles(const std::vector<bool>& b) {
  std::vector<double> v;
  for (bool x : b) v.push_back(x ? 1.0 : 0.0);
  return v;
}

nlohmann::json optional_number(const std::optional<double>& v) {
  return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
}

// The serial HDF5 library is not thread-safe (hdf5_io.hpp): the ensemble's workers take turns for
// their (short) file reads and writes; the analyses themselves run in parallel.
std::mutex& hdf5_mutex() {
  static std::mutex m;
  return m;
}

// summary.json carries a checksum of its own values: the 64-bit FNV-1a of the compact dump of the document
// without this key (object keys sorted, numbers in their shortest exact form, so that parsing the file and
// dumping it again gives the same text).
constexpr const char* kSummaryChecksumKey = "checksum_fnv1a64";

std::string summary_checksum(nlohmann::json j) {
  j.erase(kSummaryChecksumKey);
  return fnv1a64_hex(j.dump());
}

std::optional<CellStatus> status_from_name(const std::string& s) {
  if (s == "step_limit") return CellStatus::ReachedEnd;  // its earlier name, in the archived cells
  for (CellStatus c : {CellStatus::Separated, CellStatus::ReachedEnd, CellStatus::Failed})
    if (s == to_string(c)) return c;
  return std::nullopt;
}

}  // namespace

nlohmann::json cell_summary_json(const CellJob& job, const CellResult& r, const PostOptions& o,
                                 const Provenance& provenance) {
  const CellResponse& resp = r.response;
  const CurveFeatures& f = r.features;
  nlohmann::json j;
  j["format"] = kCellSummaryFormat;
  j["status"] = to_string(resp.status);
  j["diagnostic"] = resp.diagnostic;
  j["cell"] = {{"size_m", job.size_m},      {"seed", job.seed},
               {"size_index", job.size_index}, {"realization", job.realization},
               {"porosity", resp.porosity}, {"side_m", resp.side_m}};
  j["E0_bar_Pa"] = resp.E0_bar_Pa;
  const std::size_t n = resp.states.size();
  j["steps"] = n > 0 ? n - 1 : 0;
  int newton = 0;
  double max_opening = 0.0;
  for (const CellState& s : resp.states) {
    newton += s.newton_iterations;
    max_opening = std::max(max_opening, s.max_opening_m);
  }
  j["newton_iterations"] = newton;
  j["max_opening_m"] = max_opening;
  if (r.bridged) {
    j["peak_stress_Pa"] = f.peak_stress_Pa;
    j["strain_at_peak"] = f.strain_at_peak;
    j["strain_at_half_damage"] = optional_number(f.strain_at_half_damage);
    j["max_strain"] = f.max_strain;
    j["dissipated_energy_J_m"] = f.dissipated_J_m;
    j["dissipated_energy_density_J_m3"] = f.dissipated_per_area_J_m3;
    const CellState& last = resp.states.back();
    const double stored = last.accounted_energy_J_m();
    j["external_work_J_m"] = last.external_work_J_m;
    j["jump_dissipated_J_m"] = last.jump_dissipated_J_m;
    // Work balance at the last state: external work = stored + dissipated + released in jumps (quasi-static
    // between them, no kinetic energy).
    j["energy_balance_relative"] =
        last.external_work_J_m != 0.0 ? (last.external_work_J_m - stored) / last.external_work_J_m : 0.0;
    j["bridging"] = {{"max_abs_difference", r.path.max_abs_difference},
                     {"at_state", r.path.max_difference_state},
                     {"at_strain", resp.states[r.path.max_difference_state].strain},
                     {"tolerance", o.bridging_tolerance},
                     {"within_tolerance", r.path.max_abs_difference <= o.bridging_tolerance}};
    j["snap_back"] = r.curve.snap_back;
    j["snap_back_jumps"] = r.curve.jumps;
    j["grid"] = {{"valid_points", r.resampled.valid_points}, {"complete", r.resampled.complete}};
  } else {
    for (const char* k : {"peak_stress_Pa", "strain_at_peak", "strain_at_half_damage", "max_strain",
                          "dissipated_energy_J_m", "dissipated_energy_density_J_m3", "external_work_J_m",
                          "energy_balance_relative", "jump_dissipated_J_m", "bridging", "snap_back", "snap_back_jumps", "grid"})
      j[k] = nullptr;
    j["bridging_error"] = r.bridging_error;
  }
  j["nodes"] = resp.nodes;
  j["dofs"] = resp.dofs;
  j["enriched_nodes"] = resp.enriched_nodes;
  j["growth_unloads"] = resp.growth_unloads;
  j["jumps"] = resp.jumps;
  j["factorizations"] = resp.factorizations;
  j["crack_geometries"] = resp.crack_geometries;
  j["krylov_corrections"] = resp.krylov_corrections;
  j["krylov_products"] = resp.krylov_products;
  j["operator_energy_mismatch"] = resp.operator_energy_mismatch;
  j["wall_s"] = resp.wall_s;
  j["post_options"] = post_options_json(o);
  j["cell_hash"] = cell_hash(job);
  j["post_hash"] = post_options_hash(o);
  j["provenance"] = provenance.to_json();
  return j;
}

void write_cell_results(const fs::path& dir, const CellJob& job, const CellResult& r, const PostOptions& o,
                        const std::string& program) {
  const Provenance provenance = Provenance::make(program, cell_hash(job), job.seed);
  const std::vector<CellState>& st = r.response.states;
  std::unique_lock<std::mutex> lock(hdf5_mutex());
  H5Writer w(dir / "curves.h5");
  if (!st.empty()) {
    w.write("states/strain", column(st, [](const CellState& s) { return s.strain; }), "1");
    w.write("states/sigma_bar", column(st, [](const CellState& s) { return s.sigma_bar_Pa; }), "Pa");
    w.write("states/bulk_energy", column(st, [](const CellState& s) { return s.bulk_energy_J_m; }), "J/m");
    w.write("states/cohesive_energy", column(st, [](const CellState& s) { return s.cohesive_energy_J_m; }), "J/m");
    w.write("states/dissipated_energy", column(st, [](const CellState& s) { return s.dissipated_J_m; }), "J/m");
    w.write("states/external_work", column(st, [](const CellState& s) { return s.external_work_J_m; }), "J/m");
    w.write("states/jump_dissipated", column(st, [](const CellState& s) { return s.jump_dissipated_J_m; }), "J/m");
    w.write("states/max_opening", column(st, [](const CellState& s) { return s.max_opening_m; }), "m");
    w.write("states/crack_segments", int_column(st, [](const CellState& s) { return s.crack_segments; }), "1");
    w.write("states/open_segments", int_column(st, [](const CellState& s) { return s.open_segments; }), "1");
    w.write("states/newton_iterations", int_column(st, [](const CellState& s) { return s.newton_iterations; }), "1");
  }
  if (r.bridged) {
    w.write("states/psi_bar", r.path.psi_bar_J_m3, "J/m^3");
    w.write("states/psi_0", r.path.psi_0_J_m3, "J/m^3");
    w.write("states/d_energy", r.path.d_energy, "1");
    w.write("states/d_force", r.path.d_force, "1");
    w.write("states/cracked", as_doubles(r.path.cracked), "1");
    w.write("controlled/strain", r.curve.strain, "1");
    w.write("controlled/damage", r.curve.damage, "1");
    w.write("controlled/stress", r.curve.stress_Pa, "Pa");
    w.set_attribute("controlled", "separated", static_cast<std::int64_t>(r.curve.separated));
    w.set_attribute("controlled", "strain_control", to_string(o.bridging.strain_control));
    w.set_attribute("controlled", "damage_measure", to_string(o.bridging.damage_measure));
    w.write("resampled/strain", o.grid, "1");
    w.write("resampled/damage", r.resampled.damage, "1");
    w.write("resampled/stress", r.resampled.stress_Pa, "Pa");
    w.set_attribute("resampled", "valid_points", r.resampled.valid_points);
  }
  w.set_attribute("", "status", std::string(to_string(r.response.status)));
  w.set_attribute("", "diagnostic", r.response.diagnostic);
  w.set_attribute("", "E0_bar_Pa", r.response.E0_bar_Pa);
  w.set_attribute("", "side_m", r.response.side_m);
  w.write_provenance(provenance);
  w.close();
  lock.unlock();
  // Last: a summary.json on disk marks the cell as finished (resume relies on it).
  nlohmann::json summary = cell_summary_json(job, r, o, provenance);
  summary[kSummaryChecksumKey] = summary_checksum(summary);
  write_text_atomic(dir / "summary.json", summary.dump(2) + "\n");
}

namespace {

// Cells written before checksums (the archived ones) carry none in either file and are read as they
// are; a cell with one file checksummed and the other not was altered.
void check_checksums_paired(bool summary_checksummed, bool curves_checksummed) {
  if (summary_checksummed && !curves_checksummed)
    throw std::runtime_error("curves.h5 carries no checksums beside a checksummed summary.json");
  if (!summary_checksummed && curves_checksummed)
    throw std::runtime_error(std::string("summary.json carries no '") + kSummaryChecksumKey + "' beside a checksummed curves.h5");
}

}  // namespace

std::optional<StoredCell> load_cell_results(const fs::path& dir, const std::string& expected_cell_hash,
                                            const std::string& expected_post_hash, const std::string& former_cell_hash) {
  std::error_code ec;
  if (!fs::exists(dir / "summary.json", ec) || !fs::exists(dir / "curves.h5", ec)) return std::nullopt;
  // A finished cell that does not read back (corrupt or altered files) is computed again, with a warning;
  // a cell of another hash (other settings, another solver revision) silently.
  const auto corrupt = [&](const std::string& what) -> std::optional<StoredCell> {
    spdlog::warn("{}: the finished cell does not read back ({}): it is computed again", dir.string(), what);
    return std::nullopt;
  };
  nlohmann::json j;
  try {
    std::ifstream in(dir / "summary.json");
    j = nlohmann::json::parse(in);
    if (!j.is_object()) return corrupt("summary.json: not a JSON object");
    if (j.contains(kSummaryChecksumKey) && j[kSummaryChecksumKey] != summary_checksum(j))
      return corrupt(std::string("summary.json: its values do not match '") + kSummaryChecksumKey + "'");
  } catch (const std::exception& e) {
    return corrupt(std::string("summary.json: ") + e.what());
  }
  try {
    const bool former = !former_cell_hash.empty() && j.at("cell_hash") == former_cell_hash;
    if (j.at("format") != kCellSummaryFormat || (j.at("cell_hash") != expected_cell_hash && !former)) return std::nullopt;
    StoredCell s;
    s.former_hash = former;
    CellResponse& r = s.response;
    const std::optional<CellStatus> status = status_from_name(j.at("status").get<std::string>());
    if (!status) return corrupt("summary.json: unknown status");
    r.status = *status;
    r.diagnostic = j.at("diagnostic").get<std::string>();
    r.side_m = j.at("cell").at("side_m").get<double>();
    r.porosity = j.at("cell").at("porosity").get<double>();
    r.E0_bar_Pa = j.at("E0_bar_Pa").get<double>();
    r.nodes = j.at("nodes").get<std::size_t>();
    r.dofs = j.at("dofs").get<std::size_t>();
    r.enriched_nodes = j.at("enriched_nodes").get<std::size_t>();
    r.growth_unloads = j.at("growth_unloads").get<std::size_t>();
    r.jumps = j.at("jumps").get<std::size_t>();
    r.factorizations = j.at("factorizations").get<std::size_t>();
    r.krylov_corrections = j.value("krylov_corrections", std::size_t{0});  // absent before revision 3
    r.krylov_products = j.value("krylov_products", std::size_t{0});
    r.crack_geometries = j.value("crack_geometries", std::size_t{0});  // absent from the archived cells
    r.operator_energy_mismatch = j.at("operator_energy_mismatch").get<double>();
    r.wall_s = j.at("wall_s").get<double>();
    const std::lock_guard<std::mutex> lock(hdf5_mutex());
    const H5Reader h5(dir / "curves.h5", H5Checksums::optional);
    check_checksums_paired(j.contains(kSummaryChecksumKey), h5.checksummed());
    if (h5.has("states/strain")) {
      const auto strain = h5.read_doubles("states/strain").values;
      const auto sigma = h5.read_doubles("states/sigma_bar").values;
      const auto bulk = h5.read_doubles("states/bulk_energy").values;
      const auto coh = h5.read_doubles("states/cohesive_energy").values;
      const auto diss = h5.read_doubles("states/dissipated_energy").values;
      const auto work = h5.read_doubles("states/external_work").values;
      const auto jumped = h5.read_doubles("states/jump_dissipated").values;
      const auto opening = h5.read_doubles("states/max_opening").values;
      const auto segments = h5.read_int64("states/crack_segments").values;
      const auto open = h5.read_int64("states/open_segments").values;
      const auto newton = h5.read_int64("states/newton_iterations").values;
      const std::size_t n = strain.size();
      for (const std::size_t len : {sigma.size(), bulk.size(), coh.size(), diss.size(), work.size(), jumped.size(), opening.size(),
                                    segments.size(), open.size(), newton.size()})
        if (len != n) return corrupt("curves.h5: the states' datasets differ in length");
      r.states.resize(n);
      for (std::size_t i = 0; i < n; ++i) {
        CellState& c = r.states[i];
        c.strain = strain[i];
        c.sigma_bar_Pa = sigma[i];
        c.bulk_energy_J_m = bulk[i];
        c.cohesive_energy_J_m = coh[i];
        c.dissipated_J_m = diss[i];
        c.external_work_J_m = work[i];
        c.jump_dissipated_J_m = jumped[i];
        c.max_opening_m = opening[i];
        c.crack_segments = static_cast<std::size_t>(segments[i]);
        c.open_segments = static_cast<std::size_t>(open[i]);
        c.newton_iterations = static_cast<int>(newton[i]);
      }
    }
    s.post_hash_matches = j.value("post_hash", std::string()) == expected_post_hash;
    return s;
  } catch (const std::exception& e) {
    return corrupt(e.what());
  }
}

}  // namespace uhpc::micro
