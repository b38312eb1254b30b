#include "distributed/gather.hpp"

#include <vector>

namespace uhpc::macro::distributed {

ParticleSet gather(const ParticleSet& mine, MPI_Comm comm, int root) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const bool everyone = root == kEveryRank, receives = everyone || rank == root;
  int count = static_cast<int>(mine.size());
  std::vector<int> counts(static_cast<std::size_t>(size)), starts(static_cast<std::size_t>(size), 0),
      value_counts(static_cast<std::size_t>(size)), value_starts(static_cast<std::size_t>(size), 0);
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  for (int r = 0; r < size; ++r) {
    if (r > 0) starts[r] = starts[r - 1] + counts[r - 1];
    value_counts[r] = counts[r] * mine.width;
    value_starts[r] = starts[r] * mine.width;
  }
  ParticleSet all(mine.width);
  if (receives) {
    const std::size_t total = static_cast<std::size_t>(starts.back() + counts.back());
    all.id.resize(total);
    all.values.resize(total * static_cast<std::size_t>(mine.width));
  }
  if (everyone) {
    MPI_Allgatherv(mine.id.data(), count, MPI_UINT32_T, all.id.data(), counts.data(), starts.data(), MPI_UINT32_T, comm);
    MPI_Allgatherv(mine.values.data(), count * mine.width, MPI_DOUBLE, all.values.data(), value_counts.data(),
                   value_starts.data(), MPI_DOUBLE, comm);
  } else {
    MPI_Gatherv(mine.id.data(), count, MPI_UINT32_T, all.id.data(), counts.data(), starts.data(), MPI_UINT32_T, root, comm);
    MPI_Gatherv(mine.values.data(), count * mine.width, MPI_DOUBLE, all.values.data(), value_counts.data(),
                value_starts.data(), MPI_DOUBLE, root, comm);
  }
  all.sort_by_id();
  return all;
}

}  // namespace uhpc::macro::distributed
