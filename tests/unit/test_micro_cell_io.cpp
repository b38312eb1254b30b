// cell.json and the cell configuration (micro/app/cell_io.hpp, micro/app/cell_settings.hpp): the geometry
// survives a round trip, the same settings and seed give byte-identical files apart from the
// provenance date, and bad input names the file, key and reason.
#include <string>

#include <gtest/gtest.h>

#include "cell_io.hpp"
#include "cell_settings.hpp"
#include "test_support.hpp"
#include "uhpc/errors.hpp"

namespace uhpc::micro {
namespace {

const std::string kCellConfig = std::string(UHPC_DATA_DIR) + "/micro_cell.json";
const std::string kMicro = std::string(UHPC_DATA_DIR) + "/microstructure.json";

nlohmann::json generated_json(const std::vector<std::string>& overrides, bool mesh) {
  CellSettings s = load_cell_settings(kCellConfig, overrides);
  const GeneratedCell c = generate_cell(s.cell, s.seed);
  std::optional<CellDiscretization> m;
  if (mesh) m = mesh_cell(c.geometry, s.mesh);
  nlohmann::json j = cell_json(c, s, m ? &*m : nullptr, Provenance::make("test", s.config_hash, s.seed));
  j["provenance"].erase("date_utc");
  return j;
}

TEST(microCellIo, ShippedConfigReadsIntoThePaperOptions) {
  const CellSettings s = load_cell_settings(kCellConfig, {});
  EXPECT_EQ(s.cell.burr.k, 3.9313);
  EXPECT_EQ(s.cell.truncation_m, 1.3e-3);
  EXPECT_EQ(s.cell.porosity.target, 0.034);
  EXPECT_EQ(s.cell.porosity.tolerance, 0.0005);
  EXPECT_EQ(s.cell.side_m, 0.003);
  EXPECT_EQ(s.cell.load, LoadAxis::X);
  EXPECT_NEAR(s.cell.placement.min_ligament_m, 3 * 50e-6, 1e-18);
  EXPECT_NEAR(s.cell.seeds.length_m, 50e-6, 1e-18);
  EXPECT_EQ(s.mesh.min_nodes_per_pore, 8);
}

TEST(microCellIo, SameSeedByteIdenticalJsonApartFromDate) {
  const nlohmann::json a = generated_json({"seed=17"}, true), b = generated_json({"seed=17"}, true);
  EXPECT_EQ(a.dump(2), b.dump(2));
  EXPECT_NE(a.dump(), generated_json({"seed=18"}, true).dump());
  EXPECT_EQ(a.at("seed"), 17);
  EXPECT_EQ(a.at("provenance").at("seed"), 17);
}

TEST(microCellIo, GeometryRoundTrips) {
  const CellSettings s = load_cell_settings(kCellConfig, {"cell_size_m=0.0045"});
  const GeneratedCell c = generate_cell(s.cell, s.seed);
  const nlohmann::json j = nlohmann::json::parse(cell_json(c, s, nullptr, Provenance::make("test", "", s.seed)).dump());
  const CellGeometry g = cell_geometry_from_json(j, "cell.json");
  ASSERT_EQ(g.pores.size(), c.geometry.pores.size());
  for (std::size_t i = 0; i < g.pores.size(); ++i) {
    EXPECT_EQ(g.pores[i].center_m.x, c.geometry.pores[i].center_m.x);
    EXPECT_EQ(g.pores[i].diameter_m, c.geometry.pores[i].diameter_m);
  }
  ASSERT_EQ(g.seeds.size(), c.geometry.seeds.size());
  EXPECT_EQ(g.seeds.back().tip_m.y, c.geometry.seeds.back().tip_m.y);
  EXPECT_EQ(g.porosity(), c.geometry.porosity());
  EXPECT_TRUE(j.at("discretization").is_null());
  nlohmann::json wrong = j;
  wrong["format"] = "uhpc-micro-cell/0";
  EXPECT_EQ(test::error_of<InputError>([&] { cell_geometry_from_json(wrong, "cell.json"); }),
            "cell.json: key 'format': expected \"uhpc-micro-cell/1\", got \"uhpc-micro-cell/0\"");
}

TEST(microCellIo, BadInputNamesFileKeyAndReason) {
  auto error = [](const std::vector<std::string>& o) {
    return test::error_of<InputError>([&] { load_cell_settings(kCellConfig, o); });
  };
  EXPECT_EQ(error({"microstructure.area_porosity=0.3"}),
            kMicro + ": key 'area_porosity': value 0.3 is out of range, must be in (0, 0.3)");
  EXPECT_EQ(error({"microstructure.burr.alpha=0"}), kMicro + ": key 'burr.alpha': value 0 is out of range, must be > 0");
  EXPECT_EQ(error({"microstructure.burr.truncation_m=7e-5"}),
            kMicro + ": key 'burr.truncation_m': value 7e-05 must exceed gamma_m = 7.7e-05 (the smallest pore)");
  EXPECT_EQ(error({"cell_size_m=0.00035"}),
            kCellConfig + ": key 'cell_size_m': cell side 0.00035 m cannot hold the smallest pore (7.7e-05 m) with two "
                          "ligaments of 0.00015 m (placement.min_ligament_m)");
  // Two ligaments as wide as the cell leave no room at any pore size: the ligament is named (issue 48).
  EXPECT_EQ(error({"cell_size_m=0.0003"}),
            kCellConfig + ": key 'placement.min_ligament_m': value 0.00015 leaves no room for a pore: two ligaments "
                          "of 0.00015 m are as wide as the cell side 0.0003 m (cell_size_m) or wider");
  EXPECT_EQ(error({"seeds.length_m=1e-4"}),
            kCellConfig + ": key 'seeds.length_m': value 0.0001 must be below half of "
                          "placement.min_ligament_m (0.00015), so that seeds cannot reach another pore, seed or edge");
  // Beyond the mesh budget (2e6 nodes) before gmsh is asked: a 1 m cell, a 10 nm spacing.
  EXPECT_EQ(error({"cell_size_m=1.0"}),
            kCellConfig + ": key 'discretization.nominal_spacing_m': a cell of side 1 m (cell_size_m) at spacing "
                          "5e-05 m needs about 4.6e+08 mesh nodes, more than the 2e+06 a cell may have (reduce "
                          "cell_size_m or raise nominal_spacing_m)");
  EXPECT_NE(error({"discretization.nominal_spacing_m=1e-8"}).find("mesh nodes, more than the 2e+06"), std::string::npos);
  EXPECT_EQ(error({"loading_direction=z"}), kCellConfig + ": key 'loading_direction': value 'z' is not one of: x, y");
  EXPECT_EQ(error({"placement.min_ligament=3"}),
            kCellConfig + ": key 'placement.min_ligament': unknown key (did you mean 'min_ligament_m'?)");
}

TEST(microCellIo, UnreachablePorosityIsBadInput) {
  // Before drawing: one smallest pore already overshoots the band.
  EXPECT_EQ(test::error_of<InputError>([&] {
              load_cell_settings(kCellConfig, {"microstructure.area_porosity=0.0002", "porosity.tolerance=0.00001"});
            }),
            kMicro + ": key 'area_porosity': porosity 0.0002 +- 1e-05 is unreachable: one smallest pore (7.7e-05 m) "
                     "alone gives 0.00052");
  // While drawing: the draw budget runs out.
  const CellSettings s = load_cell_settings(kCellConfig, {"porosity.max_draws=3"});
  EXPECT_EQ(test::error_of<InputError>([&] {
              try {
                generate_cell(s.cell, s.seed);
              } catch (const CellGenerationError& e) {
                rethrow_as_input_error(e, s, kCellConfig);
              }
            }).rfind(kMicro + ": key 'area_porosity': porosity 0.034 not reached within 0.0005 after 3 draws", 0),
            0u);
}

}  // namespace
}  // namespace uhpc::micro
