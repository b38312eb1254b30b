// The distributed step (macro/distributed/distributed_run.hpp) against the one-process solver: a small
// graded disc of the AFC law with the SDEL and NSNI, held by the frame of the shipped case, struck in
// two ways: its core thrown at t = 0 (300 m/s into the disc and 180 m/s across it, over a radius of 8
// mm), which carries particles across the ranks' regions, and the shipped case's sphere at 817 m/s,
// whose kinematic contact is solved over every rank's candidates. After every step the owners
// refresh their ghosts; every skin of motion the particles migrate and the halo and the rank's
// solvers are made again from the records. After the run, every particle's evolving fields and
// material state, the time and the step equal the one-process run's bit for bit, at 1-4 ranks, one
// thread a rank; the energy books, which each rank sums over its own particles before the ranks' sums
// are added, agree to 1e-12 relative. Run by ctest under mpirun.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <mpi.h>

#include "case_config.hpp"
#include "case_setup.hpp"
#include "distributed/distributed_run.hpp"
#include "distributed/gather.hpp"
#include "material_factory.hpp"
#include "uhpc/config.hpp"

namespace {

using namespace uhpc;
using namespace uhpc::macro;
using namespace uhpc::macro::distributed;

constexpr int kSteps = 160;

// The coarse case's law, solver and frame on a disc small enough for ctest, with every row rebuilt each
// step or with lazy rows (SmallDisc's reuse).
enum class Strike { Core, Sphere };

struct SmallDisc {
  Strike strike;
  Config cfg = Config::load(std::string(UHPC_DATA_DIR) + "/macro_disc_afc_coarse.json", {});
  CaseSettings settings;
  ParticleBody body;
  MaterialSet law;

  // reuse: solver.shape_reuse_tolerance (0: every row rebuilt each step; the shipped cases' 3e-4: lazy rows).
  explicit SmallDisc(Strike how, double reuse = 0.0)
      : strike(how), settings(read_case(cfg)), law(make_material(cfg.section("material"), 0, std::nullopt).set) {
    settings.target.disc.radius_m = 0.036;
    settings.target.disc.thickness_m = 0.012;
    settings.target.disc.h_axis_m = 0.003;
    settings.target.disc.h_rim_m = 0.0045;
    settings.target.disc.core_radius_m = 0.012;
    settings.support.rim_width_m = 0.006;
    settings.solver.shape_reuse_tolerance = reuse;
    if (strike == Strike::Core) {  // the sphere waits at rest, 10 mm off the entry face
      settings.projectile.velocity_m_s = 0.0;
      settings.projectile.initial_gap_m = 0.01;
    }
    body = make_target_body(settings.target);
  }

  // The solver over the body's particles `ids`, as the whole body's solver would start them.
  ExplicitSolver solver(const std::vector<std::uint32_t>& ids) const {
    ExplicitSolver s = make_part_solver(settings, body, law, ids);
    if (strike == Strike::Core)
      set_initial_velocity(s.particles(), [](const double* x) {
        return std::hypot(x[0], x[1]) < 0.008 ? Vec3{150.0, 100.0, 300.0} : Vec3{0.0, 0.0, 0.0};
      });
    return s;
  }

