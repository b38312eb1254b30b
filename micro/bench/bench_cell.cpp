// Speed of the elastic microcell analysis (`uhpc-micro elastic`) on one 6.5 mm cell: the shipped
// configs (data/micro_elastic.json, its cell config data/micro_cell.json and the microstructure) with
// cell_size_m = 6.5 mm and the seed data/micro_analysis_ensemble.json gives its first 6.5 mm cell,
// derive_cell_seed(base_seed, size index, 0).
//  BM_CellMesh: generate_cell + mesh_cell (gmsh), as `uhpc-micro elastic` does before the analysis.
//  BM_RkModel: build_rk_galerkin_model (RK shape tables at the Gauss points, VCI).
//  BM_StiffnessAssembly: assemble_elastic_system (domain stiffness, Nitsche terms, point penalty).
//  BM_Factorization: the factorization of K that solve_sparse computes (UMFPACK LU for the
//    unsymmetric VCI stiffness of the shipped options, CHOLMOD LLT for a symmetric one);
//  BM_Solve: one solve with that factorization.
//  BM_ElasticCell: uniaxial_elastic_response (model, assembly, solve, reactions and energy), i.e.
//    `uhpc-micro elastic` without generating, meshing and writing files.
//  BM_CrackedCell/k: the crack analysis of the first 3.0 mm cell at 100 um, GMRES corrections on or off.
//  BM_EnsembleCell/size_um: the crack analysis of the first cell of each size of the shipped ensemble.
// The settings, the cell, its mesh (generated once, outside any timed loop and any OpenMP region:
// gmsh is global state), the model, the system and the factorization are built once, on first use,
// and shared; nothing of it is timed except by its own benchmark. peak_rss_MiB is the process's peak
// resident set so far (getrusage ru_maxrss), so it includes every benchmark run before it.
// Run: `cmake --build build --target bench_micro` (3 repetitions, figures in build/bench/micro.json),
// or build/micro/uhpc_bench_micro [--benchmark_filter=BM_ElasticCell].
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/CholmodSupport>
#include <Eigen/UmfPackSupport>
#include <nlohmann/json.hpp>

#include "cell_analysis.hpp"
#include "cell_analysis_settings.hpp"
#include "cell_generator.hpp"
#include "elastic_settings.hpp"
#include "stiffness_assembly.hpp"
#include "uhpc/config.hpp"
#include "uhpc/resources.hpp"
#include "uniaxial_cell.hpp"

