#pragma once
// The material of a body: one law and the per-particle states it owns, held in a std::variant so the
// solver visits it once per particle loop and the loop body is a direct (inlinable) call, never a
// virtual one. A new law (the AFC concrete model) is one more alternative here; it needs the members
// every law has: State with a `stress` (Mat3, the stress the solver integrates), update(State&,
// MaterialStep), rotate(State&, R) (every objective tensor of the state), wave_speed(State,
// density_ratio), stress_free(State, density_ratio), reference_density(), moduli(State),
// effective_stress(State), stored_energy(State) and dissipation(State).
#include <cstddef>
#include <variant>
#include <vector>

#include "materials/afc.hpp"
#include "materials/elastic.hpp"
#include "materials/j2_plasticity.hpp"

namespace uhpc::macro {

template <class Law>
struct MaterialBlock {
  Law law;
  std::vector<typename Law::State> state;  // one per particle

  MaterialBlock(const Law& l, std::size_t n) : law(l), state(n) {}
};

using MaterialSet =
    std::variant<MaterialBlock<ElasticMaterial>, MaterialBlock<J2Material>, MaterialBlock<AfcMaterial>>;

template <class Law>
MaterialSet make_material_set(const Law& law, std::size_t n) {
  return MaterialSet(std::in_place_type<MaterialBlock<Law>>, law, n);
}

// The law of `set` with n fresh states (one rank's part of a body in a distributed run).
inline MaterialSet same_law(const MaterialSet& set, std::size_t n) {
  return std::visit([n](const auto& b) { return make_material_set(b.law, n); }, set);
}

inline double reference_density(const MaterialSet& set) {
  return std::visit([](const auto& b) { return b.law.reference_density(); }, set);
}

}  // namespace uhpc::macro
