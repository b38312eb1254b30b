#include "distributed/huge_pages.hpp"

#include <sys/mman.h>

#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <new>

namespace uhpc::macro::distributed {
namespace {
std::atomic<bool> advise_large_blocks{false};
constexpr std::size_t kLargeBlock = std::size_t{4} << 20;
constexpr std::uintptr_t kPage = 4096;

// The whole pages inside [p, p + bytes), advised as huge-page candidates. A refusal changes nothing.
void advise(void* p, std::size_t bytes) {
  const std::uintptr_t from = (reinterpret_cast<std::uintptr_t>(p) + kPage - 1) & ~(kPage - 1);
  const std::uintptr_t to = (reinterpret_cast<std::uintptr_t>(p) + bytes) & ~(kPage - 1);
  if (to > from) (void)madvise(reinterpret_cast<void*>(from), to - from, MADV_HUGEPAGE);
}

void* allocate(std::size_t bytes) {
  if (bytes == 0) bytes = 1;
  for (;;) {
    if (void* p = std::malloc(bytes)) {
      if (bytes >= kLargeBlock && advise_large_blocks.load(std::memory_order_relaxed)) advise(p, bytes);
      return p;
    }
    const std::new_handler handler = std::get_new_handler();
    if (!handler) throw std::bad_alloc();
    handler();
  }
}
}  // namespace

void advise_huge_pages_for_large_blocks() { advise_large_blocks.store(true, std::memory_order_relaxed); }

}  // namespace uhpc::macro::distributed

// new and delete replaced as a pair, malloc and free, so that no runtime (a sanitizer's included) sees a
// block of one freed by the other. The nothrow forms call these; the aligned forms stay the library's.
void* operator new(std::size_t bytes) { return uhpc::macro::distributed::allocate(bytes); }
void* operator new[](std::size_t bytes) { return uhpc::macro::distributed::allocate(bytes); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
