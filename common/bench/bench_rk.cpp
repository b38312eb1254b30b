// Benchmarks of the common library's hot paths: RK shape functions with gradients (2D and 3D, at
// every node of a jittered lattice, support radius 2 spacings) and the cell-list neighbour search.
// Figures are evaluations (or queries) per second: items_per_second in the JSON output.
// Thread counts 1 and 2 (this machine has 2 cores) are separate cases: compare their ratio within one
// run, not absolute times across runs.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "uhpc/neighbour_search.hpp"
#include "uhpc/rk_shape.hpp"

namespace {

template <int Dim>
struct Lattice {
  std::vector<double> x, a;
  std::size_t size() const { return a.size(); }
};

template <int Dim>
Lattice<Dim> jittered_lattice(int per_side, double support_factor) {
  Lattice<Dim> l;
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> jitter(-0.2, 0.2);
  const long total = Dim == 2 ? long(per_side) * per_side : long(per_side) * per_side * per_side;
  for (long n = 0; n < total; ++n) {
    const long idx[3] = {n % per_side, (n / per_side) % per_side, n / (long(per_side) * per_side)};
    for (int d = 0; d < Dim; ++d) l.x.push_back(idx[d] + jitter(rng));
    l.a.push_back(support_factor);
  }
  return l;
}

void set_threads(const benchmark::State& state) {
#ifdef _OPENMP
  omp_set_num_threads(static_cast<int>(state.range(1)));
#else
  (void)state;
#endif
}

template <int Dim>
void BM_ShapeTable(benchmark::State& state) {
  set_threads(state);
  const Lattice<Dim> l = jittered_lattice<Dim>(static_cast<int>(state.range(0)), 2.0);
  uhpc::rk::Options options;
  std::size_t entries = 0;
  for (auto _ : state) {
    const auto table = uhpc::rk::build_shape_table<Dim>(options, l.x.data(), l.size(), l.x.data(), l.a.data(), l.size());
    entries = table.psi.size();
    benchmark::DoNotOptimize(table.psi.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * l.size()));
  state.counters["points"] = static_cast<double>(l.size());
  state.counters["neighbours_per_point"] = static_cast<double>(entries) / static_cast<double>(l.size());
  state.counters["threads"] = static_cast<double>(state.range(1));
}

// Shape functions only (neighbour lists built once, outside the timing).
template <int Dim>
void BM_ShapeEvaluate(benchmark::State& state) {
  set_threads(state);
  const Lattice<Dim> l = jittered_lattice<Dim>(static_cast<int>(state.range(0)), 2.0);
  const auto support = uhpc::nodes_covering<Dim>(l.x.data(), l.size(), l.x.data(), l.a.data(), l.size());
  std::vector<double> psi(support.indices.size()), grad(support.indices.size() * Dim);
  const uhpc::rk::Options options;
  const std::int64_t n = static_cast<std::int64_t>(l.size());
  for (auto _ : state) {
#pragma omp parallel for schedule(dynamic, 128)
    for (std::int64_t p = 0; p < n; ++p) {
      const std::int64_t b = support.begin(p);
      uhpc::rk::evaluate<Dim>(options, &l.x[p * Dim], l.x.data(), l.a.data(), support.row(p),
                              static_cast<int>(support.count(p)), psi.data() + b, grad.data() + b * Dim);
    }
    benchmark::DoNotOptimize(psi.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * n);
  state.counters["threads"] = static_cast<double>(state.range(1));
}

template <int Dim>
void BM_NeighbourSearch(benchmark::State& state) {
  set_threads(state);
  const Lattice<Dim> l = jittered_lattice<Dim>(static_cast<int>(state.range(0)), 2.0);
  std::size_t entries = 0;
  for (auto _ : state) {
    const auto list = uhpc::nodes_covering<Dim>(l.x.data(), l.size(), l.x.data(), l.a.data(), l.size());
    entries = list.indices.size();
    benchmark::DoNotOptimize(list.indices.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * l.size()));
  state.counters["neighbours_per_point"] = static_cast<double>(entries) / static_cast<double>(l.size());
  state.counters["threads"] = static_cast<double>(state.range(1));
}

// The same search repeated into one list with one workspace, as a 3D run does every step.
template <int Dim>
void BM_NeighbourSearchReused(benchmark::State& state) {
  set_threads(state);
  const Lattice<Dim> l = jittered_lattice<Dim>(static_cast<int>(state.range(0)), 2.0);
  uhpc::NeighbourList list;
  uhpc::NeighbourWorkspace<Dim> workspace;
  for (auto _ : state) {
    uhpc::nodes_covering<Dim>(l.x.data(), l.size(), l.x.data(), l.a.data(), l.size(), list, workspace);
    benchmark::DoNotOptimize(list.indices.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * l.size()));
  state.counters["threads"] = static_cast<double>(state.range(1));
}

// 2D: 200 x 200 = 40 000 points (a fine microcell); 3D: 50^3 = 125 000 points (paper-size disc).
BENCHMARK_TEMPLATE(BM_ShapeTable, 2)->Args({200, 1})->Args({200, 2})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_TEMPLATE(BM_ShapeTable, 3)->Args({50, 1})->Args({50, 2})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_TEMPLATE(BM_ShapeEvaluate, 2)->Args({200, 1})->Args({200, 2})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_TEMPLATE(BM_ShapeEvaluate, 3)->Args({50, 1})->Args({50, 2})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_TEMPLATE(BM_NeighbourSearch, 2)->Args({200, 1})->Args({200, 2})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_TEMPLATE(BM_NeighbourSearch, 3)->Args({50, 1})->Args({50, 2})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_TEMPLATE(BM_NeighbourSearchReused, 3)->Args({50, 1})->Args({50, 2})->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
