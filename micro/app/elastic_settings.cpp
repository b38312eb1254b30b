#include "elastic_settings.hpp"

#include <filesystem>

#include "quadrature.hpp"
#include "uhpc/config.hpp"
#include "uhpc/errors.hpp"
#include "uhpc/hash.hpp"

namespace fs = std::filesystem;

namespace uhpc::micro {

namespace {

void read_matrix(const std::string& path, const std::vector<std::string>& overrides, PlaneStrain& m) {
  const Config micro = Config::load(path, overrides);
  const Config matrix = micro.section("matrix");
  m.youngs_modulus_Pa = matrix.number("youngs_modulus_Pa", Range::positive());
  // Plane strain needs nu < 1/2 (D is singular at 1/2).
  m.poissons_ratio = matrix.number("poissons_ratio", Range{-1.0, 0.5, true, true});
  // The rest is read (and validated) by load_cell_settings or by the cohesive analysis.
  micro.accept_any("source");
  micro.accept_any("burr");
  micro.accept_any("area_porosity");
  micro.accept_any("cell_sizes_m");
  micro.accept_any("l_mac_m");
  matrix.accept_any("tensile_strength_Pa");
  matrix.accept_any("fracture_energy_J_m2");
  micro.finish();
}

void read_options(const Config& c, UniaxialOptions& o) {
  c.accept_any("notes");
  o.strain = c.number("strain", Range::positive());
  const Config rk = c.section("rk");
  o.rk.support_factor = rk.number("support_factor", Range::closed(1.0, 4.0));
  const std::string kernel = rk.choice("kernel", {"cubic_bspline", "quartic_spline"});
  o.rk.kernel = kernel_from_name(kernel);
  if (rk.has("derivatives")) o.rk.derivatives = rk::derivatives_from_name(rk.choice("derivatives", {"implicit", "direct"}));
  const Config q = c.section("quadrature");
  o.rk.triangle_points = static_cast<int>(q.integer("triangle_points", Range::closed(1, 12)));
  if (!is_triangle_rule(o.rk.triangle_points))
    q.fail("triangle_points", "value " + std::to_string(o.rk.triangle_points) + " is not one of: 1, 3, 6, 7, 12");
  o.rk.segment_points = static_cast<int>(q.integer("segment_points", Range::closed(1, 5)));
  o.rk.correction = q.choice("correction", {"vci", "none"}) == "vci" ? IntegrationCorrection::Vci
                                                                    : IntegrationCorrection::None;
  const Config bc = c.section("essential_bc");
  bc.choice("method", {"nitsche"});
  o.nitsche_factor = bc.number("nitsche_factor", Range::positive());
  c.finish();
}

}  // namespace

ElasticSettings load_elastic_settings(const std::string& config_path, std::vector<std::string> overrides) {
  std::vector<std::string> cell_overrides = take_prefixed_overrides(overrides, "cell");
  const std::vector<std::string> micro_overrides = take_prefixed_overrides(overrides, "microstructure");
  for (const std::string& o : micro_overrides) cell_overrides.push_back("microstructure." + o);
  const Config cfg = Config::load(config_path, overrides);
  ElasticSettings s;
  s.cell_config = cfg.text("cell_config");
  if (fs::path(s.cell_config).is_relative())
    s.cell_config = (fs::path(config_path).parent_path() / s.cell_config).string();
  read_options(cfg, s.options);
  s.cell = load_cell_settings(s.cell_config, cell_overrides);
  if (!s.cell.mesh_enabled)
    throw_input_error(s.cell_config, "discretization.mesh", "must be true: the elastic analysis integrates on the mesh");
  read_matrix(s.cell.microstructure_file, micro_overrides, s.material);
  s.config_hash = fnv1a64_hex(cfg.hash() + s.cell.config_hash);
  return s;
}

}  // namespace uhpc::micro
