// Speed of the explicit step (elastic box of 32 x 32 x 32 = 32 768 particles, support 2 h, moving and
// deforming so the lists are really rebuilt): items are particle-steps. Arguments: threads, strain
// configuration (0 midpoint, 1 end of step), stabilization (0 none, 1 NSNI).
#include <benchmark/benchmark.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "bodies/generators.hpp"
#include "solver/explicit_solver.hpp"

namespace {

using namespace uhpc::macro;

void BM_ElasticStep(benchmark::State& state) {
#ifdef _OPENMP
  omp_set_num_threads(static_cast<int>(state.range(0)));
#endif
  SolverOptions options;
  options.strain_configuration = state.range(1) == 0 ? StrainConfiguration::Midpoint : StrainConfiguration::End;
  options.stabilization = state.range(2) == 0 ? Stabilization::None : Stabilization::Nsni;
  const ParticleBody body = box_body(0.32, 0.32, 0.32, 0.01);
  ExplicitSolver solver(Particles::from_body(body, 2500.0, options.support_factor),
                        make_material_set(ElasticMaterial(ElasticParams{2500.0, 20e9, 15e9}), body.size()), options);
  set_initial_velocity(solver.particles(), [](const double* x) -> Vec3 { return {20.0 * x[1], -10.0 * x[0], 5.0}; });
  solver.initialize();
  for (int s = 0; s < 2; ++s) solver.step();  // buffers settle
  for (auto _ : state) solver.step();
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(body.size()));
  state.counters["particles"] = static_cast<double>(body.size());
}

BENCHMARK(BM_ElasticStep)
    ->ArgNames({"threads", "end_config", "nsni"})
    ->Args({1, 0, 1})
    ->Args({2, 0, 1})
    ->Args({1, 1, 1})
    ->Args({2, 1, 1})
    ->Args({1, 1, 0})
    ->Args({2, 1, 0})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
