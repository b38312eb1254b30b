// Large blocks advised as transparent huge pages once a distributed run asks for it (huge_pages.hpp):
// the advice lands on the block's pages (VmFlags "hg" in /proc/self/smaps), only after it was asked
// for, only on blocks of 4 MB and more, and the memory holds what is written to it.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "distributed/huge_pages.hpp"

namespace {

// Whether the mapping that holds p carries the huge-page advice (the kernel's "hg" flag).
bool advised(const void* p) {
  const auto at = reinterpret_cast<std::uintptr_t>(p);
  std::ifstream smaps("/proc/self/smaps");
  std::string line;
  bool inside = false;
  while (std::getline(smaps, line)) {
    std::uintptr_t from = 0, to = 0;
    char dash = 0;
    std::istringstream head(line);
    if (head >> std::hex >> from >> dash >> to && dash == '-') {
      inside = from <= at && at < to;
    } else if (inside && line.rfind("VmFlags:", 0) == 0) {
      std::istringstream flags(line.substr(8));
      std::string flag;
      while (flags >> flag)
        if (flag == "hg") return true;
      return false;
    }
  }
  ADD_FAILURE() << "no mapping in /proc/self/smaps holds " << p;
  return false;
}

TEST(MacroHugePages, LargeBlocksAreAdvisedOnlyOnceAskedFor) {
  if (!std::filesystem::exists("/sys/kernel/mm/transparent_hugepage/enabled"))
    GTEST_SKIP() << "this kernel has no transparent huge pages";
  const std::size_t large = (std::size_t{8} << 20) / sizeof(double), small = (std::size_t{1} << 20) / sizeof(double);
  const auto before = std::make_unique<double[]>(large);
  EXPECT_FALSE(advised(before.get() + large / 2));

  uhpc::macro::distributed::advise_huge_pages_for_large_blocks();
  std::vector<double> after(large);
  const auto below_threshold = std::make_unique<double[]>(small);
  EXPECT_TRUE(advised(after.data() + large / 2));
  EXPECT_FALSE(advised(below_threshold.get() + small / 2));

  for (std::size_t i = 0; i < large; ++i) after[i] = static_cast<double>(i);
  double sum = 0.0;
  for (const double v : after) sum += v;
  EXPECT_EQ(sum, 0.5 * static_cast<double>(large) * static_cast<double>(large - 1));
}

}  // namespace
