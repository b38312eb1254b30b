// Speed of the explicit step; items are particle-steps.
//  BM_ElasticStep: elastic box of 32 x 32 x 32 = 32 768 particles, support 2 h, moving and deforming
//    so the lists are really rebuilt. Arguments: threads, strain configuration (0 midpoint, 1 end of
//    step, 2 endpoint average), stabilization (0 none, 1 NSNI).
//  BM_PaperDisc: the paper-scale target of data/macro_disc_elastic.json (disc 406.4 x 31.75 mm, spacing
//    3.0 mm at the axis growing to 4.5 mm at the rim: 79 957 particles; elastic stand-in with the AFC
//    moduli) hit by the paper's sphere (9.071 g, 6.35 mm) at 817 m/s, already touching the entry face.
//    Arguments: threads, support factor x 10 (20: 2.0 h, 25: 2.5 h), NSNI (0/1), strain configuration
//    (as above), lazy-row tolerance x 1e4 (0: off). Fixed 8 steps per configuration: the eight of the product with midpoint strain (about
//    a minute on this machine; comparable with the earlier figures), and end / endpoint average at
//    2.5 h with NSNI; the three strain configurations of the shipped setting alone:
//    --benchmark_filter='PaperDisc/.*/support_x10:25/nsni:1/'.
//  BM_PaperDisc100: the figure, the same disc in the shipped configuration (2.5 h, NSNI,
//    endpoint-average strain) over 100 steps, on 1 and 2 threads, every RK row rebuilt every step
//    (reuse_e4 0) and with the shipped lazy rows (reuse_e4 3: shape_reuse_tolerance 3e-4) (a few
//    minutes; compared with LAMMPS by pipelines/bench_ratio.py). The disc starts at rest, so lazy rows
//    keep most rows here: a whole shot gains less (macro/README.md, Speed).
//  Counters of both: particles, rows_built (the fraction of RK rows rebuilt), searches/reuses (RK rebuilds in the timed steps that searched the
//    neighbours afresh / reused the Verlet candidates), full_searches (of the searches, those over every
//    particle; the others searched only the fast ones), in_contact, peak_rss_MiB. peak_rss_MiB is the
//    process's peak resident set so far (getrusage ru_maxrss after the timed steps), not the
//    configuration's own: it includes every benchmark run before it, so for a clean figure run one
//    configuration alone, e.g. --benchmark_filter='BM_PaperDisc100/threads:2'. heap_B_per_particle is
//    the configuration's own: the heap the shot holds after its timed steps (body, particles, material,
//    solver), per particle (uhpc::heap_in_use_bytes; -1 where the C library does not tell).
//  BM_PaperDiscModels100: the same disc and shipped solver settings (lazy rows 3e-4) with the law and
//    the contact as arguments: law 0 elastic stand-in, 1 AFC with the paper's SDEL (eq. 21's split:
//    the NSNI gradients are kept effective and split for the forces); contact 0 kinematic (the
//    default), 1 penalty. 100 steps from the sphere touching at 817 m/s, on 1 and 2 threads: what the
//    inelastic contact and the AFC law with its NSNI cost against the elastic penalty run.
// `uhpc_bench_macro --benchmark_filter=PaperDisc` runs the disc alone (all), `--benchmark_filter=
// PaperDisc/` the 8-step product only, `--benchmark_filter=PaperDisc100` the 100-step figure only.
#include <benchmark/benchmark.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include <functional>
#include <memory>

#include "bodies/generators.hpp"
#include "materials/afc_config.hpp"
#include "solver/explicit_solver.hpp"
#include "uhpc/resources.hpp"

