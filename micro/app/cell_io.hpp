#pragma once
// cell.json: the generated cell (pores, seeds, porosity, RNG seed), the options that made it, a
// summary of its discretization and the provenance block. Same config and seed give the same file
// except provenance.date_utc (nothing timing- or machine-dependent goes in).
#include <string>

#include <nlohmann/json.hpp>

#include "cell_generator.hpp"
#include "cell_mesh.hpp"
#include "cell_settings.hpp"
#include "uhpc/provenance.hpp"

namespace uhpc::micro {

inline constexpr const char* kCellFormat = "uhpc-micro-cell/1";

// Node counts and spacing of a discretization, and how well it covers the porous area.
nlohmann::json mesh_summary_json(const CellGeometry& cell, const CellDiscretization& mesh);

// `mesh` may be nullptr (discretization.mesh = false).
nlohmann::json cell_json(const GeneratedCell& cell, const CellSettings& settings, const CellDiscretization* mesh,
                         const Provenance& provenance);

// Reads the geometry back from a cell.json document (for the analysis). Throws uhpc::InputError
// naming `source` on a wrong format or missing keys.
CellGeometry cell_geometry_from_json(const nlohmann::json& document, const std::string& source);

}  // namespace uhpc::micro
