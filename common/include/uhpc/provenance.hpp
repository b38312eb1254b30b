#pragma once
// The provenance block every result carries: what produced it, from which inputs, when.
#include <cstdint>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace uhpc {

struct Provenance {
  std::string program;       // e.g. "uhpc-micro run"
  std::string version;       // project version (build_version())
  std::string git_commit;    // build_git_commit()
  std::string config_hash;   // Config::hash() of the effective configuration, "" if none
  std::string date_utc;      // ISO 8601, e.g. "2026-11-21T23:59:01Z"
  std::optional<std::uint64_t> seed;  // random seed, if the run used one

  // Fills version, commit and date from this build and the clock.
  static Provenance make(std::string program, std::string config_hash,
                         std::optional<std::uint64_t> seed = std::nullopt);

  nlohmann::json to_json() const;
  static Provenance from_json(const nlohmann::json& j);  // throws std::runtime_error when malformed
};

}  // namespace uhpc
