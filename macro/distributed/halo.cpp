#include "distributed/halo.hpp"

#include <algorithm>
#include <stdexcept>

#include "distributed/reach_map.hpp"

namespace uhpc::macro::distributed {

Halo::Halo(const ParticlePartition& partition, const ParticleSet& owned, const std::vector<double>& node_reach,
           const std::vector<double>& row_reach, double cell)
    : comm_(partition.comm()), ghosts_(owned.width) {
  if (node_reach.size() != owned.size() || row_reach.size() != owned.size())
    throw std::invalid_argument("Halo: one node reach and one row reach for each owned particle");
  std::vector<double> x(3 * owned.size());
  for (std::size_t i = 0; i < owned.size(); ++i) std::copy(owned.at(i), owned.at(i) + 3, x.data() + 3 * i);
  const std::vector<ReachMap> maps =
      ReachMap::gather(ReachMap(x.data(), row_reach.data(), owned.size(), cell), comm_.get());
  std::vector<std::uint32_t> rows;
  std::vector<int> ranks;
  for (std::size_t i = 0; i < owned.size(); ++i)
    for (int q = 0; q < partition.size(); ++q)
      if (q != partition.rank() && maps[static_cast<std::size_t>(q)].needs(x.data() + 3 * i, node_reach[i])) {
        rows.push_back(static_cast<std::uint32_t>(i));
        ranks.push_back(q);
      }
  transfer_ = std::make_unique<Transfer>(std::move(rows), std::move(ranks), comm_.get());
  ghosts_ = transfer_->carry(owned);
}

std::vector<std::uint32_t> Halo::sent_rows() const {
  std::vector<std::uint32_t> rows = transfer_->rows();
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  return rows;
}

ParticleSet Halo::local(const ParticleSet& owned, std::vector<std::size_t>* owned_at) const {
  if (owned.width != ghosts_.width || !std::is_sorted(owned.id.begin(), owned.id.end()))
    throw std::logic_error("Halo::local: the owned set must be the halo's, sorted by id");
  ParticleSet merged(owned.width);
  merged.id.reserve(owned.size() + ghosts_.size());
  merged.values.reserve(owned.values.size() + ghosts_.values.size());
  if (owned_at) owned_at->clear();
  std::size_t a = 0, g = 0;
  while (a < owned.size() || g < ghosts_.size()) {
    if (g == ghosts_.size() || (a < owned.size() && owned.id[a] < ghosts_.id[g])) {
      if (owned_at) owned_at->push_back(merged.size());
      merged.push_back(owned.id[a], owned.at(a));
      ++a;
    } else {
      merged.push_back(ghosts_.id[g], ghosts_.at(g));
      ++g;
    }
  }
  return merged;
}

}  // namespace uhpc::macro::distributed
