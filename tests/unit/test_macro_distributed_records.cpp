// A solver's particles as records (macro/distributed/particle_records.hpp), run by ctest under mpirun at
// 1-3 ranks: the coarse AFC disc stepped until the sphere is in it, its checkpoint turned into records,
// partitioned over the ranks by Zoltan and gathered back, gives the same checkpoint bit for bit, on each
// rank for its own particles and for the whole body; a solver resumed from the gathered copy goes on
// exactly as one resumed from the original.
#include <gtest/gtest.h>

#include <cstring>
#include <numeric>
#include <string>
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
  const std::vector<std::uint32_t> none;
  ParticleSet owned = to_records(layout, c, p, rank == 0 ? all : none, rank == 0 ? all : none);
  ParticlePartition partition(MPI_COMM_WORLD);
  partition.balance(owned);

  // Each rank's own particles, unpacked: the original's, bit for bit.
  SolverCheckpoint mine;
  Particles mine_constants;
  from_records(layout, owned, mine, mine_constants);
  expect_same(slice(c, layout, p.n, owned.id), mine);
  for (std::size_t k = 0; k < owned.size(); ++k) {
    const std::uint32_t i = owned.id[k];
    EXPECT_TRUE(std::memcmp(owned.at(k), c.particle_fields.front().second.data() + 3 * i, 3 * sizeof(double)) == 0)
        << "the record starts with the position";
    for (auto constant : {&Particles::mass, &Particles::volume0, &Particles::spacing, &Particles::support})
      EXPECT_TRUE(std::memcmp(&(mine_constants.*constant)[k], &(p.*constant)[i], sizeof(double)) == 0);
  }

  // Gathered back: the whole checkpoint, and a solver resumed from it goes on as from the original.
  // (The step state's per-particle forces come from the records too, not from the original.)
  SolverCheckpoint back;
  back.state = c.state;
  back.state.f_ext_old.clear();
  back.state.f_contact_old.clear();
  back.counters = c.counters;
  Particles back_constants;
  from_records(layout, gather(owned, MPI_COMM_WORLD), back, back_constants);
  expect_same(c, back);
  EXPECT_TRUE(same_bits(back.state.f_ext_old, c.state.f_ext_old));
  EXPECT_TRUE(same_bits(back.state.f_contact_old, c.state.f_contact_old));
  for (auto constant : {&Particles::mass, &Particles::volume0, &Particles::spacing, &Particles::support})
    EXPECT_TRUE(same_bits(back_constants.*constant, p.*constant));
  ExplicitSolver from_original = coarse_disc_solver(), from_records_back = coarse_disc_solver();
  from_original.initialize();
  from_records_back.initialize();
  from_original.resume(c);
  from_records_back.resume(back);
  for (int k = 0; k < 10; ++k) {
    ASSERT_TRUE(from_original.step());
    ASSERT_TRUE(from_records_back.step());
  }
  const SolverCheckpoint end_original = from_original.checkpoint(), end_back = from_records_back.checkpoint();
  expect_same(end_original, end_back);
}

// Records of a few particles taken out of order, with a material state that is not a whole number of
// doubles and a field of no width: every value comes back where it was, the global ids named.
TEST(MacroDistributedRecords, AnyRowsAnyIdsAndStatesOfAnyByteCount) {
  constexpr std::size_t n = 3, bytes = 5;
  SolverCheckpoint c;
  c.particle_fields = {{"q", {1.5, 2.5, 3.5}}, {"x", {0, 1, 2, 3, 4, 5, 6, 7, 8}}, {"none", {}},
                       {"f_ext", {9, 8, 7, 6, 5, 4, 3, 2, 1}}, {"f_contact", {-1, -2, -3, -4, -5, -6, -7, -8, -9}}};
  for (std::size_t k = 0; k < n * bytes; ++k) c.material_states.push_back(static_cast<std::uint8_t>(200 + k));
  Particles p;
  p.n = n;
  p.mass = {1, 2, 3};
  p.volume0 = {4, 5, 6};
  p.spacing = {7, 8, 9};
  p.support = {10, 11, 12};
  const RecordLayout layout = record_layout(c, n);
  EXPECT_EQ(layout.fields, (std::vector<std::string>{"x", "q", "none", "f_ext", "f_contact"}));
  EXPECT_EQ(layout.width, 3 + 1 + 0 + 3 + 3 + 4 + 1);  // a 5-byte state takes one double
  const ParticleSet records = to_records(layout, c, p, {2, 0}, {70, 30});
  EXPECT_EQ(records.id, (std::vector<std::uint32_t>{70, 30}));
  EXPECT_EQ(records.at(0)[0], 6.0);  // the position first
  SolverCheckpoint back;
  Particles constants;
  from_records(layout, records, back, constants);
  EXPECT_EQ(constants.n, 2u);
  EXPECT_EQ(constants.mass, (std::vector<double>{3, 1}));
  EXPECT_EQ(constants.support, (std::vector<double>{12, 10}));
  const auto field = [&back](const std::string& name) {
    for (const auto& f : back.particle_fields)
      if (f.first == name) return f.second;
    ADD_FAILURE() << "no field " << name;
    return std::vector<double>{};
  };
  EXPECT_EQ(field("x"), (std::vector<double>{6, 7, 8, 0, 1, 2}));
  EXPECT_EQ(field("q"), (std::vector<double>{3.5, 1.5}));
  EXPECT_TRUE(field("none").empty());
  EXPECT_EQ(back.state.f_ext_old, (std::vector<double>{3, 2, 1, 9, 8, 7}));
  EXPECT_EQ(back.state.f_contact_old, (std::vector<double>{-7, -8, -9, -1, -2, -3}));
  EXPECT_EQ(back.material_states, (std::vector<std::uint8_t>{210, 211, 212, 213, 214, 200, 201, 202, 203, 204}));
}

}  // namespace
