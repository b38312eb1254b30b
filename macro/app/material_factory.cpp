#include "material_factory.hpp"

#include <filesystem>

#include <fmt/format.h>
#include <utility>

#include "materials/afc_config.hpp"

namespace uhpc::macro {

namespace {

ElasticParams read_elastic(const Config& b) {
  ElasticParams p;
  p.density_kg_m3 = b.number("density_kg_m3", Range::positive());
  p.bulk_modulus_Pa = b.number("bulk_modulus_Pa", Range::positive());
  p.shear_modulus_Pa = b.number("shear_modulus_Pa", Range::positive());
  return p;
}

J2Params read_j2(const Config& b) {
  const ElasticParams e = read_elastic(b);
  J2Params p;
  p.density_kg_m3 = e.density_kg_m3;
  p.bulk_modulus_Pa = e.bulk_modulus_Pa;
  p.shear_modulus_Pa = e.shear_modulus_Pa;
  p.yield_stress_Pa = b.number("yield_stress_Pa", Range::positive());
  p.hardening_modulus_Pa = b.number("hardening_modulus_Pa", Range::non_negative());
  return p;
}

// A path in a case file is relative to that file, so shipped cases run from any directory.
std::string relative_to(const Config& block, const std::string& path) {
  if (std::filesystem::path(path).is_absolute()) return path;
  return (std::filesystem::path(block.source()).parent_path() / path).string();
}

// {"model": "afc", "constants_file": "afc_uhpc.json", "sdel_file": "sdel_paper.json", "options": {...}}:
// the constants (Table 6, with an optional "options" block), the SDEL handoff (--sdel replaces
// sdel_file) and the case's own optional "options", which override the constants file's key by key
// (so --set material.options.lode=willam_warnke needs no copy of the constants).
AfcParams read_afc(const Config& block, const std::optional<SdelHandoff>& sdel, MaterialInputs& record) {
  const std::string constants = relative_to(block, block.text("constants_file"));
  const std::string sdel_file = relative_to(block, block.text("sdel_file"));
  const SdelHandoff handoff = sdel ? *sdel : read_sdel_handoff(sdel_file);
  const Config cfg = Config::load(constants);
  AfcParams p = afc_params_from_config(cfg, handoff);
  cfg.finish();
  if (block.has("options")) p.options = afc_options_from_config(block.section("options"), p.options);
  record.files_read.push_back(constants);
  if (!sdel) {
    record.files_read.push_back(sdel_file);
    record.handoff_path = sdel_file;
  }
  record.handoff = handoff;
  return p;
}

std::string elastic_inputs(const ElasticParams& p) {
  return fmt::format("material.density_kg_m3 = {:g}, material.bulk_modulus_Pa = {:g}, material.shear_modulus_Pa = {:g}",
                     p.density_kg_m3, p.bulk_modulus_Pa, p.shear_modulus_Pa);
}

}  // namespace

MaterialChoice make_material(const Config& block, std::size_t n, const std::optional<SdelHandoff>& sdel) {
  const std::string model = block.choice("model", {"elastic", "j2", "afc"});
  if (model == "elastic") {
    const ElasticParams p = read_elastic(block);
    return {make_material_set(ElasticMaterial(p), n), model, false, {}, elastic_inputs(p)};
  }
  if (model == "afc") {
    MaterialInputs inputs;
    const AfcParams params = read_afc(block, sdel, inputs);
    const std::string speed = fmt::format("density_kg_m3 = {:g}, shear_modulus_Pa = {:g}, C6_Pa = {:g} and C7 = {:g} "
                                          "(bulk modulus C6/C7) of material.constants_file {}",
                                          params.density_kg_m3, params.shear_modulus_Pa, params.C6_Pa, params.C7,
                                          inputs.files_read.front());
    return {make_material_set(AfcMaterial(params), n), model, true, std::move(inputs), speed};
  }
  // model == "j2" (the choice above admits nothing else). Neither elastic nor J2 uses the SDEL.
  const J2Params p = read_j2(block);
  return {make_material_set(J2Material(p), n), model, false, {},
          elastic_inputs({p.density_kg_m3, p.bulk_modulus_Pa, p.shear_modulus_Pa})};
}

std::vector<std::string> law_output_fields(const MaterialSet& set) {
  return std::visit([](const auto& b) { return std::decay_t<decltype(b.law)>::output_fields(); }, set);
}

void law_output_values_at(const MaterialSet& set, std::size_t i, double* out) {
  std::visit([&](const auto& b) { b.law.output_values(b.state[i], out); }, set);
}

}  // namespace uhpc::macro
