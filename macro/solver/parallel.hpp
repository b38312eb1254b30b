#pragma once
// Below this many particles the solver's own loops run on one thread (OpenMP `if` clauses): a
// parallel region costs a fork and a barrier, which for a few thousand particles outweighs the work,
// and on an oversubscribed machine each barrier can wait a whole scheduler slice. (The neighbour
// search and RK evaluation of common/ always run in parallel.)
#include <cstdint>

namespace uhpc::macro {
constexpr std::int64_t kParallelMinParticles = 4096;
// Loops over RK rows are split in static chunks of this many rows, dealt to the threads in turn: the
// costly rows (rebuilt lazy rows, contact, fragments) cluster in index ranges, which a plain static
// split would hand to one thread. A fixed chunk keeps the work (and each thread's sums) deterministic;
// with one thread the rows are taken in order as before.
constexpr std::int64_t kRowChunk = 1024;
}  // namespace uhpc::macro
