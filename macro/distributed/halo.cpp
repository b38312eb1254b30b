#include "distributed/halo.hpp"

#include <stdexcept>

namespace uhpc::macro::distributed {

Halo::Halo(const ParticlePartition& partition, const ParticleSet& owned, const std::vector<double>& reach)
    : ghosts_(owned.width) {
  if (reach.size() != owned.size()) throw std::invalid_argument("Halo: one reach for each owned particle");
  std::vector<std::uint32_t> rows;
  std::vector<int> ranks, meeting;
  for (std::size_t i = 0; i < owned.size(); ++i) {
    const double* x = owned.at(i);
    const double lo[3] = {x[0] - reach[i], x[1] - reach[i], x[2] - reach[i]};
    const double hi[3] = {x[0] + reach[i], x[1] + reach[i], x[2] + reach[i]};
    partition.ranks_meeting(lo, hi, meeting);
    for (int r : meeting) {
      if (r == partition.rank()) continue;
      rows.push_back(static_cast<std::uint32_t>(i));
      ranks.push_back(r);
    }
  }
  transfer_ = std::make_unique<Transfer>(std::move(rows), std::move(ranks), partition.comm());
  ghosts_ = transfer_->carry(owned);
}

}  // namespace uhpc::macro::distributed