  std::size_t size() const { return body.size(); }
};

std::vector<std::uint32_t> all_ids(std::size_t n) {
  std::vector<std::uint32_t> ids(n);
  for (std::size_t i = 0; i < n; ++i) ids[i] = static_cast<std::uint32_t>(i);
  return ids;
}

// Each particle's rank now, on rank 0 (sorted by id; empty elsewhere).
std::vector<int> owners(DistributedRun& run, int rank) {
  const ParticleSet& records = run.owned_records();
  ParticleSet mine(4);
  for (std::size_t k = 0; k < records.size(); ++k) {
    const double r[4] = {records.at(k)[0], records.at(k)[1], records.at(k)[2], static_cast<double>(rank)};
    mine.push_back(records.id[k], r);
  }
  const ParticleSet all = gather(mine, MPI_COMM_WORLD, 0);
  std::vector<int> out;
  for (std::size_t i = 0; i < all.size(); ++i) out.push_back(static_cast<int>(all.at(i)[3]));
  return out;
}

double settings_velocity(const SmallDisc& disc) { return disc.settings.projectile.velocity_m_s; }

double relative(double a, double b) { return a == b ? 0.0 : std::fabs(a - b) / std::max(std::fabs(a), std::fabs(b)); }

// Steps the disc at this many ranks and at one process, and compares (rank 0).
void expect_the_one_process_run(Strike strike, double reuse = 0.0) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  const SmallDisc disc(strike, reuse);
  DistributedRun run(MPI_COMM_WORLD, disc.size(), [&](const std::vector<std::uint32_t>& ids) { return disc.solver(ids); });
  const std::vector<int> first_owners = owners(run, rank);
  int failed_at = 0;
  std::int64_t most_in_contact = 0;
  for (int k = 1; k <= kSteps && failed_at == 0; ++k) {
    if (!run.step()) failed_at = k;
    if (strike == Strike::Sphere) most_in_contact = std::max(most_in_contact, run.solver().contact().particles_in_contact);
  }
  ASSERT_EQ(failed_at, 0) << "the distributed run failed a step";
  const std::vector<int> last_owners = owners(run, rank);
  const ParticleSet all = gather(run.owned_records(), MPI_COMM_WORLD, 0);
  // The halo was made again as the particles moved, and (at 2 or more ranks) particles changed ranks.
  EXPECT_GE(run.halo_builds(), 4u);
  if (rank != 0) return;
  std::size_t migrated = 0;
  for (std::size_t i = 0; i < first_owners.size(); ++i) migrated += first_owners[i] != last_owners[i];
  if (size > 1) {
    EXPECT_GT(migrated, 0u) << "no particle changed ranks";
  }

  ExplicitSolver serial = disc.solver(all_ids(disc.size()));
  serial.initialize();
  for (int k = 1; k <= kSteps; ++k) ASSERT_TRUE(serial.step()) << "the one-process run failed step " << k;
  if (reuse > 0.0) {
    const double kept = static_cast<double>(serial.shapes().rows_kept);
    EXPECT_GT(kept, 0.2 * (kept + static_cast<double>(serial.shapes().rows_built))) << "too few rows kept to try lazy rows";
    EXPECT_GE(serial.shapes().layouts, 2u) << "no new slot layout after the first";
  }

  ASSERT_EQ(all.size(), disc.size());
  const std::size_t width = serial.particle_record_width();
  std::vector<double> expected(width);
  std::size_t differ = 0;
  double moved = 0.0;
  for (std::size_t i = 0; i < all.size(); ++i) {
    ASSERT_EQ(all.id[i], i);
    serial.write_particle(i, expected.data());
    if (std::memcmp(expected.data(), all.at(i), width * sizeof(double)) != 0) ++differ;
    moved = std::max(moved, std::fabs(all.at(i)[2] - disc.body.position[3 * i + 2]));
  }
  EXPECT_EQ(differ, 0u) << "particles whose state differs from the one-process run's, of " << all.size();
  EXPECT_GT(moved, 2.0 * run.skin()) << "the struck disc moved too little to carry particles across the regions";
  EXPECT_EQ(run.solver().time(), serial.time());
  EXPECT_EQ(run.solver().steps(), serial.steps());
  EXPECT_EQ(run.solver().dt(), serial.dt());
  const EnergyLedger &a = run.solver().ledger(), &b = serial.ledger();
  for (const auto& [name, x, y] : {std::tuple{"kinetic", a.kinetic, b.kinetic}, std::tuple{"internal", a.internal, b.internal},
                                   std::tuple{"viscous", a.viscous, b.viscous}, std::tuple{"external", a.external, b.external},
                                   std::tuple{"stored", a.material_stored, b.material_stored},
                                   std::tuple{"opening", a.opening, b.opening}, std::tuple{"plastic", a.plastic, b.plastic},
                                   std::tuple{"stabilization", a.stabilization, b.stabilization},
                                   std::tuple{"momentum z", a.momentum[2], b.momentum[2]}})
    EXPECT_LE(relative(x, y), 1e-12) << name << ": " << x << " against " << y;
  if (strike == Strike::Sphere) {
    const RigidSphere &mine = run.solver().sphere(), &one = serial.sphere();
    EXPECT_TRUE(std::memcmp(&mine.x, &one.x, sizeof mine.x) == 0 && std::memcmp(&mine.v, &one.v, sizeof mine.v) == 0 &&
                std::memcmp(&mine.force, &one.force, sizeof mine.force) == 0)
        << "the sphere differs: v_z " << mine.v[2] << " against " << one.v[2];
    EXPECT_GE(most_in_contact, 4) << "the contact's active set was never shared";
    EXPECT_LT(one.v[2], 0.99 * settings_velocity(disc)) << "the sphere has not struck yet";
    EXPECT_LE(relative(a.contact, b.contact), 1e-12) << "contact: " << a.contact << " against " << b.contact;
  }
  std::printf("%d ranks%s: %zu particles, %zu halo builds, %zu balances, %zu changed ranks, largest axial motion %.2f mm, "
              "kinetic %.6g J, opening %.6g J; one process: %zu rows built, %zu kept, %zu layouts\n",
              size, reuse > 0.0 ? " (lazy rows)" : "", all.size(), run.halo_builds(), run.balances(), migrated, 1e3 * moved,
              a.kinetic, a.opening, serial.shapes().rows_built, serial.shapes().rows_kept, serial.shapes().layouts);
}

