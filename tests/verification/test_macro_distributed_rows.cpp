// The distributed solver's plan checked on the real RK rows and internal force (macro/distributed/,
// docs/cluster.md): each rank holds its particles and a halo of every particle K within a_K + 2 s + a_J
// of one of them, J (s the Verlet skin), builds every row over that set itself in ascending global ids, and then the
// internal force (nodal integration plus NSNI) on each of its particles equals the one-process force
// bit for bit, at any number of ranks, also after every particle has moved by up to half the skin since
// the halo was built. One row deep (reach a_K + s) is not enough: rows of ghosts that reach into the
// rank then miss nodes. (The skin's own share cannot be shown here: the reach maps' cells, of the
// largest support radius, add more slack than the skin; the unit test checks the halo against the
// exact criterion on fine cells.) Run by ctest under mpirun at 1-4 ranks, one thread a rank (the
// serial reference is itself one thread: the disc is below the solver's OpenMP threshold).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "bodies/generators.hpp"
#include "distributed/halo.hpp"
#include "distributed/particle_partition.hpp"
#include "distributed/particle_set.hpp"
#include "solver/internal_force.hpp"
#include "solver/particles.hpp"
#include "solver/shape_cache.hpp"

namespace {

using namespace uhpc::macro;
using namespace uhpc::macro::distributed;

constexpr int kStress = 5, kGrad = 14, kWidth = 41;  // x (3), support, volume, stress (9), its gradient (27)

// A graded disc as the shipped one is made (finer core, coarser rim), scaled down, with a smooth
// stress field and its gradient at every particle.
struct Body {
  Particles p;
  std::vector<double> stress, stress_grad;
};

Body make_body() {
  DiscSpec spec;
  spec.radius_m = 0.036;
  spec.thickness_m = 0.012;
  spec.h_axis_m = 0.003;
  spec.h_rim_m = 0.0045;
  spec.core_radius_m = 0.012;
  Body b{Particles::from_body(disc_body(spec), 2400.0, 2.5), {}, {}};
  b.stress.resize(9 * b.p.n);
  b.stress_grad.resize(27 * b.p.n);
  for (std::size_t i = 0; i < b.p.n; ++i) {
    const double* x = b.p.x.data() + 3 * i;
    for (int m = 0; m < 9; ++m) b.stress[9 * i + m] = 1e6 * std::sin(40.0 * x[m % 3] + m) * std::cos(25.0 * x[(m + 1) % 3]);
    for (int m = 0; m < 27; ++m) b.stress_grad[27 * i + m] = 1e8 * std::cos(30.0 * x[m % 3] - m);
  }
  return b;
}

constexpr double kSkin = 0.2;  // the solver's default neighbour_skin, a fraction of the smallest support

// Every particle moved by less than half the skin s = kSkin a_min, the most a halo built before the
// move must stand (a halo is rebuilt when some particle has moved that far: the Verlet rule).
void move(std::uint32_t id, double s, double* x) {
  for (int d = 0; d < 3; ++d) x[d] += 0.28 * s * std::sin(1.7 * id + 2.1 * d);  // |dx| <= 0.28 sqrt(3) s < s / 2
}

std::vector<double> serial_force(const Body& b) {
  ShapeCache shapes;
  shapes.skin = kSkin;
  const SecondGradientOptions second;
  shapes.rebuild(uhpc::rk::Options{}, b.p.x.data(), b.p.support.data(), b.p.n, &second);
  std::vector<double> f(3 * b.p.n);
  InternalForce force;
  force.compute(shapes, b.stress.data(), nullptr, b.p.volume.data(), b.p.n, f.data(), b.stress_grad.data());
  return f;
}

ParticleSet records_on_rank_zero(const Body& b, int rank) {
  ParticleSet s(kWidth);
  if (rank != 0) return s;
  for (std::size_t i = 0; i < b.p.n; ++i) {
    double r[kWidth];
    std::copy(b.p.x.data() + 3 * i, b.p.x.data() + 3 * i + 3, r);
    r[3] = b.p.support[i];
    r[4] = b.p.volume[i];
    std::copy(b.stress.data() + 9 * i, b.stress.data() + 9 * i + 9, r + kStress);
    std::copy(b.stress_grad.data() + 27 * i, b.stress_grad.data() + 27 * i + 27, r + kGrad);
    s.push_back(static_cast<std::uint32_t>(i), r);
  }
  return s;
}

// The owned particles' forces from rows built over owned + ghosts, in ascending global ids. Returns
// how many owned particles' forces differ from the serial ones in any bit.
std::size_t owned_force_mismatches(const ParticleSet& owned, const Halo& halo, const std::vector<double>& serial) {
  std::vector<std::size_t> owned_at;  // local index of each owned particle
  const ParticleSet local = halo.local(owned, &owned_at);
  const std::size_t n = local.size();
  std::vector<double> x(3 * n), support(n), volume(n), stress(9 * n), stress_grad(27 * n), f(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const double* r = local.at(i);
    std::copy(r, r + 3, x.data() + 3 * i);
    support[i] = r[3];
    volume[i] = r[4];
    std::copy(r + kStress, r + kStress + 9, stress.data() + 9 * i);
    std::copy(r + kGrad, r + kGrad + 27, stress_grad.data() + 27 * i);
  }
  ShapeCache shapes;
  shapes.skin = kSkin;
  const SecondGradientOptions second;
  shapes.rebuild(uhpc::rk::Options{}, x.data(), support.data(), n, &second);
  InternalForce force;
  force.compute(shapes, stress.data(), nullptr, volume.data(), n, f.data(), stress_grad.data());
  std::size_t mismatches = 0;
  for (std::size_t k = 0; k < owned.size(); ++k) {
    const std::size_t i = owned_at[k], gid = owned.id[k];
    bool same = true;
    for (int d = 0; d < 3; ++d) same = same && f[3 * i + d] == serial[3 * gid + d];
    mismatches += same ? 0 : 1;
  }
  return mismatches;
}

TEST(MacroDistributedRows, TwoRowsOfHaloGiveTheSerialForceBitForBitAfterAMoveOneRowDoesNot) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  Body body = make_body();
  ParticleSet owned = records_on_rank_zero(body, rank);
  ParticlePartition partition(MPI_COMM_WORLD);
  partition.balance(owned);

