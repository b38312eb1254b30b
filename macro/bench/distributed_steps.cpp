// uhpc_distributed_steps: the distributed step (distributed/distributed_run.hpp) on a real case, with its
// costs. Under mpirun -np N: the case's first `steps` steps over the ranks, with the case's RK rows
// (the shipped lazy rows; solver.shape_reuse_tolerance=0 rebuilds every row each step). Prints on rank 0 the particles, the largest rank's ghosts, the halo builds (each a migration,
// a new halo and new rank solvers made from the particles' records), and the wall times of the steps
// and of the halo builds within them. serial=1: rank 0 then runs the same steps in one process, reports
// its time and compares the sphere's state and every particle's record bit for bit (one thread a rank
// gives the same bits).
//   mpirun -np 2 build/macro/uhpc_distributed_steps data/macro_disc_afc_coarse.json steps=200 serial=1 [key=value ...]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

#include "case_config.hpp"
#include "case_setup.hpp"
#include "distributed/distributed_run.hpp"
#include "distributed/gather.hpp"
#include "distributed/mpi_session.hpp"
#include "material_factory.hpp"
#include "mpi_timing.hpp"
#include "uhpc/config.hpp"

using namespace uhpc::macro;
using namespace uhpc::macro::distributed;
using namespace uhpc::macro::bench;

int main(int argc, char** argv) {
  MpiSession mpi(&argc, &argv);
  if (argc < 2) {
    if (mpi.rank() == 0)
      std::fprintf(stderr, "usage: uhpc_distributed_steps CASE.json [steps=N] [serial=1] [key=value ...] (under mpirun -np N)\n");
    return 2;
  }
  try {
    int steps = 200;
    bool serial = false;
    std::vector<std::string> overrides;
    for (int k = 2; k < argc; ++k) {
      const std::string a = argv[k];
      if (a.rfind("steps=", 0) == 0) steps = std::stoi(a.substr(6));
      else if (a.rfind("serial=", 0) == 0) serial = a.substr(7) == "1";
      else overrides.push_back(a);
    }
    const uhpc::Config cfg = uhpc::Config::load(argv[1], overrides);
    const CaseSettings s = read_case(cfg);
    const ParticleBody body = make_target_body(s.target);
    const MaterialSet law = make_material(cfg.section("material"), 0, std::nullopt).set;
    const auto factory = [&](const std::vector<std::uint32_t>& ids) { return make_part_solver(s, body, law, ids); };

    MPI_Barrier(MPI_COMM_WORLD);
    auto t0 = std::chrono::steady_clock::now();
    DistributedRun run(MPI_COMM_WORLD, body.size(), factory);
    const double t_setup = max_over_ranks(seconds_since(t0));
    std::size_t most_ghosts = 0;
    MPI_Barrier(MPI_COMM_WORLD);
    t0 = std::chrono::steady_clock::now();
    int done = 0;
    for (; done < steps; ++done) {
      if (!run.step()) break;
      std::size_t ghosts = 0;
      for (const std::uint8_t o : run.owned()) ghosts += o ? 0 : 1;
      most_ghosts = std::max(most_ghosts, ghosts);
    }
    const double t_steps = max_over_ranks(seconds_since(t0));
    const ParticleSet all = gather(run.owned_records(), MPI_COMM_WORLD, 0);
    double ghosts_max = max_over_ranks(static_cast<double>(most_ghosts));
    const double t_builds = max_over_ranks(run.halo_build_seconds());
    const double t_exchanges = max_over_ranks(run.row_exchange_seconds());
    if (mpi.rank() == 0) {
      std::printf("%d ranks, %zu particles, %d steps%s: setup %.2f s, steps %.2f s (%.2f ms a step), %zu halo builds (%.2f s), "
                  "%zu row exchanges (%.2f s), most ghosts on a rank %.0f, sphere v_z %.6f m/s\n",
                  mpi.size(), body.size(), done, done < steps ? " (a step failed)" : "", t_setup, t_steps,
                  1e3 * t_steps / std::max(done, 1), run.halo_builds(), t_builds, run.row_exchanges(), t_exchanges,
                  ghosts_max, run.solver().sphere().v[2]);
      if (serial) {
        t0 = std::chrono::steady_clock::now();
        std::vector<std::uint32_t> ids(body.size());
        for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = static_cast<std::uint32_t>(i);
        ExplicitSolver one = factory(ids);
        one.initialize();
        for (int k = 0; k < done; ++k)
          if (!one.step()) throw std::runtime_error("the one-process run failed step " + std::to_string(k + 1));
        const double t_one = seconds_since(t0);
        std::vector<double> r(one.particle_record_width());
        std::size_t differ = 0;
        for (std::size_t i = 0; i < all.size(); ++i) {
          one.write_particle(i, r.data());
          differ += std::memcmp(r.data(), all.at(i), r.size() * sizeof(double)) != 0 ? 1 : 0;
        }
        const RigidSphere &a = run.solver().sphere(), &b = one.sphere();
        const bool same_sphere = std::memcmp(&a.x, &b.x, sizeof a.x) == 0 && std::memcmp(&a.v, &b.v, sizeof a.v) == 0;
        std::printf("one process: %.2f s (%.2f ms a step), sphere v_z %.6f m/s (%s), %zu particles differ\n", t_one,
                    1e3 * t_one / std::max(done, 1), b.v[2], same_sphere ? "the same bits" : "DIFFERS", differ);
      }
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "uhpc_distributed_steps (rank %d): %s\n", mpi.rank(), e.what());
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
}
