#include "run_inputs.hpp"

#include <fstream>
#include <iterator>
#include <optional>

#include "uhpc/errors.hpp"
#include "uhpc/hash.hpp"
#include "uhpc/sdel_handoff.hpp"

namespace uhpc::macro {

namespace {

std::string file_hash(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open file to record its hash");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return fnv1a64_hex(bytes);
}

nlohmann::json file_entry(const std::string& role, const std::string& path) {
  return {{"role", role}, {"path", path}, {"fnv1a64", file_hash(path)}};
}

}  // namespace

RunInputs run_inputs(const Config& cfg, const std::string& case_file, const std::vector<std::string>& overrides,
                     const std::string& sdel_path, const MaterialInputs& material) {
  nlohmann::json files = nlohmann::json::array();
  files.push_back(file_entry("case", case_file));
  for (const std::string& f : material.files_read)
    files.push_back(file_entry(f == material.handoff_path ? "sdel" : "material", f));
  if (!sdel_path.empty()) files.push_back(file_entry("sdel", sdel_path));
  nlohmann::json sdel = nullptr;
  if (material.handoff) {
    const SdelHandoff& h = *material.handoff;
    sdel = {{"path", sdel_path.empty() ? material.handoff_path : sdel_path},
            {"a", h.constants.a},
            {"A", h.constants.A},
            {"nu", h.constants.nu},
            {"chi", h.constants.chi},
            {"l_mac_m", h.l_mac_m},
            {"strain_measure", h.strain_measure}};
  }
  RunInputs r;
  r.record = {{"case_file", case_file}, {"overrides", overrides}, {"case", cfg.json()}, {"files", files},
              {"sdel", sdel}};
  // The case enters through its effective document (cfg, after --set) without its notes, not its bytes:
  // a note or the layout of the file does not make another run, a value does, in the file or by --set. The
  // material constants enter through their file's bytes; the SDEL through the values the law uses (its
  // constants, l_mac, strain measure), not its bytes: a handoff fitted again to the same constants (a new
  // date in its provenance, as `make paper` and the quickstart write it) makes no other run, and a
  // handoff the law does not use makes none.
  std::string data_hashes;
  for (const auto& f : files)
    if (f.at("role") == "material") data_hashes += f.at("fnv1a64").get<std::string>();
  if (!sdel.is_null()) {
    nlohmann::json values = sdel;
    values.erase("path");
    data_hashes += fnv1a64_hex(values.dump());
  }
  r.hash = fnv1a64_hex(cfg.hash() + data_hashes);
  r.former_hash = fnv1a64_hex(cfg.hash_including_notes() + data_hashes);
  nlohmann::json resumable = without_notes(cfg.json());
  for (const char* key : kRestartMayChange) resumable.at("run").erase(key);
  r.restart_hash = fnv1a64_hex(fnv1a64_hex(resumable.dump()) + data_hashes);
  r.record["hash"] = r.hash;
  return r;
}

std::string restart_may_change_list() {
  std::string list;
  for (const char* key : kRestartMayChange) list += (list.empty() ? "run." : ", run.") + std::string(key);
  return list;
}

nlohmann::json inputs_summary(const RunInputs& inputs) {
  const nlohmann::json& c = inputs.record.at("case");
  return {{"files", inputs.record.at("files")},
          {"sdel", inputs.record.at("sdel")},
          {"target", c.at("target")},
          {"projectile", c.at("projectile")},
          {"overrides", inputs.record.at("overrides")},
          {"hash", inputs.hash}};
}

}  // namespace uhpc::macro
