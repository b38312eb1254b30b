#pragma once
// What the running process has used, for run records and benchmarks.

namespace uhpc {

// The process's peak resident set so far, MiB (getrusage ru_maxrss; on Linux in KiB); -1 when the
// system does not tell. It includes every thread and everything done before the call.
double peak_memory_MiB();

// The bytes the heap holds now: malloc's blocks in use in every arena, mmapped ones included (glibc's
// mallinfo2); -1 where the C library does not tell. The difference of two calls is what was allocated
// in between and is still held, however the allocator placed it (unlike the resident set, which keeps
// pages freed earlier).
double heap_in_use_bytes();

}  // namespace uhpc
