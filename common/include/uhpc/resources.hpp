#pragma once
// What the running process has used, for run records and benchmarks.

namespace uhpc {

// The process's peak resident set so far, MiB (getrusage ru_maxrss; on Linux in KiB); -1 when the
// system does not tell. It includes every thread and everything done before the call.
double peak_memory_MiB();

}  // namespace uhpc
