#pragma once
// The drivers of `uhpc-micro generate` and `uhpc-micro generate-ensemble`: configs in, files out.
#include <filesystem>
#include <string>
#include <vector>

namespace uhpc::micro {

int run_generate(const std::string& config_path, const std::vector<std::string>& overrides,
                 const std::filesystem::path& out);

int run_generate_ensemble(const std::string& config_path, const std::vector<std::string>& overrides,
                          const std::filesystem::path& out);

}  // namespace uhpc::micro
