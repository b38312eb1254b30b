#pragma once
// One writer per output at a time (issue 48). Two runs given the same --out would interleave their
// files (a result.json of one beside the fields.h5 of the other), so a program takes a lock before it
// writes and a second writer stops with exit 2 naming the holder.
//
// The lock is an flock(2) on a small file (".uhpc.lock" in an output directory, ".<name>.lock" beside an
// output file) that records its holder: "pid 1234 (uhpc-macro) on host node01 since 2026-12-06T16:00:00Z".
// The kernel releases an flock when its holder exits, however it exits, so a crashed or killed run never
// leaves a directory locked; the file it leaves behind is taken over by the next writer. A lock released
// normally removes its file.
#include <filesystem>
#include <string>

namespace uhpc {

class OutputLock {
 public:
  OutputLock() = default;  // holds nothing
  OutputLock(OutputLock&& other) noexcept;
  OutputLock& operator=(OutputLock&& other) noexcept;
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;
  ~OutputLock();  // releases: removes the lock file, then closes it

  bool held() const { return fd_ >= 0; }
  const std::filesystem::path& file() const { return file_; }

  // Takes the lock whose file is `lock_file` for `program` (the name the holder is recorded under).
  // `output` is the directory or file the lock guards, as the user gave it, for the message. A lock held
  // by another process (or another OutputLock of this one) throws InputError:
  //   "<output>: in use by pid 1234 (uhpc-macro) on host h since <UTC time>: wait for it to end or write
  //    elsewhere"
  // The lock file's directory must exist; a lock file that cannot be made throws InputError naming it.
  static OutputLock acquire(const std::filesystem::path& lock_file, const std::filesystem::path& output,
                            const std::string& program);

 private:
  OutputLock(int fd, std::filesystem::path file) : fd_(fd), file_(std::move(file)) {}
  void release() noexcept;
  int fd_ = -1;
  std::filesystem::path file_;
};

// Locks the output directory `directory` (created when missing, with its parents) through
// DIRECTORY/.uhpc.lock. A path that cannot be a directory (a file in the way, /proc) is an InputError.
[[nodiscard]] OutputLock lock_output_directory(const std::filesystem::path& directory, const std::string& program);

// An output file's path must not name a directory (a directory called fields.h5 left in a run's --out):
// InputError "<file>: is a directory, not a file that can be written". Called by lock_output_file and by
// programs for the files they will write, before any is written.
void require_file_path(const std::filesystem::path& file);

// Locks the output file `file` (for programs whose --out is one file) through DIR/.<name>.lock beside it,
// so that runs writing other files of the same directory do not exclude each other. Creates DIR.
[[nodiscard]] OutputLock lock_output_file(const std::filesystem::path& file, const std::string& program);

}  // namespace uhpc