  // Halos built where the particles are now.
  const double a_min = *std::min_element(body.p.support.begin(), body.p.support.end());
  const double a_max = *std::max_element(body.p.support.begin(), body.p.support.end());
  const double s = kSkin * a_min;
  std::vector<double> two_rows(owned.size()), one_row(owned.size()), row_reach(owned.size()), none(owned.size(), 0.0);
  for (std::size_t i = 0; i < owned.size(); ++i) {
    two_rows[i] = owned.at(i)[3] + 2.0 * s;
    one_row[i] = owned.at(i)[3] + s;
    row_reach[i] = owned.at(i)[3];
  }
  Halo deep(partition, owned, two_rows, row_reach, a_max), shallow(partition, owned, one_row, none, a_max);

  // Then every particle moves by less than s / 2, the ghosts learn where their owners went, and the
  // rows are built at the new positions, serially and on each rank.
  for (std::size_t i = 0; i < body.p.n; ++i) move(static_cast<std::uint32_t>(i), s, body.p.x.data() + 3 * i);
  for (std::size_t i = 0; i < owned.size(); ++i) move(owned.id[i], s, owned.at(i));
  deep.refresh(owned);
  shallow.refresh(owned);
  const std::vector<double> serial = serial_force(body);

  const unsigned long long counts[3] = {owned_force_mismatches(owned, deep, serial),
                                        owned_force_mismatches(owned, shallow, serial), owned.size()};
  unsigned long long total[3] = {0, 0, 0};
  MPI_Allreduce(counts, total, 3, MPI_UNSIGNED_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
  if (rank == 0)
    std::printf("%d ranks, %llu particles: forces differing from the serial ones: %llu with two rows of halo, "
                "%llu with one\n", ranks, total[2], total[0], total[1]);
  EXPECT_EQ(total[2], body.p.n);
  EXPECT_EQ(total[0], 0u);
  if (ranks > 1) {
    EXPECT_GT(total[1], 0u);  // the test can tell a halo that is too shallow
  }
}

}  // namespace
