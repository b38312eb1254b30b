#include "uhpc/provenance.hpp"

#include <ctime>
#include <stdexcept>
#include <utility>

#include "uhpc/build_info.hpp"

namespace uhpc {
namespace {

// "YYYY-MM-DDTHH:MM:SSZ" for the current time, in UTC so that runs on different machines compare.
std::string now_utc_iso8601() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);  // the reentrant form: std::gmtime shares a static buffer between threads
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

// Messages are relative ("key 'x': ..."): callers prefix the file and the key of the block.
std::string required_string(const nlohmann::json& j, const char* key) {
  const auto it = j.find(key);
  if (it == j.end()) throw std::runtime_error(std::string("missing key '") + key + "'");
  if (!it->is_string()) {
    throw std::runtime_error(std::string("key '") + key + "': expected a string, got " + it->type_name());
  }
  return it->get<std::string>();
}

// The seed is a full 64-bit unsigned value; JSON integers read by nlohmann keep all 64 bits
// (number_unsigned), whereas a double would silently round anything above 2^53.
std::optional<std::uint64_t> required_seed(const nlohmann::json& j) {
  const auto it = j.find("seed");
  if (it == j.end()) throw std::runtime_error("missing key 'seed'");
  if (it->is_null()) return std::nullopt;
  if (it->is_number_unsigned()) return it->get<std::uint64_t>();
  if (it->is_number_integer() && it->get<std::int64_t>() >= 0) {
    return static_cast<std::uint64_t>(it->get<std::int64_t>());
  }
  const std::string got = it->is_number_integer() ? "a negative integer"
                          : it->is_number_float() ? "a non-integer number"
                                                  : std::string("a ") + it->type_name();
  throw std::runtime_error("key 'seed': expected a non-negative integer or null, got " + got);
}

}  // namespace

Provenance Provenance::make(std::string program, std::string config_hash, std::optional<std::uint64_t> seed) {
  Provenance p;
  p.program = std::move(program);
  p.version = build_version();
  p.git_commit = build_git_commit();
  p.config_hash = std::move(config_hash);
  p.date_utc = now_utc_iso8601();
  p.seed = seed;
  return p;
}

nlohmann::json Provenance::to_json() const {
  nlohmann::json j = nlohmann::json::object();
  j["program"] = program;
  j["version"] = version;
  j["git_commit"] = git_commit;
  j["config_hash"] = config_hash;
  j["date_utc"] = date_utc;
  j["seed"] = seed ? nlohmann::json(*seed) : nlohmann::json(nullptr);
  return j;
}

Provenance Provenance::from_json(const nlohmann::json& j) {
  if (!j.is_object()) throw std::runtime_error(std::string("expected an object, got ") + j.type_name());
  Provenance p;
  p.program = required_string(j, "program");
  p.version = required_string(j, "version");
  p.git_commit = required_string(j, "git_commit");
  p.config_hash = required_string(j, "config_hash");
  p.date_utc = required_string(j, "date_utc");
  p.seed = required_seed(j);
  return p;
}

}  // namespace uhpc
