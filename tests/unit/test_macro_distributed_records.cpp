// A solver's particles as records (macro/distributed/particle_records.hpp), run by ctest under mpirun at
// 1-3 ranks: the coarse AFC disc stepped until the sphere is in it, its checkpoint turned into records,
// partitioned over the ranks by Zoltan and gathered back, gives the same checkpoint bit for bit, on each
// rank for its own particles and for the whole body; a solver resumed from the gathered copy goes on
// exactly as one resumed from the original.
#include <gtest/gtest.h>

#include <numeric>
#include <vector>

#include "coarse_disc_solver.hpp"
#include "distributed/gather.hpp"
#include "distributed/particle_partition.hpp"
#include "distributed/particle_records.hpp"

namespace {

using namespace uhpc::macro;
using namespace uhpc::macro::distributed;

using uhpc::test::coarse_disc_solver;
using uhpc::test::same_bits;

// c's fields and states of the particles `ids`, as one-particle slices in that order.
SolverCheckpoint slice(const SolverCheckpoint& c, const RecordLayout& layout, std::size_t n, const std::vector<std::uint32_t>& ids) {
  SolverCheckpoint s;
  for (const auto& [name, values] : c.particle_fields) {
    const std::size_t w = values.size() / n;
    std::vector<double> part;
    for (std::uint32_t i : ids) part.insert(part.end(), values.begin() + w * i, values.begin() + w * (i + 1));
    s.particle_fields.emplace_back(name, std::move(part));
  }
  for (std::uint32_t i : ids)
    s.material_states.insert(s.material_states.end(), c.material_states.begin() + layout.state_bytes * i,
                             c.material_states.begin() + layout.state_bytes * (i + 1));
  return s;
}

// The same fields (by name: records put x first), states and constants, bit for bit.
void expect_same(const SolverCheckpoint& a, const SolverCheckpoint& b) {
  ASSERT_EQ(a.particle_fields.size(), b.particle_fields.size());
  for (const auto& [name, values] : a.particle_fields) {
    const auto it = std::find_if(b.particle_fields.begin(), b.particle_fields.end(), [&](const auto& f) { return f.first == name; });
    ASSERT_NE(it, b.particle_fields.end()) << name;
    EXPECT_TRUE(same_bits(values, it->second)) << name;
  }
  EXPECT_TRUE(same_bits(a.material_states, b.material_states));
}

TEST(MacroDistributedRecords, ASolversParticlesTravelAndComeBackBitForBit) {
  ExplicitSolver a = coarse_disc_solver();
  a.initialize();
  for (int k = 0; k < 30; ++k) ASSERT_TRUE(a.step());
  const SolverCheckpoint c = a.checkpoint();
  const Particles& p = a.particles();
  const RecordLayout layout = record_layout(c, p.n);
  EXPECT_EQ(layout.fields.front(), "x");

  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  std::vector<std::uint32_t> all(p.n);
  std::iota(all.begin(), all.end(), 0u);
  ParticleSet owned = to_records(layout, c, p, rank == 0 ? all : std::vector<std::uint32_t>{});
  ParticlePartition partition(MPI_COMM_WORLD);
  partition.balance(owned);

  // Each rank's own particles, unpacked: the original's, bit for bit.
  SolverCheckpoint mine;
  Particles mine_constants;
  from_records(layout, owned, mine, mine_constants);
  expect_same(slice(c, layout, p.n, owned.id), mine);
  for (std::size_t k = 0; k < owned.size(); ++k) {
    EXPECT_EQ(mine_constants.mass[k], p.mass[owned.id[k]]);
    EXPECT_EQ(mine_constants.support[k], p.support[owned.id[k]]);
  }

  // Gathered back: the whole checkpoint, and a solver resumed from it goes on as from the original.
  SolverCheckpoint back = c;
  Particles back_constants;
  from_records(layout, gather(owned, MPI_COMM_WORLD), back, back_constants);
  expect_same(c, back);
  EXPECT_TRUE(same_bits(back_constants.volume0, p.volume0));
  EXPECT_TRUE(same_bits(back_constants.spacing, p.spacing));
  ExplicitSolver from_original = coarse_disc_solver(), from_records_back = coarse_disc_solver();
  from_original.initialize();
  from_records_back.initialize();
  from_original.resume(c);
  from_records_back.resume(back);
  for (int k = 0; k < 10; ++k) {
    ASSERT_TRUE(from_original.step());
    ASSERT_TRUE(from_records_back.step());
  }
  EXPECT_TRUE(same_bits(from_original.particles().x, from_records_back.particles().x));
  EXPECT_TRUE(same_bits(from_original.particles().stress, from_records_back.particles().stress));
}

}  // namespace
