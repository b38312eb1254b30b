#pragma once
// Counts every allocation of the test program through the global operator new, for tests that prove a
// hot loop allocates nothing. Include in exactly one source file of a test program (each suite is its
// own executable).
#include <atomic>
#include <cstdlib>
#include <new>

namespace uhpc::test {
inline std::atomic<long> g_allocations{0};
}  // namespace uhpc::test

void* operator new(std::size_t size) {
  ++uhpc::test::g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
