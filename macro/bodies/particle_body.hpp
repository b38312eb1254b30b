#pragma once
// A body discretized into particles: positions, the volume each particle carries (its share of the
// body; they sum to the body's volume) and its nodal spacing h_I (the cube root of that volume, the
// length that sets a particle's support radius and its SDEL length scale lambda = h_I / l_mac).
#include <cstddef>
#include <vector>

namespace uhpc::macro {

struct ParticleBody {
  std::vector<double> position;  // 3 per particle, m
  std::vector<double> volume;    // m^3
  std::vector<double> spacing;   // m

  std::size_t size() const { return volume.size(); }
  void add(double x, double y, double z, double v);  // spacing = cbrt(v)
  double total_volume() const;
};

}  // namespace uhpc::macro
