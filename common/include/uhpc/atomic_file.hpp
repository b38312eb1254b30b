#pragma once
// Files are written under a temporary name in the same directory and renamed into place, so a reader
// (or a crash) never sees a half-written result.
#include <filesystem>
#include <string_view>

namespace uhpc {

// The temporary name used for `target` while it is being written: "<dir>/.<name>.tmp.<pid>".
std::filesystem::path temporary_path_for(const std::filesystem::path& target);

// Writes `content` to `target` atomically (temporary file, flush, rename). Creates missing parent
// directories. Throws std::runtime_error naming the path on failure.
void write_text_atomic(const std::filesystem::path& target, std::string_view content);

// Renames a finished temporary file onto its target (used by writers that produce the file
// themselves, e.g. HDF5). Throws std::runtime_error naming both paths on failure.
void commit_temporary(const std::filesystem::path& temporary, const std::filesystem::path& target);

}  // namespace uhpc
