#include "uhpc/resources.hpp"

#include <sys/resource.h>

namespace uhpc {

double peak_memory_MiB() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return -1.0;
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

}  // namespace uhpc
