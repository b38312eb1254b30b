#include "uhpc/data_dir.hpp"

#include <cstdlib>
#include <string>
#include <system_error>

#include "uhpc/errors.hpp"

namespace uhpc {

std::filesystem::path shipped_data_dir() {
  namespace fs = std::filesystem;
  if (const char* env = std::getenv("UHPC_DATA_DIR"); env != nullptr && *env != '\0') {
    std::error_code ec;
    if (!fs::is_directory(env, ec))
      throw InputError(std::string("UHPC_DATA_DIR=") + env + ": not a directory (it names the shipped data/)");
    return fs::path(env);
  }
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  const fs::path beside = ec ? fs::path() : exe.parent_path().parent_path() / "share" / "uhpc_multiscale" / "data";
  if (!beside.empty() && fs::is_directory(beside, ec)) return fs::weakly_canonical(beside, ec);
  throw InputError("the shipped data directory was not found (looked for " +
                   (beside.empty() ? std::string("<prefix>/share/uhpc_multiscale/data") : beside.string()) +
                   "); set UHPC_DATA_DIR to the project's data/ directory");
}

}  // namespace uhpc
