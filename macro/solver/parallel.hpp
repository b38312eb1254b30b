#pragma once
// Below this many particles the solver's own loops run on one thread (OpenMP `if` clauses): a
// parallel region costs a fork and a barrier, which for a few thousand particles outweighs the work,
// and on an oversubscribed machine each barrier can wait a whole scheduler slice. (The neighbour
// search and RK evaluation of common/ always run in parallel.)
#include <cstdint>

namespace uhpc::macro {
constexpr std::int64_t kParallelMinParticles = 4096;
}  // namespace uhpc::macro
