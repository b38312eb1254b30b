#include "distributed/halo.hpp"

#include <algorithm>
#include <stdexcept>

#include "distributed/reach_map.hpp"

namespace uhpc::macro::distributed {

Halo::Halo(const ParticlePartition& partition, const ParticleSet& owned, const std::vector<double>& node_reach,
           const std::vector<double>& row_reach, double cell)
    : ghosts_(owned.width) {
  if (node_reach.size() != owned.size() || row_reach.size() != owned.size())
    throw std::invalid_argument("Halo: one node reach and one row reach for each owned particle");
  if (!partition.balanced()) throw std::logic_error("Halo: the partition has no regions yet (balance first)");
  std::vector<double> x(3 * owned.size());
  for (std::size_t i = 0; i < owned.size(); ++i) std::copy(owned.at(i), owned.at(i) + 3, x.data() + 3 * i);
  const std::vector<ReachMap> maps =
      ReachMap::gather(ReachMap(x.data(), row_reach.data(), owned.size(), cell), partition.comm());
  double widest = 0.0;
  for (const ReachMap& m : maps) widest = std::max(widest, m.widest());
  std::vector<std::uint32_t> rows;
  std::vector<int> ranks, near;
  for (std::size_t i = 0; i < owned.size(); ++i) {
    // The ranks whose regions are near enough for the widest reach (Zoltan's box query), then each
    // by its own map.
    const double* xi = x.data() + 3 * i;
    const double r = node_reach[i] + widest;
    const double lo[3] = {xi[0] - r, xi[1] - r, xi[2] - r}, hi[3] = {xi[0] + r, xi[1] + r, xi[2] + r};
    partition.ranks_meeting(lo, hi, near);
    for (int q : near)
      if (q != partition.rank() && maps[static_cast<std::size_t>(q)].needs(xi, node_reach[i])) {
        rows.push_back(static_cast<std::uint32_t>(i));
        ranks.push_back(q);
      }
  }
  transfer_ = std::make_unique<Transfer>(std::move(rows), std::move(ranks), partition.comm());
  ghosts_ = transfer_->carry(owned);
}

}  // namespace uhpc::macro::distributed
