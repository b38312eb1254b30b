#pragma once
// Reading and validating the cell configuration (data/micro_cell.json) and the microstructure it
// names (data/microstructure.json) into the physics-side options. Every problem is a uhpc::InputError
// naming the file, the key and the reason.
#include <cstdint>
#include <string>
#include <vector>

#include "cell_generator.hpp"
#include "cell_mesh.hpp"
#include "cell_picture.hpp"
#include "uhpc/config.hpp"

namespace uhpc::micro {

struct CellSettings {
  CellOptions cell;
  MeshOptions mesh;
  bool mesh_enabled = true;
  PictureOptions picture;
  std::uint64_t seed = 0;
  std::string microstructure_file;  // as resolved (relative paths are relative to the cell config)
  std::string config_hash;          // hash of the effective cell config and microstructure together
  std::string config_hash_including_notes;  // the same in the former scheme (Config::hash_including_notes)
  // Where the cell side came from, for messages: the cell config's cell_size_m, or an ensemble's
  // cell_sizes_m entry that replaced it (load_cell_settings' size_override_m).
  std::string side_input = "cell_size_m";
};

// Overrides ("key=value" from --set) whose key starts with `prefix` + "." are returned with the prefix
// stripped and removed from `overrides`.
std::vector<std::string> take_prefixed_overrides(std::vector<std::string>& overrides, const std::string& prefix);

// The overrides of a command whose config names a cell config: "cell.<key>=v" and
// "microstructure.<key>=v" are removed from `overrides` and returned as the cell config's own
// ("<key>=v" and "microstructure.<key>=v"); the rest stay for the command's config.
std::vector<std::string> take_cell_overrides(std::vector<std::string>& overrides);

// The optional "cell_overrides" section of a command's config (`uhpc-micro run`, `ensemble`): cell
// config keys the command sets for its cells, e.g. {"discretization": {"nominal_spacing_m": 1e-4}},
// as "<key>=v" overrides (nested keys joined by dots), followed by `command_line` (the command's
// take_cell_overrides), which therefore win. Marks the section read.
std::vector<std::string> config_cell_overrides(const Config& cfg, const std::vector<std::string>& command_line);

// Loads both files (overrides "microstructure.*" go to the microstructure file, the rest to the cell
// config), validates everything and checks that a cell can be generated at all (cell too small,
// unreachable porosity). Calls finish() on both configs. `size_override_m` > 0 replaces cell_size_m
// and `seed_override` (when set) replaces seed: the ensemble uses them.
CellSettings load_cell_settings(const std::string& cell_config_path, std::vector<std::string> overrides,
                                double size_override_m = 0.0, const std::uint64_t* seed_override = nullptr);

// Turns a CellGenerationError of generate_cell into the InputError the user sees, naming the key that
// controls it in `settings`' files.
[[noreturn]] void rethrow_as_input_error(const CellGenerationError& e, const CellSettings& settings,
                                         const std::string& cell_config_path);

}  // namespace uhpc::micro
