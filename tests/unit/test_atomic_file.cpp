// write_text_atomic and friends: content arrives complete under the real name, nothing is left
// under the temporary name, and failures name the path and the OS reason.
#include "uhpc/atomic_file.hpp"
#include "uhpc/errors.hpp"

#include <unistd.h>

#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "test_support.hpp"

namespace fs = std::filesystem;

namespace {

using AtomicFileTest = uhpc::test::ScratchDirTest;

using uhpc::test::read_file;
std::vector<std::string> names_in(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
  return names;
}

}  // namespace

TEST(TemporaryPath, HiddenNextToTargetWithPid) {
  const fs::path tmp = uhpc::temporary_path_for("/data/run/result.json");
  EXPECT_EQ(tmp, fs::path("/data/run/.result.json.tmp." + std::to_string(::getpid())));
  EXPECT_EQ(uhpc::temporary_path_for("a.h5"), fs::path(".a.h5.tmp." + std::to_string(::getpid())));
}

TEST(TemporaryPath, RejectsPathWithoutFileName) {
  EXPECT_THROW(uhpc::temporary_path_for("/data/run/"), std::invalid_argument);
}

TEST_F(AtomicFileTest, WritesContentAndLeavesNoTemporary) {
  const fs::path target = dir_ / "summary.json";
  uhpc::write_text_atomic(target, "{\"peak_stress_Pa\": 1.5e7}\n");
  EXPECT_EQ(read_file(target), "{\"peak_stress_Pa\": 1.5e7}\n");
  EXPECT_FALSE(fs::exists(uhpc::temporary_path_for(target)));
  EXPECT_EQ(names_in(dir_), std::vector<std::string>{"summary.json"});
}

TEST_F(AtomicFileTest, ReplacesExistingFile) {
  const fs::path target = dir_ / "out.txt";
  uhpc::write_text_atomic(target, "first version, longer than the second\n");
  uhpc::write_text_atomic(target, "second\n");
  EXPECT_EQ(read_file(target), "second\n");
  EXPECT_EQ(names_in(dir_).size(), 1u);
}

TEST_F(AtomicFileTest, KeepsBinaryAndEmptyContent) {
  const std::string binary("a\0b\n\xff", 5);
  uhpc::write_text_atomic(dir_ / "bin", binary);
  EXPECT_EQ(read_file(dir_ / "bin"), binary);
  uhpc::write_text_atomic(dir_ / "empty", "");
  EXPECT_TRUE(fs::exists(dir_ / "empty"));
  EXPECT_EQ(fs::file_size(dir_ / "empty"), 0u);
}

TEST_F(AtomicFileTest, CreatesParentDirectories) {
  const fs::path target = dir_ / "a" / "b" / "c.csv";
  uhpc::write_text_atomic(target, "t,v\n0,1\n");
  EXPECT_EQ(read_file(target), "t,v\n0,1\n");
}

TEST_F(AtomicFileTest, ErrorNamesPathAndReason) {
  // A regular file where a directory is needed: creating the parent must fail.
  uhpc::write_text_atomic(dir_ / "blocker", "x");
  const fs::path target = dir_ / "blocker" / "sub" / "out.json";
  try {
    uhpc::write_text_atomic(target, "{}");
    FAIL() << "expected an exception";
  } catch (const uhpc::InputError& e) {  // an unusable output path is bad input (exit 2)
    const std::string message = e.what();
    EXPECT_NE(message.find(target.string()), std::string::npos) << message;
    EXPECT_NE(message.find("Not a directory"), std::string::npos) << message;
  }
}

// A killed run leaves its temporary behind: the next writer of the same target removes it, but not
// the temporary of a writer that is still alive (pid 1 here).
TEST_F(AtomicFileTest, TemporariesOfKilledWritersAreRemovedByTheNextWriter) {
  const fs::path target = dir_ / "result.json";
  const fs::path dead = dir_ / ".result.json.tmp.999999999";  // above any pid_max: no such process
  const fs::path alive = dir_ / ".result.json.tmp.1";
  const fs::path other = dir_ / ".other.json.tmp.999999999";
  for (const fs::path& p : {dead, alive, other}) std::ofstream(p) << "half";
  uhpc::write_text_atomic(target, "{}");
  EXPECT_FALSE(fs::exists(dead));
  EXPECT_TRUE(fs::exists(alive));
  EXPECT_TRUE(fs::exists(other));  // another target's
  EXPECT_EQ(read_file(target), "{}");
}

TEST_F(AtomicFileTest, FailedRenameRemovesTemporary) {
  // The target is an existing non-empty directory, so the final rename fails: bad input (exit 2), the
  // user's path to fix, not an internal error (issue 48).
  const fs::path target = dir_ / "taken";
  fs::create_directories(target / "inside");
  EXPECT_THROW(uhpc::write_text_atomic(target, "data"), uhpc::InputError);
  EXPECT_FALSE(fs::exists(uhpc::temporary_path_for(target)));
}

TEST_F(AtomicFileTest, CommitTemporaryRenamesAndNamesBothPathsOnError) {
  const fs::path target = dir_ / "result.h5";
  const fs::path tmp = uhpc::temporary_path_for(target);
  { std::ofstream(tmp) << "payload"; }
  uhpc::commit_temporary(tmp, target);
  EXPECT_EQ(read_file(target), "payload");
  EXPECT_FALSE(fs::exists(tmp));

  try {
    uhpc::commit_temporary(tmp, target);  // the temporary is gone now
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(tmp.string()), std::string::npos) << message;
    EXPECT_NE(message.find(target.string()), std::string::npos) << message;
    EXPECT_NE(message.find("No such file"), std::string::npos) << message;
  }
}

TEST_F(AtomicFileTest, SyncToDiskNamesMissingFile) {
  uhpc::write_text_atomic(dir_ / "f", "x");
  EXPECT_NO_THROW(uhpc::sync_to_disk(dir_ / "f"));
  try {
    uhpc::sync_to_disk(dir_ / "missing");
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find((dir_ / "missing").string()), std::string::npos) << e.what();
  }
}
