#include "uhpc/atomic_file.hpp"

#include "uhpc/errors.hpp"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <stdexcept>
#include <string>
#include <system_error>

namespace uhpc {
namespace {

std::string os_reason(int error) { return std::error_code(error, std::generic_category()).message(); }

std::string quoted(const std::filesystem::path& p) { return "'" + p.string() + "'"; }

void create_parent_directories(const std::filesystem::path& target) {
  const std::filesystem::path parent = target.parent_path();
  if (parent.empty()) return;
  std::error_code ec;
  std::filesystem::create_directories(parent, ec);
  if (ec) {
    // An output path that cannot be made is the user's to fix (a file in the way, /proc, no permission).
    throw InputError(target.string() + ": cannot create directory " + quoted(parent) + ": " + ec.message());
  }
}

// Owns a POSIX file descriptor so that every early exit closes it.
class Fd {
 public:
  explicit Fd(int fd) : fd_(fd) {}
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  ~Fd() {
    if (fd_ >= 0) ::close(fd_);
  }
  int get() const { return fd_; }
  // Closes now and reports the result: close() can be the first to report a failed delayed write.
  int close_now() {
    const int rc = ::close(fd_);
    fd_ = -1;
    return rc;
  }

 private:
  int fd_;
};

// Writes all of `content`, retrying on interrupts and short writes. Returns 0 or an errno value.
int write_all(int fd, std::string_view content) {
  const char* p = content.data();
  std::size_t left = content.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  return 0;
}

// Makes a rename durable. Best effort: some file systems refuse fsync on directories, and the data
// itself is already safe, so failures here are not errors.
void sync_directory(const std::filesystem::path& dir) {
  const std::filesystem::path d = dir.empty() ? std::filesystem::path(".") : dir;
  Fd fd(::open(d.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
  if (fd.get() >= 0) (void)::fsync(fd.get());
}

// Removes the temporaries of `target` left by writers that were killed: ".<name>.tmp.<pid>" whose
// process no longer exists. A live writer's (another run on the same target) is left alone.
void remove_stale_temporaries(const std::filesystem::path& target) {
  const std::string prefix = "." + target.filename().string() + ".tmp.";
  const std::filesystem::path dir = target.parent_path().empty() ? std::filesystem::path(".") : target.parent_path();
  std::error_code ec;
  for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string entry = it->path().filename().string();
    if (entry.rfind(prefix, 0) != 0) continue;
    const std::string digits = entry.substr(prefix.size());
    if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 9) continue;
    const pid_t pid = static_cast<pid_t>(std::stol(digits));
    if (pid == ::getpid() || ::kill(pid, 0) == 0 || errno != ESRCH) continue;
    std::error_code ignored;
    std::filesystem::remove(it->path(), ignored);
  }
}

}  // namespace

std::filesystem::path temporary_path_for(const std::filesystem::path& target) {
  const std::filesystem::path name = target.filename();
  if (name.empty() || name == "." || name == "..") {
    throw std::invalid_argument(target.string() + ": not a file name");
  }
  remove_stale_temporaries(target);
  return target.parent_path() / ("." + name.string() + ".tmp." + std::to_string(::getpid()));
}

void write_text_atomic(const std::filesystem::path& target, std::string_view content) {
  const std::filesystem::path temporary = temporary_path_for(target);
  create_parent_directories(target);

  Fd fd(::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644));
  if (fd.get() < 0) {
    throw InputError(target.string() + ": cannot create " + quoted(temporary) + ": " + os_reason(errno));
  }
  auto fail = [&](const char* what, int error) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw std::runtime_error(target.string() + ": cannot " + what + " " + quoted(temporary) + ": " +
                             os_reason(error));
  };
  if (const int error = write_all(fd.get(), content); error != 0) fail("write", error);
  if (::fsync(fd.get()) != 0) fail("flush", errno);
  if (fd.close_now() != 0) fail("close", errno);

  try {
    commit_temporary(temporary, target);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw;
  }
}

void commit_temporary(const std::filesystem::path& temporary, const std::filesystem::path& target) {
  std::error_code ec;
  std::filesystem::rename(temporary, target, ec);
  if (ec) {
    // The finished file cannot take its name (a directory of that name in the way, no permission, a
    // read-only file system): an output path the user must fix, exit 2 like an unusable directory.
    throw InputError(target.string() + ": cannot rename " + quoted(temporary) + " to " + quoted(target) + ": " +
                     ec.message());
  }
  sync_directory(target.parent_path());
}

void sync_to_disk(const std::filesystem::path& file) {
  Fd fd(::open(file.c_str(), O_RDONLY | O_CLOEXEC));
  if (fd.get() < 0) throw std::runtime_error(file.string() + ": cannot open to flush: " + os_reason(errno));
  if (::fsync(fd.get()) != 0) throw std::runtime_error(file.string() + ": cannot flush: " + os_reason(errno));
}

}  // namespace uhpc