namespace {

using namespace uhpc::macro;

StrainConfiguration strain_configuration(std::int64_t arg) {
  return arg == 0 ? StrainConfiguration::Midpoint : arg == 1 ? StrainConfiguration::End : StrainConfiguration::EndpointAverage;
}

void BM_ElasticStep(benchmark::State& state) {
#ifdef _OPENMP
  omp_set_num_threads(static_cast<int>(state.range(0)));
#endif
  SolverOptions options;
  options.strain_configuration = strain_configuration(state.range(1));
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
    ->ArgNames({"threads", "strain", "nsni"})
    ->Args({1, 0, 1})
    ->Args({2, 0, 1})
    ->Args({1, 1, 1})
    ->Args({2, 1, 1})
    ->Args({1, 2, 1})
    ->Args({2, 2, 1})
    ->Args({1, 1, 0})
    ->Args({2, 1, 0})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The paper disc (data/macro_disc_elastic.json's geometry) of the material `make_material(n)` gives
// for its n particles, the sphere touching the particles' contact radius at 817 m/s; 2 steps to
// settle the buffers, then the timed steps.
void run_paper_disc(benchmark::State& state, const SolverOptions& options,
                    const std::function<MaterialSet(std::size_t)>& make_material, SphereContactModel contact) {
  const double heap0 = uhpc::heap_in_use_bytes();
  DiscSpec spec;
  spec.radius_m = 0.2032;
  spec.thickness_m = 0.03175;
  spec.h_axis_m = 0.003;
  spec.h_rim_m = 0.0045;
  spec.core_radius_m = 0.05;
  const ParticleBody body = disc_body(spec);
  MaterialSet material = make_material(body.size());
  const double rho = reference_density(material);
  auto solver = std::make_unique<ExplicitSolver>(Particles::from_body(body, rho, options.support_factor),
                                                 std::move(material), options);
  RigidSphere sphere;
  sphere.mass_kg = 9.071e-3;
  sphere.radius_m = 0.00635;
  sphere.x = {0.0, 0.0, -0.00635 - 0.0005};  // touching the particles' contact radius (h/2 = 1.5 mm)
  sphere.v = {0.0, 0.0, 817.0};
  sphere.contact.model = contact;
  solver->set_sphere(sphere);
  solver->initialize();
  for (int s = 0; s < 2; ++s) solver->step();  // buffers settle
  const std::size_t searches0 = solver->shapes().searches, reuses0 = solver->shapes().reuses;
  const std::size_t full0 = solver->shapes().candidate_search.outer_searches;
  const std::size_t built0 = solver->shapes().rows_built, kept0 = solver->shapes().rows_kept;
  for (auto _ : state)
    if (!solver->step()) state.SkipWithError("step failed");
  state.counters["peak_rss_MiB"] = uhpc::peak_memory_MiB();  // the whole process so far
  // What the shot holds after its steps (body, particles, material, solver with its shape table and
  // lists), per particle: this configuration's own, unlike the peak resident set.
  state.counters["heap_B_per_particle"] =
      heap0 < 0.0 ? -1.0 : (uhpc::heap_in_use_bytes() - heap0) / static_cast<double>(body.size());
  // RK rebuilds in the timed steps that searched the neighbours afresh / reused the Verlet candidates.
  state.counters["searches"] = static_cast<double>(solver->shapes().searches - searches0);
  state.counters["reuses"] = static_cast<double>(solver->shapes().reuses - reuses0);
  // Of the searches, those that searched every particle (the others: only the fast ones).
  state.counters["full_searches"] = static_cast<double>(solver->shapes().candidate_search.outer_searches - full0);
  // Lazy rows: the fraction of RK rows rebuilt in the timed steps (1 without).
  const double built = static_cast<double>(solver->shapes().rows_built - built0),
               kept = static_cast<double>(solver->shapes().rows_kept - kept0);
  state.counters["rows_built"] = built + kept > 0 ? built / (built + kept) : 1.0;
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(body.size()));
  state.counters["particles"] = static_cast<double>(body.size());
  state.counters["in_contact"] = static_cast<double>(solver->contact().particles_in_contact);
}

constexpr double kRho = 2555.7, kK = 2.20704e10, kG = 1.8457e10;  // data/macro_disc_elastic.json
MaterialSet elastic_disc(std::size_t n) { return make_material_set(ElasticMaterial(ElasticParams{kRho, kK, kG}), n); }

void BM_PaperDisc(benchmark::State& state) {
#ifdef _OPENMP
  omp_set_num_threads(static_cast<int>(state.range(0)));
#endif
  SolverOptions options;
  options.support_factor = 0.1 * static_cast<double>(state.range(1));
  options.stabilization = state.range(2) == 0 ? Stabilization::None : Stabilization::Nsni;
  options.strain_configuration = strain_configuration(state.range(3));
  options.shape_reuse_tolerance = 1e-4 * static_cast<double>(state.range(4));
  run_paper_disc(state, options, elastic_disc, SphereContactModel::Kinematic);
}

void BM_PaperDiscModels(benchmark::State& state) {
#ifdef _OPENMP
  omp_set_num_threads(static_cast<int>(state.range(0)));
#endif
  SolverOptions options;  // the shipped case's solver settings
  options.support_factor = 2.5;
  options.strain_configuration = StrainConfiguration::EndpointAverage;
  options.shape_reuse_tolerance = 3e-4;
  options.viscosity.damp_stress_free_points = false;
  const auto afc = [](std::size_t n) {
    return make_material_set(AfcMaterial(load_afc_params(UHPC_DATA_DIR "/afc_uhpc.json", UHPC_DATA_DIR "/sdel_paper.json")), n);
  };
  run_paper_disc(state, options, state.range(1) == 0 ? std::function<MaterialSet(std::size_t)>(elastic_disc) : afc,
                 state.range(2) == 0 ? SphereContactModel::Kinematic : SphereContactModel::Penalty);
}

BENCHMARK(BM_PaperDisc)
    ->ArgNames({"threads", "support_x10", "nsni", "strain", "reuse_e4"})
    ->ArgsProduct({{1, 2}, {20, 25}, {0, 1}, {0}, {0}})
    ->Args({1, 25, 1, 1, 0})
    ->Args({2, 25, 1, 1, 0})
    ->Args({1, 25, 1, 2, 0})
    ->Args({2, 25, 1, 2, 0})
    ->Iterations(8)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The figure: shipped configuration (2.5 h, NSNI, endpoint-average strain), 100 steps, without
// and with the shipped lazy rows.
BENCHMARK(BM_PaperDisc)
    ->Name("BM_PaperDisc100")
    ->ArgNames({"threads", "support_x10", "nsni", "strain", "reuse_e4"})
    ->Args({1, 25, 1, 2, 0})
    ->Args({2, 25, 1, 2, 0})
    ->Args({1, 25, 1, 2, 3})
    ->Args({2, 25, 1, 2, 3})
    ->Iterations(100)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

BENCHMARK(BM_PaperDiscModels)
    ->Name("BM_PaperDiscModels100")
    ->ArgNames({"threads", "law", "contact"})
    ->ArgsProduct({{1, 2}, {0, 1}, {0, 1}})
    ->Iterations(100)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
