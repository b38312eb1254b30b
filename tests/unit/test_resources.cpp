// What the process reports of its memory (uhpc/resources.hpp): the heap in use follows an allocation
// of known size up and back down (small blocks from the arenas and large ones mmapped alike), from this
// thread and from another thread's arena; the peak resident set is at least the heap touched.
#include <gtest/gtest.h>

#include <cstddef>
#include <memory>
#include <thread>
#include <vector>

#include "uhpc/resources.hpp"

namespace {

constexpr double kSlack = 64.0 * 1024.0;  // malloc's own bookkeeping and the test framework's noise

// -1: the C library (or a sanitizer's allocator) does not report its heap; glibc always does.
#define SKIP_WITHOUT_HEAP_COUNTS()                                                 \
  if (uhpc::heap_in_use_bytes() < 0.0) GTEST_SKIP() << "no heap counts in this build"

void expect_follows(std::size_t bytes) {
  const double before = uhpc::heap_in_use_bytes();
  {
    std::vector<char> block(bytes, 1);
    const double held = uhpc::heap_in_use_bytes() - before;
    EXPECT_GE(held, static_cast<double>(bytes)) << bytes << " bytes allocated";
    EXPECT_LE(held, static_cast<double>(bytes) + kSlack) << bytes << " bytes allocated";
  }
  EXPECT_NEAR(uhpc::heap_in_use_bytes(), before, kSlack) << bytes << " bytes freed";
}

TEST(Resources, HeapInUseFollowsASmallAllocation) {
  SKIP_WITHOUT_HEAP_COUNTS();
  expect_follows(100 * 1024);
}

TEST(Resources, HeapInUseFollowsALargeMappedAllocation) {
  SKIP_WITHOUT_HEAP_COUNTS();
  expect_follows(64 * 1024 * 1024);
}

TEST(Resources, HeapInUseCountsAnotherThreadsArena) {
  SKIP_WITHOUT_HEAP_COUNTS();
  const double before = uhpc::heap_in_use_bytes();
  constexpr std::size_t kBytes = 1000, kBlocks = 2000;  // small blocks: from that thread's own arena
  std::vector<std::unique_ptr<char[]>> blocks;
  std::thread([&] {
    for (std::size_t k = 0; k < kBlocks; ++k) blocks.emplace_back(new char[kBytes]());
  }).join();
  EXPECT_GE(uhpc::heap_in_use_bytes() - before, static_cast<double>(kBytes * kBlocks));
  blocks.clear();
  EXPECT_NEAR(uhpc::heap_in_use_bytes(), before, kSlack);
}

TEST(Resources, PeakResidentSetCoversWhatWasTouched) {
  std::vector<char> block(32 * 1024 * 1024, 1);
  EXPECT_GE(uhpc::peak_memory_MiB(), 32.0);
}

}  // namespace
