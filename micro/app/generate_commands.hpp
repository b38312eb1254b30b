#pragma once
// The drivers of `uhpc-micro generate`, `generate-ensemble` and `elastic`: configs in, files out.
#include <filesystem>
#include <string>
#include <vector>

namespace uhpc::micro {

int run_generate(const std::string& config_path, const std::vector<std::string>& overrides,
                 const std::filesystem::path& out);

// `uhpc-micro elastic`: the cell of the named cell config (generated and meshed as `generate` does),
// its elastic uniaxial response with the RK Galerkin solver: DIR/elastic.json (E0_bar, sigma_bar,
// energy check, counts, timing, provenance).
int run_elastic(const std::string& config_path, const std::vector<std::string>& overrides,
                const std::filesystem::path& out);

int run_generate_ensemble(const std::string& config_path, const std::vector<std::string>& overrides,
                          const std::filesystem::path& out);

}  // namespace uhpc::micro
