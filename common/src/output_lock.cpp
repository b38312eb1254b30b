#include "uhpc/output_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <ctime>
#include <string>
#include <system_error>

#include <spdlog/spdlog.h>

#include "uhpc/errors.hpp"

namespace uhpc {
namespace {

namespace fs = std::filesystem;

std::string os_reason(int error) { return std::error_code(error, std::generic_category()).message(); }

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

std::string host_name() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0) return "?";
  return name;
}

// "pid 1234 (uhpc-macro) on host node01 since 2026-12-06T16:00:00Z": what a second writer is told.
std::string holder_record(const std::string& program) {
  return "pid " + std::to_string(::getpid()) + " (" + program + ") on host " + host_name() + " since " + utc_now();
}

// The holder's record, first line only (a lock file is ours to read, but not to trust to be short).
std::string read_holder(int fd) {
  char buffer[512];
  const ssize_t n = ::pread(fd, buffer, sizeof buffer - 1, 0);
  if (n <= 0) return {};
  std::string text(buffer, static_cast<std::size_t>(n));
  text = text.substr(0, text.find('\n'));
  return text;
}

// True when `fd` is the file `path` names now: a holder that releases removes the file, and a lock won on
// a removed file excludes nobody, so the winner must find its file still in place.
bool still_named_by(int fd, const fs::path& path) {
  struct stat open_file {}, named {};
  if (::fstat(fd, &open_file) != 0 || ::stat(path.c_str(), &named) != 0) return false;
  return open_file.st_dev == named.st_dev && open_file.st_ino == named.st_ino;
}

// File systems without flock (some network mounts) answer ENOLCK or EOPNOTSUPP: the run goes on, unlocked,
// and says so, rather than refusing every run there.
bool locks_unsupported(int error) { return error == ENOLCK || error == EOPNOTSUPP || error == ENOSYS; }

}  // namespace

OutputLock::OutputLock(OutputLock&& other) noexcept : fd_(other.fd_), file_(std::move(other.file_)) { other.fd_ = -1; }

OutputLock& OutputLock::operator=(OutputLock&& other) noexcept {
  if (this != &other) {
    release();
    fd_ = other.fd_;
    file_ = std::move(other.file_);
    other.fd_ = -1;
  }
  return *this;
}

OutputLock::~OutputLock() { release(); }

void OutputLock::release() noexcept {
  if (fd_ < 0) return;
  // Removed while still held, so that no one can take a lock on the file between its removal and the
  // close; a contender that opened it before is sent back to the path by still_named_by().
  if (still_named_by(fd_, file_)) ::unlink(file_.c_str());
  ::close(fd_);
  fd_ = -1;
}

OutputLock OutputLock::acquire(const fs::path& lock_file, const fs::path& output, const std::string& program) {
  // A few rounds cover a holder that releases (removes the file) between our open and our flock.
  for (int round = 0; round < 8; ++round) {
    const int fd = ::open(lock_file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0)
      throw InputError(output.string() + ": cannot create the lock file '" + lock_file.string() +
                       "': " + os_reason(errno));
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int error = errno;
      if (error == EWOULDBLOCK) {
        const std::string holder = read_holder(fd);
        ::close(fd);
        throw InputError(output.string() + ": in use by " +
                         (holder.empty() ? std::string("another run (it has not recorded itself yet)") : holder) +
                         ": wait for it to end or write elsewhere (lock file " + lock_file.string() + ")");
      }
      ::close(fd);
      if (error == EINTR) continue;
      if (locks_unsupported(error)) {
        spdlog::warn("{}: not locked, the file system does not support flock ({}): nothing stops a second run "
                     "from writing here at the same time",
                     output.string(), os_reason(error));
        return OutputLock();
      }
      throw InputError(output.string() + ": cannot lock '" + lock_file.string() + "': " + os_reason(error));
    }
    if (!still_named_by(fd, lock_file)) {
      ::close(fd);
      continue;
    }
    // The record replaces a crashed holder's, which the kernel has already unlocked.
    const std::string record = holder_record(program) + "\n";
    if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, record.data(), record.size(), 0) != static_cast<ssize_t>(record.size()))
      spdlog::warn("{}: could not record this run in its lock file ({}); the lock holds all the same",
                   lock_file.string(), os_reason(errno));
    return OutputLock(fd, lock_file);
  }
  throw InputError(output.string() + ": cannot lock '" + lock_file.string() +
                   "': its lock file keeps being replaced (another run starting and ending here)");
}

namespace {

void make_directory(const fs::path& directory, const fs::path& output) {
  std::error_code ec;
  fs::create_directories(directory, ec);
  if (ec || !fs::is_directory(directory))
    throw InputError(output.string() + ": cannot create the directory '" + directory.string() +
                     "': " + (ec ? ec.message() : std::string("a file of that name is in the way")));
}

}  // namespace

OutputLock lock_output_directory(const fs::path& directory, const std::string& program) {
  make_directory(directory, directory);
  return OutputLock::acquire(directory / ".uhpc.lock", directory, program);
}

void require_file_path(const fs::path& file) {
  if (fs::is_directory(file)) throw InputError(file.string() + ": is a directory, not a file that can be written");
}

OutputLock lock_output_file(const fs::path& file, const std::string& program) {
  const fs::path name = file.filename();
  if (name.empty() || name == "." || name == "..")
    throw InputError(file.string() + ": not a file name (the output is one file)");
  require_file_path(file);
  const fs::path directory = file.has_parent_path() ? file.parent_path() : fs::path(".");
  make_directory(directory, file);
  return OutputLock::acquire(directory / ("." + name.string() + ".lock"), file, program);
}

}  // namespace uhpc
