#include "cell_settings.hpp"

#include <cmath>
#include <filesystem>
#include <limits>

#include <fmt/format.h>

#include "uhpc/errors.hpp"
#include "uhpc/hash.hpp"

namespace fs = std::filesystem;

namespace uhpc::micro {

namespace {

struct Sources {
  Config cell;
  Config micro;
};

void read_microstructure(const Config& m, CellOptions& o) {
  const Config burr = m.section("burr");
  o.burr.k = burr.number("k", Range::positive());
  o.burr.alpha = burr.number("alpha", Range::positive());
  o.burr.beta_m = burr.number("beta_m", Range::positive());
  o.burr.gamma_m = burr.number("gamma_m", Range::positive());
  o.truncation_m = burr.number("truncation_m", Range::positive());
  if (!(o.truncation_m > o.burr.gamma_m))
    burr.fail("truncation_m", fmt::format("value {:g} must exceed gamma_m = {:g} (the smallest pore)", o.truncation_m,
                                          o.burr.gamma_m));
  o.porosity.target = m.number("area_porosity", Range::open(0.0, 0.3));
  // Read by other stages (cell sizes by the ensemble, matrix and l_mac by the analysis).
  m.accept_any("source");
  m.accept_any("cell_sizes_m");
  m.accept_any("l_mac_m");
  m.accept_any("matrix");
}

// gmsh is asked for about 1.155 (side / spacing)^2 nodes (equilateral triangles; more around the
// pores). A cell far beyond that budget (a 1 m cell, a 10 nm spacing) would allocate without bound
// inside gmsh's threads, where no error can reach the user, so it is refused before meshing. The
// paper's largest cell, 6.5 mm at 50 um, has about 2e4 nodes.
constexpr double kMaxMeshNodes = 2e6;

void check_mesh_budget(const CellSettings& s, const std::string& cell_config_path) {
  if (!s.mesh_enabled) return;
  const double ratio = s.cell.side_m / s.mesh.nominal_spacing_m;
  const double nodes = 1.155 * ratio * ratio;
  if (nodes > kMaxMeshNodes)
    throw_input_error(cell_config_path, "discretization.nominal_spacing_m",
                      fmt::format("a cell of side {:g} m ({}) at spacing {:g} m needs about {:.2g} mesh nodes, more "
                                  "than the {:.0g} a cell may have (reduce {} or raise nominal_spacing_m)",
                                  s.cell.side_m, s.side_input, s.mesh.nominal_spacing_m, nodes, kMaxMeshNodes,
                                  s.side_input));
}

void read_cell(const Config& c, CellSettings& s, double size_override_m, const std::uint64_t* seed_override) {
  CellOptions& o = s.cell;
  c.accept_any("notes");
  o.side_m = c.number("cell_size_m", Range::positive());
  if (size_override_m > 0.0) {
    o.side_m = size_override_m;
    s.side_input = "the ensemble's cell_sizes_m";
  }
  s.seed = static_cast<std::uint64_t>(c.integer("seed", Range::closed(0, 9007199254740991.0)));  // < 2^53
  if (seed_override) s.seed = *seed_override;
  o.load = c.choice("loading_direction", {"x", "y"}) == "x" ? LoadAxis::X : LoadAxis::Y;

  const Config disc = c.section("discretization");
  s.mesh_enabled = disc.flag("mesh");
  s.mesh.nominal_spacing_m = disc.number("nominal_spacing_m", Range::positive());
  s.mesh.boundary_ratio = disc.number("boundary_ratio", Range{0.0, 1.0, true, false});
  s.mesh.min_nodes_per_pore = static_cast<int>(disc.integer("min_nodes_per_pore", Range::closed(4, 1000)));
  s.mesh.grading = disc.number("grading", Range::positive());

  const Config por = c.section("porosity");
  o.porosity.tolerance = por.number("tolerance", Range::positive());
  if (o.porosity.tolerance >= o.porosity.target)
    por.fail("tolerance", fmt::format("value {:g} must be below the target porosity {:g}", o.porosity.tolerance,
                                      o.porosity.target));
  o.porosity.max_draws = por.integer("max_draws", Range::closed(1, 1e9));

  const Config place = c.section("placement");
  // Geometry lengths are in metres, not in mesh spacings: a resolution study must change the
  // discretization of one and the same microstructure.
  o.placement.min_ligament_m = place.number("min_ligament_m", Range::positive());
  o.placement.max_attempts_per_pore = place.integer("max_attempts_per_pore", Range::closed(1, 1e9));

  const Config seeds = c.section("seeds");
  o.seeds.per_pore = static_cast<int>(seeds.integer("per_pore", Range::closed(0, 2)));
  o.seeds.length_m = seeds.number("length_m", Range::positive());
  if (!(2.0 * o.seeds.length_m < o.placement.min_ligament_m))
    seeds.fail("length_m", fmt::format("value {:g} must be below half of placement.min_ligament_m ({:g}), "
                                       "so that seeds cannot reach another pore, seed or edge",
                                       o.seeds.length_m, o.placement.min_ligament_m));
  o.seeds.tilt_rad = seeds.number("tilt_deg", Range::open(-90.0, 90.0)) * M_PI / 180.0;

  const Config pic = c.section("picture");
  s.picture.show_mesh = pic.flag("show_mesh");
  s.picture.size_px = static_cast<int>(pic.integer("size_px", Range::closed(100, 10000)));
}

}  // namespace

std::vector<std::string> take_prefixed_overrides(std::vector<std::string>& overrides, const std::string& prefix) {
  std::vector<std::string> taken, kept;
  const std::string p = prefix + ".";
  for (const std::string& o : overrides) {
    if (o.compare(0, p.size(), p) == 0)
      taken.push_back(o.substr(p.size()));
    else
      kept.push_back(o);
  }
  overrides = kept;
  return taken;
}

std::vector<std::string> take_cell_overrides(std::vector<std::string>& overrides) {
  std::vector<std::string> cell = take_prefixed_overrides(overrides, "cell");
  for (const std::string& o : take_prefixed_overrides(overrides, "microstructure")) cell.push_back("microstructure." + o);
  return cell;
}

namespace {

void flatten(const nlohmann::json& j, const std::string& path, std::vector<std::string>& out) {
  if (j.is_object()) {
    for (const auto& [key, value] : j.items()) flatten(value, path.empty() ? key : path + "." + key, out);
  } else {
    out.push_back(path + "=" + j.dump());
  }
}

}  // namespace

std::vector<std::string> config_cell_overrides(const Config& cfg, const std::vector<std::string>& command_line) {
  std::vector<std::string> out;
  if (cfg.has("cell_overrides")) {
    const Config section = cfg.section("cell_overrides");
    cfg.accept_any("cell_overrides");
    flatten(section.json(), "", out);
  }
  out.insert(out.end(), command_line.begin(), command_line.end());
  return out;
}

CellSettings load_cell_settings(const std::string& cell_config_path, std::vector<std::string> overrides,
                                double size_override_m, const std::uint64_t* seed_override) {
  const std::vector<std::string> micro_overrides = take_prefixed_overrides(overrides, "microstructure");
  const Config cell = Config::load(cell_config_path, overrides);
  CellSettings s;
  s.microstructure_file = cell.text("microstructure_file");
  // Relative to the cell config, so shipped configs work from any directory.
  if (fs::path(s.microstructure_file).is_relative())
    s.microstructure_file = (fs::path(cell_config_path).parent_path() / s.microstructure_file).string();
  const Config micro = Config::load(s.microstructure_file, micro_overrides);
  read_microstructure(micro, s.cell);
  read_cell(cell, s, size_override_m, seed_override);
  micro.finish();
  cell.finish();
  s.config_hash = fnv1a64_hex(cell.hash() + micro.hash());
  s.config_hash_including_notes = fnv1a64_hex(cell.hash_including_notes() + micro.hash_including_notes());
  try {
    check_cell_options(s.cell);
  } catch (const CellGenerationError& e) {
    rethrow_as_input_error(e, s, cell_config_path);
  }
  check_mesh_budget(s, cell_config_path);
  return s;
}

void rethrow_as_input_error(const CellGenerationError& e, const CellSettings& s, const std::string& cell_config_path) {
  using R = CellGenerationError::Reason;
  switch (e.reason()) {
    case R::CellTooSmall: {
      // Two ligaments as wide as the cell leave no room for any pore whatever the cell's size: the
      // ligament is the value to fix (min_ligament_m = 1 on a 3 mm cell), otherwise the side is.
      const CellOptions& o = s.cell;
      if (2.0 * o.placement.min_ligament_m >= o.side_m)
        throw_input_error(cell_config_path, "placement.min_ligament_m",
                          fmt::format("value {:g} leaves no room for a pore: two ligaments of {:g} m are as wide as "
                                      "the cell side {:g} m ({}) or wider",
                                      o.placement.min_ligament_m, o.placement.min_ligament_m, o.side_m, s.side_input));
      if (s.side_input == "cell_size_m")
        throw_input_error(cell_config_path, "cell_size_m", fmt::format("{} (placement.min_ligament_m)", e.what()));
      throw_input_error(cell_config_path, "",
                        fmt::format("{} (the side is {}, the ligaments placement.min_ligament_m)", e.what(), s.side_input));
    }
    case R::UnreachablePorosity:
      throw_input_error(s.microstructure_file, "area_porosity", e.what());
    case R::PlacementFailed:
      throw_input_error(cell_config_path, "placement.min_ligament_m", e.what());
    case R::BadOption:
      break;
  }
  throw_input_error(cell_config_path, "", e.what());
}

}  // namespace uhpc::micro
