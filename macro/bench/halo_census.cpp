// uhpc_halo_census: what the distributed layer's owner-computes plan costs on a real case, before the
// solver uses it. Under mpirun -np N: the case's target body partitioned by Zoltan RCB, its two-row halo
// (halo.hpp) built and refreshed, and per rank the owned and ghost particles (the ghosts
// are the redundant rows and the extra memory of owner computes; beside them what a one-row halo,
// enough for partial sums sent back to the owners, would hold) and the wall times (the largest rank's;
// refresh: one exchange of the records, x and a; rows + force: every row of the rank's particles and
// ghosts built and the internal force summed, the work of a step that rebuilds every row). Prints one
// table row on rank 0; reach maps of cells of the largest support radius.
//   mpirun -np 4 build/macro/uhpc_halo_census data/macro_disc_afc.json [key=value ...]   (the case's --set)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "case_config.hpp"
#include "case_setup.hpp"
#include "distributed/halo.hpp"
#include "distributed/mpi_session.hpp"
#include "distributed/particle_partition.hpp"
#include "mpi_timing.hpp"
#include "solver/internal_force.hpp"
#include "solver/particles.hpp"
#include "solver/shape_cache.hpp"
#include "uhpc/config.hpp"

using namespace uhpc::macro;
using namespace uhpc::macro::distributed;
using namespace uhpc::macro::bench;

int main(int argc, char** argv) {
  MpiSession mpi(&argc, &argv);
  if (argc < 2) {
    if (mpi.rank() == 0) std::fprintf(stderr, "usage: uhpc_halo_census CASE.json [key=value ...] (under mpirun -np N)\n");
    return 2;
  }
  try {
    const CaseSettings s = read_case(uhpc::Config::load(argv[1], std::vector<std::string>(argv + 2, argv + argc)));
    // Every rank reads the case; rank 0 alone makes the body, as a run would, and tells the others its
    // smallest and largest support radius.
    ParticleSet owned(4);  // x, support radius
    double radii[2] = {0.0, 0.0};
    if (mpi.rank() == 0) {
      const Particles p = Particles::from_body(make_target_body(s.target), 2400.0, s.solver.support_factor);
      radii[0] = *std::min_element(p.support.begin(), p.support.end());
      radii[1] = *std::max_element(p.support.begin(), p.support.end());
      for (std::size_t i = 0; i < p.n; ++i) {
        const double r[4] = {p.x[3 * i], p.x[3 * i + 1], p.x[3 * i + 2], p.support[i]};
        owned.push_back(static_cast<std::uint32_t>(i), r);
      }
    }
    MPI_Bcast(radii, 2, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    const double a_min = radii[0], a_max = radii[1];
    const double skin = s.solver.neighbour_skin * a_min;
    MPI_Barrier(MPI_COMM_WORLD);
    auto t0 = std::chrono::steady_clock::now();
    ParticlePartition partition(MPI_COMM_WORLD);
    partition.balance(owned);
    const double t_balance = max_over_ranks(seconds_since(t0));
    std::vector<double> node_reach(owned.size()), row_reach(owned.size());
    for (std::size_t i = 0; i < owned.size(); ++i) {
      node_reach[i] = owned.at(i)[3] + 2.0 * skin;
      row_reach[i] = owned.at(i)[3];
    }
    MPI_Barrier(MPI_COMM_WORLD);
    t0 = std::chrono::steady_clock::now();
    Halo halo(partition, owned, node_reach, row_reach, a_max);
    const double t_halo = max_over_ranks(seconds_since(t0));
    MPI_Barrier(MPI_COMM_WORLD);
    t0 = std::chrono::steady_clock::now();
    constexpr int kRefreshes = 20;
    for (int k = 0; k < kRefreshes; ++k) halo.refresh(owned);
    const double t_refresh = max_over_ranks(seconds_since(t0)) / kRefreshes;

    // What a one-row halo (nodes covering a rank's points, as partial sums sent back would need) holds.
    std::vector<double> one_row(owned.size()), none(owned.size(), 0.0);
    for (std::size_t i = 0; i < owned.size(); ++i) one_row[i] = owned.at(i)[3] + skin;
    const Halo shallow(partition, owned, one_row, none, a_max);
    const double one_row_ghosts = sum_over_ranks(static_cast<double>(shallow.ghosts().size()));

    // The work the halo buys: every row over owned + ghosts built (NSNI second gradients, the case's
    // skin) and the internal force of a uniform stress, timed on the busiest rank. Against one rank on
    // as many OpenMP threads this is item 5's "ranks x 1 thread against 1 rank x threads".
    const ParticleSet local = halo.local(owned);
    const std::size_t held = local.size();
    std::vector<double> x(3 * held), support(held), volume(held), stress(9 * held), stress_grad(27 * held, 0.0), f(3 * held);
    for (std::size_t i = 0; i < held; ++i) {
      const double* r = local.at(i);
      std::copy(r, r + 3, x.data() + 3 * i);
      support[i] = r[3];
      const double h = r[3] / s.solver.support_factor;
      volume[i] = h * h * h;
      for (int m = 0; m < 9; ++m) stress[9 * i + m] = (m % 4 == 0) ? -1e7 : 2e6;
    }
    ShapeCache shapes;
    shapes.skin = s.solver.neighbour_skin;
    shapes.keep_psi = false;
    const SecondGradientOptions second;
    InternalForce force;
    MPI_Barrier(MPI_COMM_WORLD);
    t0 = std::chrono::steady_clock::now();
    shapes.rebuild(s.solver.rk, x.data(), support.data(), held, &second);
    force.compute(shapes, stress.data(), nullptr, volume.data(), held, f.data(), stress_grad.data());
    const double t_rows = max_over_ranks(seconds_since(t0));

    const double n_owned = static_cast<double>(owned.size()), n_ghost = static_cast<double>(halo.ghosts().size());
    const double total = sum_over_ranks(n_owned), ghosts = sum_over_ranks(n_ghost);
    const double most_owned = max_over_ranks(n_owned), most_held = max_over_ranks(n_owned + n_ghost);
    const double worst_ratio = max_over_ranks(n_owned > 0 ? (n_owned + n_ghost) / n_owned : 0.0);
    if (mpi.rank() == 0) {
      std::printf("| ranks | particles | largest rank owns | ghosts / owned, all ranks | one-row halo's | "
                  "largest rank holds | worst held / owned | balance s | halo s | refresh s | rows + force s |\n"
                  "|---|---|---|---|---|---|---|---|---|---|---|\n");
      std::printf("| %d | %.0f | %.0f | %.3f | %.3f | %.0f | %.3f | %.3f | %.3f | %.4f | %.3f |\n", mpi.size(), total,
                  most_owned, ghosts / total, one_row_ghosts / total, most_held, worst_ratio, t_balance, t_halo,
                  t_refresh, t_rows);
      std::printf("(a_min %.3g m, a_max %.3g m, skin %.3g m; ghosts: K within a_K + 2 skin + a_J of an owned J)\n", a_min, a_max, skin);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "uhpc_halo_census: %s\n", e.what());
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  return 0;
}
