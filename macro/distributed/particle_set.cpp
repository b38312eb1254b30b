#include "distributed/particle_set.hpp"

#include <algorithm>
#include <numeric>

namespace uhpc::macro::distributed {

void ParticleSet::push_back(std::uint32_t global_id, const double* record) {
  id.push_back(global_id);
  values.insert(values.end(), record, record + width);
}

void ParticleSet::sort_by_id() {
  std::vector<std::size_t> order(size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [this](std::size_t a, std::size_t b) { return id[a] < id[b]; });
  ParticleSet sorted(width);
  sorted.id.reserve(size());
  sorted.values.reserve(values.size());
  for (std::size_t k : order) sorted.push_back(id[k], at(k));
  *this = std::move(sorted);
}

}  // namespace uhpc::macro::distributed
