#pragma once
// Files are written under a temporary name in the same directory and renamed into place, so a reader
// (or a crash) never sees a half-written result: the target either holds its old content or the
// complete new one. One writer per target at a time (the temporary name is per process).
#include <filesystem>
#include <string_view>

namespace uhpc {

// The temporary name used for `target` while it is being written: "<dir>/.<name>.tmp.<pid>". Removes
// the temporaries of `target` that killed writers left (their process is gone) on the way.
// Throws std::invalid_argument when `target` has no file name.
std::filesystem::path temporary_path_for(const std::filesystem::path& target);

// Writes `content` to `target` atomically (temporary file, write, fsync, rename). Creates missing
// parent directories. Throws InputError when the path is unusable (its directory cannot be made, the
// temporary cannot be created, the target cannot be renamed onto) and std::runtime_error when a write or
// flush fails, naming the path and the OS reason; the temporary file is removed then.
void write_text_atomic(const std::filesystem::path& target, std::string_view content);

// Renames a finished temporary file onto its target (used by writers that produce the file
// themselves, e.g. HDF5). Throws InputError naming both paths on failure (a directory of the target's
// name in the way, no permission: an output path the user must fix).
void commit_temporary(const std::filesystem::path& temporary, const std::filesystem::path& target);

// Flushes a finished file's data to the storage device (fsync), so that a rename or an index that
// refers to it never outlives the data after a power loss. Throws std::runtime_error naming the path.
void sync_to_disk(const std::filesystem::path& file);

}  // namespace uhpc
