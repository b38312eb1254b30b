#pragma once
// Reading and validating the elastic-analysis configuration (data/micro_elastic.json): the cell
// config it names (read by load_cell_settings, exactly as `generate` reads it), the matrix of the
// microstructure file (Table 2), and the analysis options. Every problem is a uhpc::InputError naming
// the file, the key and the reason.
#include <string>
#include <vector>

#include "cell_settings.hpp"
#include "plane_strain.hpp"
#include "uniaxial_cell.hpp"

namespace uhpc::micro {

struct ElasticSettings {
  CellSettings cell;
  std::string cell_config;  // as resolved (relative to the elastic config)
  PlaneStrain material;
  UniaxialOptions options;
  std::string config_hash;  // the elastic config and the cell settings together
};

// Overrides: "cell.<key>=v" go to the cell config, "microstructure.<key>=v" to the microstructure
// file, the rest to the elastic config.
ElasticSettings load_elastic_settings(const std::string& config_path, std::vector<std::string> overrides);

}  // namespace uhpc::micro
