#include "checkpoint.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "run_inputs.hpp"
#include "uhpc/build_info.hpp"
#include "uhpc/errors.hpp"
#include "uhpc/hdf5_io.hpp"

namespace uhpc::macro {
namespace {

constexpr const char* kFormat = "uhpc-macro-checkpoint/1";

// Plain structs (doubles, arrays, enums) go in as their bytes: exact, infinities included.
template <class T>
std::vector<std::uint8_t> bytes_of(const T& value) {
  static_assert(std::is_trivially_copyable_v<T>, "stored as bytes");
  const auto* b = reinterpret_cast<const std::uint8_t*>(&value);
  return {b, b + sizeof(T)};
}

template <class T>
T from_bytes(const std::vector<std::uint8_t>& bytes, const std::string& what) {
  static_assert(std::is_trivially_copyable_v<T>, "stored as bytes");
  if (bytes.size() != sizeof(T))
    throw std::runtime_error(what + ": " + std::to_string(bytes.size()) + " bytes, expected " + std::to_string(sizeof(T)));
  T value;
  std::memcpy(&value, bytes.data(), sizeof(T));
  return value;
}

std::vector<std::uint8_t> text_bytes(const std::string& text) { return {text.begin(), text.end()}; }
std::string bytes_text(const std::vector<std::uint8_t>& bytes) { return {bytes.begin(), bytes.end()}; }

nlohmann::json steps_json(const std::vector<XdmfStep>& steps) {
  nlohmann::json out = nlohmann::json::array();
  for (const XdmfStep& s : steps) {
    nlohmann::json attributes = nlohmann::json::array();
    for (const XdmfStep::Attribute& a : s.attributes) attributes.push_back({a.name, a.components});
    out.push_back({{"time_s", s.time_s}, {"group", s.group}, {"count", s.count}, {"dim", s.dim},
                   {"attributes", attributes}});
  }
  return out;
}

std::vector<XdmfStep> steps_from(const nlohmann::json& j) {
  std::vector<XdmfStep> steps;
  for (const nlohmann::json& s : j) {
    XdmfStep step;
    step.time_s = s.at("time_s").get<double>();
    step.group = s.at("group").get<std::string>();
    step.count = s.at("count").get<std::size_t>();
    step.dim = s.at("dim").get<int>();
    for (const nlohmann::json& a : s.at("attributes")) step.attributes.push_back({a.at(0), a.at(1)});
    steps.push_back(std::move(step));
  }
  return steps;
}

}  // namespace

std::string checkpoint_build() { return std::string(build_version()) + " " + build_git_commit(); }

void write_checkpoint(const std::filesystem::path& file, const RunCheckpoint& c) {
  H5Writer h5(file);
  h5.set_attribute("", "format", std::string(kFormat));
  h5.set_attribute("", "config_hash", c.config_hash);
  h5.set_attribute("", "build", c.build);
  for (const auto& [name, values] : c.solver.particle_fields) h5.write("particles/" + name, values, "1");
  h5.write("solver/material_states", c.solver.material_states, "1");
  const StepState& s = c.solver.state;
  const StepCounters& n = c.solver.counters;
  h5.write("solver/f_ext_old", s.f_ext_old, "N");
  h5.write("solver/f_contact_old", s.f_contact_old, "N");
  h5.write("solver/sphere", s.sphere ? bytes_of(*s.sphere) : std::vector<std::uint8_t>{}, "1");
  h5.write("solver/sphere_force_old", bytes_of(s.sphere_force_old), "1");
  h5.write("solver/contact", bytes_of(s.contact), "1");
  h5.write("solver/ledger", bytes_of(s.ledger), "1");
  h5.write("solver/clock", std::vector<double>{s.time_s, s.dt_s, s.wall_force_N, n.last_dt_s}, "1");
  h5.write("solver/counters", std::vector<std::int64_t>{n.steps, n.repeats}, "1");
  h5.write("run/history", text_bytes(c.history_text), "1");
  h5.write("run/history_rows", std::vector<std::int64_t>{static_cast<std::int64_t>(c.history_rows)}, "1");
  h5.write("run/impact", bytes_of(c.impact), "1");
  h5.write("run/balance", bytes_of(c.balance), "1");
  const nlohmann::json fields = {{"particles", steps_json(c.fields.particle_steps)},
                                 {"sphere", steps_json(c.fields.sphere_steps)}};
  h5.write("run/field_steps", text_bytes(fields.dump()), "1");
  h5.write("run/field_last_time", std::vector<double>{c.fields.last_time_s}, "s");
  h5.close();
}

bool written_by_this_build(const std::filesystem::path& file) {
  try {
    const H5Reader h5(file, H5Checksums::required);
    return h5.string_attribute("", "build") == checkpoint_build();
  } catch (const std::exception&) {
  }
  try {  // an HDF5 file without checksums: written before every build wrote them, so by another one
    const H5Reader h5(file, H5Checksums::optional);
    return h5.checksummed();
  } catch (const std::exception&) {
    return true;  // unreadable: read_checkpoint says what is wrong with it
  }
}

RunCheckpoint read_checkpoint(const std::filesystem::path& file, const std::string& config_hash) {
  const std::string name = file.string();
  if (!std::filesystem::exists(file))
    throw InputError(name + ": no checkpoint to restart from (the run wrote none: run.checkpoint_interval_steps, "
                            "--checkpoint-every-min or an undecided end)");
  RunCheckpoint c;
  try {
    const H5Reader h5(file, H5Checksums::required);
    if (h5.string_attribute("", "format") != kFormat) throw std::runtime_error("not a " + std::string(kFormat) + " file");
    c.config_hash = h5.string_attribute("", "config_hash");
    c.build = h5.string_attribute("", "build");
    if (c.build != checkpoint_build())
      throw InputError(name + ": written by uhpc-macro " + c.build + ", this is " + checkpoint_build() +
                       ": a checkpoint is resumed by the build that wrote it");
    if (c.config_hash != config_hash)
      throw InputError(name + ": written for a case whose hash is " + c.config_hash + ", this case's is " + config_hash +
                       ": restart with the case, --sdel and --set of the run that wrote it (only " +
                       restart_may_change_list() + " may change)");
    for (const std::string& field : h5.children("particles"))
      c.solver.particle_fields.emplace_back(field, h5.read_doubles("particles/" + field).values);
    c.solver.material_states = h5.read_bytes("solver/material_states").values;
    StepState& s = c.solver.state;
    StepCounters& n = c.solver.counters;
    s.f_ext_old = h5.read_doubles("solver/f_ext_old").values;
    s.f_contact_old = h5.read_doubles("solver/f_contact_old").values;
    const std::vector<std::uint8_t> sphere = h5.read_bytes("solver/sphere").values;
    if (!sphere.empty()) s.sphere = from_bytes<RigidSphere>(sphere, "solver/sphere");
    s.sphere_force_old = from_bytes<Vec3>(h5.read_bytes("solver/sphere_force_old").values, "solver/sphere_force_old");
    s.contact = from_bytes<SphereContactSums>(h5.read_bytes("solver/contact").values, "solver/contact");
    s.ledger = from_bytes<EnergyLedger>(h5.read_bytes("solver/ledger").values, "solver/ledger");
    const std::vector<double> clock = h5.read_doubles("solver/clock").values;
    const std::vector<std::int64_t> counters = h5.read_int64("solver/counters").values;
    if (clock.size() != 4 || counters.size() != 2) throw std::runtime_error("solver/clock or solver/counters: wrong size");
    s.time_s = clock[0];
    s.dt_s = clock[1];
    s.wall_force_N = clock[2];
    n.last_dt_s = clock[3];
    n.steps = counters[0];
    n.repeats = counters[1];
    c.history_text = bytes_text(h5.read_bytes("run/history").values);
    const std::vector<std::int64_t> rows = h5.read_int64("run/history_rows").values;
    if (rows.size() != 1 || rows[0] < 0) throw std::runtime_error("run/history_rows: wrong size");
    c.history_rows = static_cast<std::size_t>(rows[0]);
    c.impact = from_bytes<ImpactTracker>(h5.read_bytes("run/impact").values, "run/impact");
    c.balance = from_bytes<BalanceTracker>(h5.read_bytes("run/balance").values, "run/balance");
    const nlohmann::json fields = nlohmann::json::parse(bytes_text(h5.read_bytes("run/field_steps").values));
    c.fields.particle_steps = steps_from(fields.at("particles"));
    c.fields.sphere_steps = steps_from(fields.at("sphere"));
    const std::vector<double> last = h5.read_doubles("run/field_last_time").values;
    if (last.size() != 1) throw std::runtime_error("run/field_last_time: wrong size");
    c.fields.last_time_s = last[0];
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(name + ": not a usable checkpoint: " + e.what());
  }
  return c;
}

void check_checkpoint_values(const RunCheckpoint& c, const RunSettings& run, const std::filesystem::path& file) {
  const StepState& s = c.solver.state;
  const StepCounters& n = c.solver.counters;
  const auto refuse = [&](const std::string& value, const std::string& reason) {
    throw InputError(file.string() + ": " + value + ": " + reason);
  };
  const std::string edited = ": the checkpoint is corrupt or was edited";
  if (!std::isfinite(s.time_s) || s.time_s < 0.0)
    refuse(fmt::format("solver/clock time_s = {}", s.time_s), "not a time >= 0 s" + edited);
  if (!(s.time_s < run.end_time_s))
    refuse(fmt::format("solver/clock time_s = {} s", s.time_s),
           fmt::format("at or past run.end_time_s = {} s: a restart carries a run on to a later end time", run.end_time_s));
  if (n.steps < 0 || n.steps > run.max_steps)
    refuse(fmt::format("solver/counters steps = {}", n.steps),
           fmt::format("outside [0, run.max_steps = {}]{} (a run that really took more steps goes on with a larger "
                       "run.max_steps)",
                       run.max_steps, edited));
  if ((n.steps == 0) != (s.time_s == 0.0))
    refuse(fmt::format("solver/counters steps = {} at solver/clock time_s = {}", n.steps, s.time_s),
           "a run is at time 0 exactly at step 0" + edited);
  if (n.repeats < 0) refuse(fmt::format("solver/counters repeats = {}", n.repeats), "negative" + edited);
  if (!std::isfinite(s.dt_s) || !(s.dt_s > 0.0))
    refuse(fmt::format("solver/clock dt_s = {}", s.dt_s), "not a step > 0 s" + edited);
  if (!std::isfinite(n.last_dt_s) || n.last_dt_s < 0.0 || n.last_dt_s > s.time_s)
    refuse(fmt::format("solver/clock last_dt_s = {}", n.last_dt_s), fmt::format("outside [0, time_s = {}]", s.time_s) + edited);
  if (!std::isfinite(s.wall_force_N))
    refuse(fmt::format("solver/clock wall_force_N = {}", s.wall_force_N), "not finite" + edited);
  if (!std::isfinite(c.fields.last_time_s) || c.fields.last_time_s > s.time_s)
    refuse(fmt::format("run/field_last_time = {}", c.fields.last_time_s), fmt::format("after time_s = {}", s.time_s) + edited);
}

}  // namespace uhpc::macro