// A particle whose velocity is not finite fails the first step on its rank: every rank must give the
// step up with the same failure as one process (none may repeat it while another stops).
TEST(MacroDistributedStep, AFailureOnOneRankIsTheSameFailureOnEvery) {
  const SmallDisc disc(Strike::Core);
  const std::uint32_t broken = 517;
  const auto factory = [&](const std::vector<std::uint32_t>& ids) {
    ExplicitSolver s = disc.solver(ids);
    for (std::size_t i = 0; i < ids.size(); ++i)
      if (ids[i] == broken) s.particles().v[3 * i] = std::nan("");
    return s;
  };
  ExplicitSolver one = factory(all_ids(disc.size()));
  one.initialize();
  ASSERT_FALSE(one.step());
  DistributedRun run(MPI_COMM_WORLD, disc.size(), factory);
  EXPECT_FALSE(run.step());
  EXPECT_EQ(run.solver().failure().kind, one.failure().kind) << to_string(run.solver().failure().kind);
  EXPECT_NE(one.failure().kind, StepFailure::None);
  EXPECT_EQ(run.solver().time(), 0.0);
  // The owner names the particle by its global id, as one process does.
  const auto owner = std::find(run.local_ids().begin(), run.local_ids().end(), broken);
  if (owner != run.local_ids().end() && run.owned()[static_cast<std::size_t>(owner - run.local_ids().begin())]) {
    EXPECT_EQ(run.solver().failure().particle, static_cast<std::int64_t>(broken));
    EXPECT_EQ(one.failure().particle, static_cast<std::int64_t>(broken));
  }
}

TEST(MacroDistributedStep, AThrownCoreEqualsTheOneProcessRunBitForBit) { expect_the_one_process_run(Strike::Core); }

TEST(MacroDistributedStep, TheSphereEqualsTheOneProcessRunBitForBit) { expect_the_one_process_run(Strike::Sphere); }

// The same with lazy rows (the shipped tolerance): the rows kept by their owners travel with the
// particles at every halo build, so they are the one-process rows whatever rank holds them.
constexpr double kShippedReuse = 3e-4;

TEST(MacroDistributedStep, AThrownCoreWithLazyRowsEqualsTheOneProcessRunBitForBit) {
  expect_the_one_process_run(Strike::Core, kShippedReuse);
}

TEST(MacroDistributedStep, TheSphereWithLazyRowsEqualsTheOneProcessRunBitForBit) {
  expect_the_one_process_run(Strike::Sphere, kShippedReuse);
}

}  // namespace
