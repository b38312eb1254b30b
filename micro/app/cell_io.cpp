#include "cell_io.hpp"

#include <algorithm>
#include <cmath>

#include "uhpc/config.hpp"
#include "uhpc/errors.hpp"

namespace uhpc::micro {

nlohmann::json mesh_summary_json(const CellGeometry& cell, const CellDiscretization& mesh) {
  std::size_t smallest = 0;
  for (std::size_t p = 1; p < cell.pores.size(); ++p)
    if (cell.pores[p].diameter_m < cell.pores[smallest].diameter_m) smallest = p;
  std::size_t min_pore_nodes = 0, boundary_nodes = 0;
  for (std::size_t p = 0; p < mesh.pore_nodes.size(); ++p) {
    min_pore_nodes = p == 0 ? mesh.pore_nodes[p].size() : std::min(min_pore_nodes, mesh.pore_nodes[p].size());
    boundary_nodes += mesh.pore_nodes[p].size();
  }
  const double porous_area = cell.cell_area_m2() - cell.pore_area_m2();
  const double mesh_area = mesh.area_m2();
  return {{"node_count", mesh.node_count()},
          {"triangle_count", mesh.triangle_count()},
          {"pore_boundary_node_count", boundary_nodes},
          {"min_nodes_on_a_pore", min_pore_nodes},
          {"nodes_on_smallest_pore", cell.pores.empty() ? 0 : mesh.pore_nodes[smallest].size()},
          {"spacing_min_m", *std::min_element(mesh.spacing_m.begin(), mesh.spacing_m.end())},
          {"spacing_max_m", *std::max_element(mesh.spacing_m.begin(), mesh.spacing_m.end())},
          {"mesh_area_m2", mesh_area},
          {"porous_area_m2", porous_area},
          {"area_relative_error", (mesh_area - porous_area) / porous_area}};
}

nlohmann::json cell_json(const GeneratedCell& generated, const CellSettings& s, const CellDiscretization* mesh,
                         const Provenance& provenance) {
  const CellGeometry& g = generated.geometry;
  const CellOptions& o = s.cell;
  auto point = [](const Vec2& v) { return nlohmann::json::array({v.x, v.y}); };
  nlohmann::json pores = nlohmann::json::array(), seeds = nlohmann::json::array();
  double largest = 0.0, smallest = g.pores.empty() ? 0.0 : g.pores.front().diameter_m;
  for (const Pore& p : g.pores) {
    pores.push_back({{"center_m", point(p.center_m)}, {"diameter_m", p.diameter_m}});
    largest = std::max(largest, p.diameter_m);
    smallest = std::min(smallest, p.diameter_m);
  }
  for (const CrackSeed& c : g.seeds) seeds.push_back({{"pore", c.pore}, {"root_m", point(c.root_m)}, {"tip_m", point(c.tip_m)}});
  nlohmann::json j = {
      {"format", kCellFormat},
      {"seed", generated.seed},
      {"cell_size_m", g.side_m},
      {"loading_direction", g.load == LoadAxis::X ? "x" : "y"},
      {"porosity", {{"target", o.porosity.target}, {"tolerance", o.porosity.tolerance}, {"achieved", g.porosity()}}},
      {"pore_count", g.pores.size()},
      {"largest_pore_diameter_m", largest},
      {"smallest_pore_diameter_m", smallest},
      {"seed_count", g.seeds.size()},
      {"burr",
       {{"k", o.burr.k},
        {"alpha", o.burr.alpha},
        {"beta_m", o.burr.beta_m},
        {"gamma_m", o.burr.gamma_m},
        {"truncation_m", o.truncation_m}}},
      {"options",
       {{"min_ligament_m", o.placement.min_ligament_m},
        {"max_attempts_per_pore", o.placement.max_attempts_per_pore},
        {"max_draws", o.porosity.max_draws},
        {"seeds_per_pore", o.seeds.per_pore},
        {"seed_length_m", o.seeds.length_m},
        {"seed_tilt_deg", o.seeds.tilt_rad * 180.0 / M_PI},
        {"nominal_spacing_m", s.mesh.nominal_spacing_m},
        {"boundary_ratio", s.mesh.boundary_ratio},
        {"min_nodes_per_pore", s.mesh.min_nodes_per_pore},
        {"grading", s.mesh.grading}}},
      {"generation",
       {{"draws", generated.record.drawn_diameters_m.size()},
        {"rejected_draws", generated.record.rejected_draws},
        {"placement_attempts", generated.record.placement_attempts}}},
      {"pores", pores},
      {"seeds", seeds},
      {"provenance", provenance.to_json()}};
  j["discretization"] = mesh ? mesh_summary_json(g, *mesh) : nlohmann::json(nullptr);
  return j;
}

CellGeometry cell_geometry_from_json(const nlohmann::json& document, const std::string& source) {
  const Config cfg = Config::from_json(document, source);
  const std::string format = cfg.text("format");
  if (format != kCellFormat)
    cfg.fail("format", "expected \"" + std::string(kCellFormat) + "\", got \"" + format + "\"");
  CellGeometry g;
  g.side_m = cfg.number("cell_size_m", Range::positive());
  g.load = cfg.choice("loading_direction", {"x", "y"}) == "x" ? LoadAxis::X : LoadAxis::Y;
  auto vec = [](const std::vector<double>& v) { return Vec2{v[0], v[1]}; };
  // An empty array is a valid list (a cell without seeds); sections() requires at least one entry.
  auto empty_list = [&](const char* key) {
    return cfg.json().contains(key) && cfg.json().at(key).is_array() && cfg.json().at(key).empty();
  };
  if (!empty_list("pores"))
    for (const Config& p : cfg.sections("pores"))
      g.pores.push_back(Pore{vec(p.numbers("center_m", Range::any(), 2)), p.number("diameter_m", Range::positive())});
  if (!empty_list("seeds"))
    for (const Config& c : cfg.sections("seeds"))
      g.seeds.push_back(CrackSeed{static_cast<int>(c.integer("pore", Range::closed(0, 1e9))),
                                  vec(c.numbers("root_m", Range::any(), 2)), vec(c.numbers("tip_m", Range::any(), 2))});
  return g;  // the other keys (summaries, provenance) are for people and statistics, not needed here
}

}  // namespace uhpc::micro