namespace {

using namespace uhpc::micro;
using SparseMatrix = Eigen::SparseMatrix<double>;

constexpr double kCellSize_m = 0.0065;

// The shipped elastic settings for the first cell of `size_m` of the analysis ensemble, with
// `overrides` on top.
ElasticSettings load_settings(double size_m, std::vector<std::string> overrides = {}) {
  const uhpc::Config ensemble = uhpc::Config::load(UHPC_DATA_DIR "/micro_analysis_ensemble.json");
  const std::vector<double> sizes = ensemble.numbers("cell_sizes_m");
  std::uint64_t index = 0;
  while (index < sizes.size() && std::abs(sizes[index] - size_m) > 1e-9) ++index;
  if (index == sizes.size()) throw std::runtime_error("micro_analysis_ensemble.json: no cell size " + std::to_string(size_m));
  const auto base_seed = static_cast<std::uint64_t>(ensemble.integer("base_seed"));
  const std::uint64_t seed = derive_cell_seed(base_seed, index, 0);
  overrides.push_back("cell.cell_size_m=" + nlohmann::json(size_m).dump());
  overrides.push_back("cell.seed=" + std::to_string(seed));
  return load_elastic_settings(UHPC_DATA_DIR "/micro_elastic.json", overrides);
}

const ElasticSettings& settings() {
  static const ElasticSettings s = load_settings(kCellSize_m);
  return s;
}

const GeneratedCell& cell() {
  static const GeneratedCell c = generate_cell(settings().cell.cell, settings().cell.seed);
  return c;
}

const CellDiscretization& mesh() {
  static const CellDiscretization m = mesh_cell(cell().geometry, settings().cell.mesh);
  return m;
}

const RkGalerkinModel& model() {
  static const RkGalerkinModel m = build_rk_galerkin_model(mesh(), settings().options.rk);
  return m;
}

ElasticProblem problem() {
  const ElasticSettings& s = settings();
  return uniaxial_problem(cell().geometry.side_m, cell().geometry.load, s.options.strain, s.material,
                          s.options.nitsche_factor);
}

// The point constraints' shape functions, as solve_elastic samples them.
PointSet constraints(const ElasticProblem& p) {
  std::vector<std::array<double, 2>> xs;
  for (const PointConstraint& c : p.points) xs.push_back(c.x_m);
  return sample_points(model(), xs);
}

const LinearSystem& linear_system() {
  static const LinearSystem sys = [] {
    const ElasticProblem p = problem();
    return assemble_elastic_system(model(), p, constraints(p));
  }();
  return sys;
}

// The two factorizations of solve_sparse (sparse_solver.cpp).
using Llt = Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower>;
using Lu = Eigen::UmfPackLU<SparseMatrix>;

struct Factorization {
  std::unique_ptr<Llt> llt;
  std::unique_ptr<Lu> lu;  // keeps a reference to linear_system().K (static: it outlives the solves)
  bool ok() const { return llt ? llt->info() == Eigen::Success : lu->info() == Eigen::Success; }
  Eigen::VectorXd solve(const Eigen::VectorXd& f) const { return llt ? Eigen::VectorXd(llt->solve(f)) : Eigen::VectorXd(lu->solve(f)); }
};

Factorization factorize(const LinearSystem& sys) {
  Factorization f;
  if (sys.symmetric)
    f.llt = std::make_unique<Llt>(sys.K);
  else
    f.lu = std::make_unique<Lu>(sys.K);
  return f;
}

void BM_CellMesh(benchmark::State& state) {
  const CellSettings& s = settings().cell;
  std::size_t nodes = 0, triangles = 0, pores = 0;
  for (auto _ : state) {
    const GeneratedCell c = generate_cell(s.cell, s.seed);
    const CellDiscretization m = mesh_cell(c.geometry, s.mesh);
    nodes = m.node_count();
    triangles = m.triangle_count();
    pores = c.geometry.pores.size();
  }
  state.SetLabel("seed " + std::to_string(s.seed));  // a counter would round it
  state.counters["pores"] = static_cast<double>(pores);
  state.counters["nodes"] = static_cast<double>(nodes);
  state.counters["triangles"] = static_cast<double>(triangles);
}
BENCHMARK(BM_CellMesh)->Iterations(1)->Unit(benchmark::kMillisecond);

void BM_RkModel(benchmark::State& state) {
  const CellDiscretization& m = mesh();
  const RkGalerkinOptions& options = settings().options.rk;
  for (auto _ : state) {
    const RkGalerkinModel rk = build_rk_galerkin_model(m, options);
    benchmark::DoNotOptimize(rk.vci_max_correction);
  }
  const RkGalerkinModel& rk = model();
  state.counters["nodes"] = static_cast<double>(rk.node_count());
  state.counters["domain_points"] = static_cast<double>(rk.domain.size());
  state.counters["boundary_points"] = static_cast<double>(rk.boundary.size());
  state.counters["shape_entries"] = static_cast<double>(rk.domain.table.support.indices.size());
}
BENCHMARK(BM_RkModel)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_StiffnessAssembly(benchmark::State& state) {
  const RkGalerkinModel& rk = model();
  const ElasticProblem p = problem();
  const PointSet c = constraints(p);
  for (auto _ : state) {
    const LinearSystem sys = assemble_elastic_system(rk, p, c);
    benchmark::DoNotOptimize(sys.K.nonZeros());
  }
  state.counters["dofs"] = static_cast<double>(rk.dof_count());
  state.counters["nnz"] = static_cast<double>(linear_system().K.nonZeros());
}
BENCHMARK(BM_StiffnessAssembly)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Factorization(benchmark::State& state) {
  const LinearSystem& sys = linear_system();
  for (auto _ : state) {
    const Factorization f = factorize(sys);
    if (!f.ok()) {
      state.SkipWithError("factorization failed");
      break;
    }
  }
  state.SetLabel(sys.symmetric ? "cholmod" : "umfpack");
  state.counters["dofs"] = static_cast<double>(sys.K.rows());
  state.counters["nnz"] = static_cast<double>(sys.K.nonZeros());
}
BENCHMARK(BM_Factorization)->Unit(benchmark::kMillisecond)->UseRealTime();

// UMFPACK's fill-reducing ordering and strategy on the same matrix (the cell analysis factorizes a
// matrix of this pattern at every Newton iteration). Args: ordering (UMFPACK_ORDERING_*), strategy.
void BM_UmfpackOrdering(benchmark::State& state) {
  const LinearSystem& sys = linear_system();
  for (auto _ : state) {
    Lu lu;
    lu.umfpackControl()(UMFPACK_ORDERING) = static_cast<double>(state.range(0));
    lu.umfpackControl()(UMFPACK_STRATEGY) = static_cast<double>(state.range(1));
    lu.compute(sys.K);
    if (lu.info() != Eigen::Success) {
      state.SkipWithError("factorization failed");
      break;
    }
  }
}
BENCHMARK(BM_UmfpackOrdering)
    ->ArgNames({"ordering", "strategy"})
    ->Args({UMFPACK_ORDERING_CHOLMOD, UMFPACK_STRATEGY_AUTO})
    ->Args({UMFPACK_ORDERING_AMD, UMFPACK_STRATEGY_AUTO})
    ->Args({UMFPACK_ORDERING_METIS, UMFPACK_STRATEGY_AUTO})
    ->Args({UMFPACK_ORDERING_METIS, UMFPACK_STRATEGY_SYMMETRIC})
    ->Args({UMFPACK_ORDERING_AMD, UMFPACK_STRATEGY_SYMMETRIC})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// What a symmetric operator would cost: CHOLMOD's supernodal LL^T of the symmetric part (K + K^T)/2
// (the cell's K is unsymmetric through VCI's Petrov-Galerkin correction and the boundary terms).
void BM_CholmodSymmetricPart(benchmark::State& state) {
  const LinearSystem& sys = linear_system();
  const SparseMatrix S = 0.5 * (SparseMatrix(sys.K.transpose()) + sys.K);
  for (auto _ : state) {
    Llt llt(S);
    if (llt.info() != Eigen::Success) {
      state.SkipWithError("factorization failed");
      break;
    }
  }
}
BENCHMARK(BM_CholmodSymmetricPart)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Solve(benchmark::State& state) {
  const LinearSystem& sys = linear_system();
  const Factorization f = factorize(sys);
  if (!f.ok()) {
    state.SkipWithError("factorization failed");
    return;
  }
  Eigen::VectorXd d;
  for (auto _ : state) {
    d = f.solve(sys.f);
    benchmark::DoNotOptimize(d.data());
  }
  state.SetLabel(sys.symmetric ? "cholmod" : "umfpack");
  state.counters["dofs"] = static_cast<double>(sys.K.rows());
  state.counters["nnz"] = static_cast<double>(sys.K.nonZeros());
  state.counters["rel_residual"] = (sys.K * d - sys.f).norm() / sys.f.norm();
}
BENCHMARK(BM_Solve)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_ElasticCell(benchmark::State& state) {
  const ElasticSettings& s = settings();
  const CellDiscretization& m = mesh();
  const CellGeometry& g = cell().geometry;
  UniaxialResult r;
  for (auto _ : state) r = uniaxial_elastic_response(m, g.side_m, g.load, s.material, s.options);
  state.SetLabel(r.solver);
  state.counters["nodes"] = static_cast<double>(r.nodes);
  state.counters["dofs"] = static_cast<double>(r.dofs);
  state.counters["E0_bar_MPa"] = r.E0_bar_Pa * 1e-6;
  state.counters["peak_rss_MiB"] = uhpc::peak_memory_MiB();
}
BENCHMARK(BM_ElasticCell)->Iterations(1)->Unit(benchmark::kMillisecond)->UseRealTime();

// The crack analysis of the first cell of `size_m` of the shipped ensemble at 100 um (the ensemble's
// mesh, `cell_overrides` of data/micro_analysis_ensemble.json) to e = 1.5e-3 (its strain grid's end),
// with the shipped solver options but newton.krylov_iterations = `krylov`: `uhpc-micro ensemble` on
// that one cell without the files. The cell and its mesh are made outside the timed loop.
void crack_first_cell(benchmark::State& state, double size_m, int krylov) {
  const ElasticSettings s = load_settings(size_m, {"cell.discretization.nominal_spacing_m=1e-4"});
  const GeneratedCell c = generate_cell(s.cell.cell, s.cell.seed);
  const CellDiscretization m = mesh_cell(c.geometry, s.cell.mesh);
  const CellMaterial material = read_cell_material(uhpc::Config::load(s.cell.microstructure_file).section("matrix"));
  CellAnalysisOptions o;
  o.max_strain = 1.5e-3;
  o.krylov_iterations = krylov;
  CellResponse r;
  for (auto _ : state) r = analyze_cell(c.geometry, m, material, o);
  state.SetLabel(to_string(r.status));
  double peak = 0.0;
  for (const CellState& x : r.states) peak = std::max(peak, x.sigma_bar_Pa);
  state.counters["dofs"] = static_cast<double>(r.dofs);
  state.counters["states"] = static_cast<double>(r.states.size());
  state.counters["peak_MPa"] = peak * 1e-6;
  state.counters["factorizations"] = static_cast<double>(r.factorizations);
  state.counters["crack_geometries"] = static_cast<double>(r.crack_geometries);
  state.counters["krylov_products"] = static_cast<double>(r.krylov_products);
  state.counters["peak_rss_MiB"] = uhpc::peak_memory_MiB();
}

// The first 3.0 mm cell with the Newton corrections by GMRES on an earlier factorization (arg:
// newton.krylov_iterations; 0: a factorization per iteration). The two args run back to back: compare
// their ratio.
void BM_CrackedCell(benchmark::State& state) { crack_first_cell(state, 0.003, static_cast<int>(state.range(0))); }
BENCHMARK(BM_CrackedCell)->Arg(0)->Arg(16)->Iterations(1)->Unit(benchmark::kMillisecond)->UseRealTime();

// One cell per size of the ensemble (arg: size in um), shipped options: what a cell of each size costs,
// the 6.5 mm cell (5-19 min) most of all. peak_rss_MiB is the process's so far: run one size alone for
// its own figure, e.g. --benchmark_filter='BM_EnsembleCell/6500'.
void BM_EnsembleCell(benchmark::State& state) {
  crack_first_cell(state, 1e-6 * static_cast<double>(state.range(0)), CellAnalysisOptions{}.krylov_iterations);
}
BENCHMARK(BM_EnsembleCell)->Arg(3000)->Arg(4500)->Arg(5000)->Arg(6500)->Iterations(1)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
