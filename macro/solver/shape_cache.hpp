#pragma once
// RK shape-function gradients of every particle at every particle, rebuilt in a given configuration
// (semi-Lagrangian: the current one), reusing all memory between steps. common's build_shape_table
// returns a fresh table each call; this keeps the lists, the values and the search workspace, so once
// the neighbour counts have settled a rebuild allocates nothing. With second derivatives (NSNI) the
// shape functions, first and second gradients come from one kernel pass and one set of moments per
// point (shape_and_second_gradients); without, from the linear-only version of the same code
// (shape_gradients). Both equal rk::evaluate<3> (+ second_gradients) to round-off.
#include <cstddef>
#include <vector>

#include "solver/second_gradients.hpp"
#include "uhpc/neighbour_search.hpp"
#include "uhpc/rk_shape.hpp"

namespace uhpc::macro {

// What ShapeCache::rebuild computes from each row right after building it, while the row is still in
// cache (instead of a second pass over the stored table): the velocity gradients of kinematics.hpp,
// L (9n) and, with second gradients and G non-null, G (27n), of the velocities v (3n).
struct RowVelocityGradients {
  const double* v = nullptr;
  double* L = nullptr;
  double* G = nullptr;
};

struct ShapeCache {
  NeighbourList support;           // support.row(L): the particles J whose support covers x_L
  // keep_psi: Psi_J(x_L), one per entry. Otherwise (the solver: nothing of its step reads the values)
  // only per-thread scratch of the evaluation, which is not written back to memory.
  std::vector<double> psi;
  bool keep_psi = true;
  std::vector<double> grad;        // grad Psi_J(x_L), 3 per entry
  std::vector<rk::PointResult> info;
  std::vector<double> hess;                      // NSNI: Psi^(ij)_J(x_L), 6 per entry (second_gradients.hpp)
  std::vector<SecondGradientPath> hess_path;     // one per point
  NeighbourWorkspace<3> workspace;
  // Verlet skin (exact): > 0 keeps candidate lists searched with radii a_J + s, s = skin * min_J a_J,
  // and only filters them (|x_L - x_J| < a_J, the search's own test, in the same ascending order) while
  // no point has moved more than s/2 from where the candidates were searched: the lists are then
  // identical to a fresh search. 0: a fresh cell-list search at every rebuild.
  double skin = 0.0;
  NeighbourList candidates;
  std::vector<double> candidate_x, candidate_support, inflated_support;
  std::vector<std::int32_t> filtered;
  std::size_t searches = 0, reuses = 0;  // rebuilds that searched / that reused the candidates

 private:
  // The arguments of the last prepare(), for build_row.
  rk::Options options_;
  const SecondGradientOptions* second_ = nullptr;
  const double* x_ = nullptr;
  const double* support_radius_ = nullptr;
  std::int64_t longest_ = 0;  // the longest row (the evaluation scratch per thread without keep_psi)

 public:

  // Rebuilds at the n points `x` (3n), which are also the nodes, with support radii `support`; with
  // `second` also the implicit second derivatives on the same lists; with `gradients` also those.
  void rebuild(const rk::Options& options, const double* x, const double* support, std::size_t n,
               const SecondGradientOptions* second = nullptr, const RowVelocityGradients* gradients = nullptr);
  // The same in parts, for a caller that works on each row while it is still in cache: prepare (the
  // neighbour lists and the sizes; keeps the pointers for build_row), then, from inside a parallel
  // region, thread_scratch once per thread and build_row for every point. rebuild is exactly that.
  void prepare(const rk::Options& options, const double* x, const double* support, std::size_t n,
               const SecondGradientOptions* second);
  double* thread_scratch();  // per-thread evaluation buffer (null with keep_psi); call from every thread
  void build_row(std::int64_t p, double* scratch);
  std::size_t count(rk::Path path) const;
  void find_with_skin(const double* x, const double* support_radius, std::size_t n);  // fills `support`
  std::size_t count(SecondGradientPath path) const;
  bool has_second_gradients() const { return !hess.empty(); }
};

}  // namespace uhpc::macro
