#pragma once
// The coarse AFC disc with the SDEL as a solver, for tests that step a real case: NSNI, lazy shape
// rows and the Verlet candidates all carry state from step to step. And a bitwise comparison.
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "case_config.hpp"
#include "case_setup.hpp"
#include "material_factory.hpp"
#include "uhpc/config.hpp"

namespace uhpc::test {

inline const std::string kCoarseDiscCase = std::string(UHPC_DATA_DIR) + "/macro_disc_afc_coarse.json";

inline macro::ExplicitSolver coarse_disc_solver() {
  const Config cfg = Config::load(kCoarseDiscCase, {});
  const macro::CaseSettings settings = macro::read_case(cfg);
  const macro::ParticleBody body = macro::make_target_body(settings.target);
  macro::MaterialChoice material = macro::make_material(cfg.section("material"), body.size(), std::nullopt);
  return macro::make_solver(settings, body, std::move(material.set));
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

}  // namespace uhpc::test
