#include "uhpc/resources.hpp"

#include <sys/resource.h>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace uhpc {

double peak_memory_MiB() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return -1.0;
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

double heap_in_use_bytes() {
#if defined(__SANITIZE_ADDRESS__)
  return -1.0;  // the sanitizer's allocator replaces malloc's, whose counts would then be zero
#elif defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 33))
  const struct mallinfo2 m = mallinfo2();
  return static_cast<double>(m.uordblks + m.hblkhd);
#else
  return -1.0;
#endif
}

}  // namespace uhpc
