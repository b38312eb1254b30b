// The output lock (uhpc/output_lock.hpp): one writer per output, a second one told who holds it, and a
// holder that dies releasing it. Locks are flock(2)s on open files, so a second OutputLock of this process
// is refused like another process would be; the dead-holder case uses a real child process.
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "uhpc/errors.hpp"
#include "uhpc/output_lock.hpp"

namespace fs = std::filesystem;
using testing::HasSubstr;
using testing::StartsWith;

namespace {

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::path(UHPC_BINARY_DIR) / "test_output_lock" / name;
  fs::remove_all(dir);
  return dir;
}

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const uhpc::InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

std::string first_line(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  return line;
}

}  // namespace

TEST(OutputLock, ASecondWriterIsRefusedNamingTheHolder) {
  const fs::path dir = fresh_dir("second_writer") / "run";
  const uhpc::OutputLock first = uhpc::lock_output_directory(dir, "uhpc-macro");
  ASSERT_TRUE(first.held());
  EXPECT_TRUE(fs::is_directory(dir));  // made on the way
  const std::string holder = "pid " + std::to_string(::getpid()) + " (uhpc-macro) on host ";
  EXPECT_THAT(first_line(dir / ".uhpc.lock"), StartsWith(holder));

  const std::string message = message_of([&] { (void)uhpc::lock_output_directory(dir, "uhpc-micro run"); });
  EXPECT_THAT(message, StartsWith(dir.string() + ": in use by " + holder));
  EXPECT_THAT(message, HasSubstr(": wait for it to end or write elsewhere (lock file " + (dir / ".uhpc.lock").string()));
}

TEST(OutputLock, ReleasedLockRemovesItsFileAndFreesTheDirectory) {
  const fs::path dir = fresh_dir("released");
  {
    const uhpc::OutputLock lock = uhpc::lock_output_directory(dir, "uhpc-micro run");
    EXPECT_TRUE(fs::exists(dir / ".uhpc.lock"));
  }
  EXPECT_FALSE(fs::exists(dir / ".uhpc.lock"));
  const uhpc::OutputLock again = uhpc::lock_output_directory(dir, "uhpc-micro run");
  EXPECT_TRUE(again.held());
}

TEST(OutputLock, MovedLockIsReleasedOnce) {
  const fs::path dir = fresh_dir("moved");
  uhpc::OutputLock outer;
  EXPECT_FALSE(outer.held());
  {
    uhpc::OutputLock inner = uhpc::lock_output_directory(dir, "uhpc-calibrate");
    outer = std::move(inner);
  }  // the moved-from lock releases nothing
  EXPECT_TRUE(outer.held());
  EXPECT_THAT(message_of([&] { (void)uhpc::lock_output_directory(dir, "uhpc-calibrate"); }), HasSubstr("in use by"));
}

// A holder killed with SIGKILL cannot clean up: its lock file stays, but the kernel has dropped the flock,
// so the next writer takes the directory and records itself over the dead holder's record.
TEST(OutputLock, AKilledHolderLeavesTheDirectoryFree) {
  const fs::path dir = fresh_dir("killed");
  int ready[2];
  ASSERT_EQ(::pipe(ready), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::close(ready[0]);
    try {
      const uhpc::OutputLock lock = uhpc::lock_output_directory(dir, "holder");
      (void)!::write(ready[1], "x", 1);
      ::pause();  // killed here, holding the lock
    } catch (...) {
    }
    ::_exit(3);
  }
  ::close(ready[1]);
  char byte = 0;
  ASSERT_EQ(::read(ready[0], &byte, 1), 1) << "the child could not take the lock";
  ::close(ready[0]);
  EXPECT_THAT(message_of([&] { (void)uhpc::lock_output_directory(dir, "second"); }),
              HasSubstr("in use by pid " + std::to_string(child) + " (holder)"));
  ::kill(child, SIGKILL);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(fs::exists(dir / ".uhpc.lock"));  // left behind by the killed holder
  const uhpc::OutputLock lock = uhpc::lock_output_directory(dir, "second");
  EXPECT_TRUE(lock.held());
  EXPECT_THAT(first_line(dir / ".uhpc.lock"), StartsWith("pid " + std::to_string(::getpid()) + " (second)"));
}

// Outputs that are one file lock the file, not its directory: two files of one directory are two outputs.
TEST(OutputLock, OneFileOutputsLockTheFileNotTheDirectory) {
  const fs::path dir = fresh_dir("files");
  const uhpc::OutputLock a = uhpc::lock_output_file(dir / "a.json", "uhpc-calibrate");
  const uhpc::OutputLock b = uhpc::lock_output_file(dir / "b.json", "uhpc-calibrate");
  EXPECT_TRUE(a.held() && b.held());
  EXPECT_EQ(a.file(), dir / ".a.json.lock");
  EXPECT_THAT(message_of([&] { (void)uhpc::lock_output_file(dir / "a.json", "uhpc-calibrate"); }),
              StartsWith((dir / "a.json").string() + ": in use by pid "));
}

TEST(OutputLock, AnUnusableOutputIsBadInput) {
  const fs::path dir = fresh_dir("unusable");
  fs::create_directories(dir / "a_directory");
  std::ofstream(dir / "a_file") << "x";
  EXPECT_EQ(message_of([&] { (void)uhpc::lock_output_file(dir / "a_directory", "p"); }),
            (dir / "a_directory").string() + ": is a directory, not a file that can be written");
  EXPECT_EQ(message_of([&] { (void)uhpc::lock_output_directory(dir / "a_file", "p"); }),
            (dir / "a_file").string() + ": cannot create the directory '" + (dir / "a_file").string() +
                "': Not a directory");
  EXPECT_THAT(message_of([&] { (void)uhpc::lock_output_file("/proc/uhpc_output_lock_test.h5", "p"); }),
              StartsWith("/proc/uhpc_output_lock_test.h5: cannot create the lock file '/proc/.uhpc_output_lock_test.h5.lock': "));
}
