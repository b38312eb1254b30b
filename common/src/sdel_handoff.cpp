#include "uhpc/sdel_handoff.hpp"

#include <stdexcept>

#include "uhpc/atomic_file.hpp"
#include "uhpc/config.hpp"
#include "uhpc/errors.hpp"

namespace uhpc {
namespace {

SdelHandoff from_config(const Config& cfg) {
  // The format comes first: a file of another format should be reported as such, not as a list of
  // missing keys.
  const std::string format = cfg.text("format");
  if (format != kSdelFormat) {
    cfg.fail("format", "expected \"" + std::string(kSdelFormat) + "\", got \"" + format + "\"");
  }
  if (cfg.has("law")) (void)cfg.text("law");  // informative; the code always applies sdel.hpp

  SdelHandoff h;
  const Config constants = cfg.section("constants");
  h.constants.a = constants.number("a", Range::positive());
  h.constants.A = constants.number("A", Range::positive());
  h.constants.nu = constants.number("nu", Range::positive());
  h.constants.chi = constants.number("chi", Range::positive());
  h.l_mac_m = cfg.number("l_mac_m", Range::positive());
  if (cfg.has("strain_measure")) {
    h.strain_measure =
        cfg.choice("strain_measure", {kSdelStrainEffectiveTensile, kSdelStrainMazars, kSdelStrainMaxPrincipal});
  }
  h.cell_sizes_m = cfg.numbers("cell_sizes_m", Range::positive());
  h.source = cfg.text("source");

  if (cfg.has("fit")) {
    const Config fit = cfg.section("fit");  // must be an object; its content is free-form
    cfg.accept_any("fit");
    h.fit = fit.json();
  }
  if (cfg.has("provenance")) {
    cfg.accept_any("provenance");
    try {
      h.provenance = Provenance::from_json(cfg.json().at("provenance"));
    } catch (const std::runtime_error& e) {
      cfg.fail("provenance", e.what());
    }
  }
  cfg.finish();
  return h;
}

// Key order as documented in the header, so the file reads top to bottom.
nlohmann::ordered_json to_ordered_json(const SdelHandoff& h) {
  nlohmann::ordered_json j;
  j["format"] = std::string(kSdelFormat);
  j["law"] = std::string(kSdelLawText);
  j["constants"] = {{"a", h.constants.a}, {"A", h.constants.A}, {"nu", h.constants.nu}, {"chi", h.constants.chi}};
  j["l_mac_m"] = h.l_mac_m;
  j["strain_measure"] = h.strain_measure;
  j["cell_sizes_m"] = h.cell_sizes_m;
  j["source"] = h.source;
  // dump() writes doubles in round-trip precision, so re-parsing changes no value.
  j["fit"] = nlohmann::ordered_json::parse(h.fit.dump());
  if (h.provenance) j["provenance"] = nlohmann::ordered_json::parse(h.provenance->to_json().dump());
  return j;
}

}  // namespace

SdelHandoff read_sdel_handoff(const std::string& path) { return from_config(Config::load(path)); }

SdelHandoff sdel_handoff_from_json(const nlohmann::json& document, const std::string& source_name) {
  return from_config(Config::from_json(document, source_name));
}

nlohmann::json sdel_handoff_to_json(const SdelHandoff& handoff) {
  return nlohmann::json::parse(to_ordered_json(handoff).dump());
}

void write_sdel_handoff(const std::string& path, const SdelHandoff& handoff) {
  const nlohmann::ordered_json document = to_ordered_json(handoff);
  try {
    (void)sdel_handoff_from_json(nlohmann::json::parse(document.dump()), path);
  } catch (const InputError& e) {
    throw std::invalid_argument(std::string("refusing to write an invalid SDEL handoff: ") + e.what());
  }
  write_text_atomic(path, document.dump(2) + "\n");
}

}  // namespace uhpc
