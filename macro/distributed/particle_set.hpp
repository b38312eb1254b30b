#pragma once
// The particles one rank holds, as fixed-width records: a global id (the particle's index in the whole
// body, which also orders them) and `width` doubles, the first three its position. What the records
// carry beyond the position is the caller's: the partition and the halo move whole records.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace uhpc::macro::distributed {

struct ParticleSet {
  explicit ParticleSet(int width_ = 3) : width(width_) {}
  int width;                      // doubles a particle (>= 3: the position comes first)
  std::vector<std::uint32_t> id;  // global ids
  std::vector<double> values;     // width per particle, in the order of id

  std::size_t size() const { return id.size(); }
  const double* at(std::size_t i) const { return values.data() + static_cast<std::size_t>(width) * i; }
  double* at(std::size_t i) { return values.data() + static_cast<std::size_t>(width) * i; }
  void push_back(std::uint32_t global_id, const double* record);
  // Ascending ids: the serial body's order, whatever the order particles arrived in.
  void sort_by_id();
};

}  // namespace uhpc::macro::distributed
