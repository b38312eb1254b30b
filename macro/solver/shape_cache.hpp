#pragma once
// RK shape-function gradients of every particle at every particle, rebuilt in a given configuration
// (semi-Lagrangian: the current one), reusing all memory between steps. common's build_shape_table
// returns a fresh table each call; this keeps the lists, the values and the search workspace, so once
// the neighbour counts have settled a rebuild allocates nothing. With second derivatives (NSNI) the
// shape functions, first and second gradients come from one kernel pass and one set of moments per
// point (shape_and_second_gradients); without, from the linear-only version of the same code
// (shape_gradients). Both equal rk::evaluate<3> (+ second_gradients) to round-off.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "solver/second_gradients.hpp"
#include "solver/verlet_candidates.hpp"
#include "uhpc/neighbour_search.hpp"
#include "uhpc/rk_shape.hpp"

namespace uhpc::macro {

// A row of fewer nodes than the linear basis has terms in 3D (4) is a fragment: one to three particles
// flying apart from the body, whose velocity field RK cannot resolve (the quasi-linear gradient along a
// pair of nodes is 1/d, and two fragments closing on each other were compressed and thrown apart at
// 2 km/s within a few steps, the energy check's failure at 610 m/s).
constexpr std::int64_t kMinContinuumRow = 4;

// What ShapeCache::rebuild computes from each row right after building it, while the row is still in
// cache (instead of a second pass over the stored table): the velocity gradients of kinematics.hpp,
// L (9n) and, with second gradients and G non-null, G (27n), of the velocities v (3n).
struct RowVelocityGradients {
  const double* v = nullptr;
  double* L = nullptr;
  double* G = nullptr;
};

struct ShapeCache {
  // The exact lists of the last prepare() without lazy rows (read rows through row_nodes/row_size/
  // row_begin, which also serve lazy rows).
  NeighbourList support;
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
  // identical to a fresh search. 0: a fresh cell-list search at every rebuild. The candidates are
  // themselves found without a full search where possible (candidate_search, below).
  double skin = 0.0;
  NeighbourList candidates;
  std::vector<double> candidate_x, candidate_support, inflated_support;
  std::vector<std::int32_t> filtered;
  std::size_t searches = 0, reuses = 0;  // rebuilds that searched / that reused the candidates
  // The searches of the candidates: a full search only now and then, otherwise only the particles that
  // moved far (verlet_candidates.hpp); the same lists.
  VerletCandidates candidate_search;
  // Lazy rows (reuse_tolerance > 0; needs skin > 0). A row is rebuilt only when its neighbourhood has
  // changed shape since it was built: some node J of it moved relative to the point L by more than
  // reuse_tolerance * a_L, or a candidate that was outside the support has come in deeper than that.
  // Otherwise the row keeps the functions of the configuration it was built in: exact for a rigid
  // translation, within O(reuse_tolerance) of the current gradients otherwise (the strain since the
  // build). Every row still reproduces linear fields in its build configuration, and the forces and
  // the strain rates read the same gradients, so momentum and the energy balance stay exact. Rows live
  // in slots of their own with room to grow (a new layout, every row built, when one outgrows it), so
  // a new search of the candidates does not force rebuilds. 0: every row is rebuilt at every prepare
  // (the semi-Lagrangian method as such).
  double reuse_tolerance = 0.0;
  // Fragments by conditioning (> 0): a row of four or more nodes that lie nearly in a plane or on a
  // line is a fragment too when the reciprocal condition number of its linear moment matrix (S of
  // rk_shape.hpp, PointResult::rcond) is below fragment_rcond, or when RK left its full path for it
  // (rcond below rk::Options::rcond_min). Its gradients across the thin direction grow like
  // 1 / sqrt(rcond): a flat sheet of four ejecta (rcond 5e-4, gradients some 25 times those of a sound
  // row) was compressed through its thickness and threw a particle to 1 km/s in one step at a step
  // that is stable for the body. 0: the node count alone.
  double fragment_rcond = 0.0;
  std::size_t rows_built = 0, rows_kept = 0;  // rows rebuilt / kept over all prepares (lazy rows only)
  std::size_t layouts = 0;                    // new slot layouts (every row built; lazy rows only)
  // One rank of a distributed run (solver/rank_share.hpp) with lazy rows: only the rows of `counted`
  // points (its own particles) decide a new layout, and the ranks decide it together (any_rank: true on
  // every rank when true on one; called once a prepare). A row not counted that would outgrow its slot
  // keeps its old values: it is a ghost's row that no owned particle reads (the halo holds the nodes of
  // every row that one reads, so those rows are their owners' and outgrow their slots with them).
  const std::uint8_t* counted = nullptr;
  std::function<bool(bool)> any_rank;

 private:
  // The arguments of the last prepare(), for build_row.
  rk::Options options_;
  const SecondGradientOptions* second_ = nullptr;
  const double* x_ = nullptr;
  const double* support_radius_ = nullptr;
  std::int64_t longest_ = 0;  // the longest row (the evaluation scratch per thread without keep_psi)
  // Lazy rows: the nodes of each row (a subset of its candidates, in their order), their number, and
  // x_J - x_L at the row's build (3 floats per entry: only compared with the tolerance); due_[L]: the
  // row must be built at the configuration of this prepare.
  std::vector<std::int32_t> lazy_nodes_, lazy_size_;
  std::vector<float> built_offset_;
  std::vector<std::uint8_t> due_;
  bool lazy() const { return reuse_tolerance > 0.0; }
  std::vector<std::int64_t> lazy_offsets_;  // row L's slot: [lazy_offsets_[L], lazy_offsets_[L + 1])
  bool row_due(std::int64_t p) const;
  std::int64_t members_now(std::int64_t p) const;  // candidates of p that cover x_p now
  // Does node j's support cover x_p now (the search's own test)? r = x_j - x_p.
  bool covers(std::int64_t p, std::int32_t j, double* r) const;
  bool update_candidates(const double* x, const double* support_radius, std::size_t n);  // true: searched

 public:

  // Rebuilds at the n points `x` (3n), which are also the nodes, with support radii `support`; with
  // `second` also the implicit second derivatives on the same lists; with `gradients` also those.
  void rebuild(const rk::Options& options, const double* x, const double* support, std::size_t n,
               const SecondGradientOptions* second = nullptr, const RowVelocityGradients* gradients = nullptr);
  // The same in parts, for a caller that works on each row while it is still in cache: prepare (the
  // neighbour lists and the sizes; keeps the pointers for build_row), then, from inside a parallel
  // region, thread_scratch once per thread and build_row for every point. rebuild is exactly that.
  // old_rows (optional): the caller also needs the velocity gradients of the rows as they are before
  // this prepare. Returns true when prepare computed them for every row into old_rows (first, before
  // it discarded the rows: no lazy rows, or a new layout), false when the old rows stay in place for
  // the caller to read (lazy rows: a due row's old values until its build_row, a kept row's for good).
  bool prepare(const rk::Options& options, const double* x, const double* support, std::size_t n,
               const SecondGradientOptions* second, const RowVelocityGradients* old_rows = nullptr);
  double* thread_scratch();  // per-thread evaluation buffer (null with keep_psi); call from every thread
  void build_row(std::int64_t p, double* scratch);
  std::size_t count(rk::Path path) const;
  void find_with_skin(const double* x, const double* support_radius, std::size_t n);  // fills `support`
  std::size_t count(SecondGradientPath path) const;
  bool has_second_gradients() const { return !hess.empty(); }

  // A fragment moves as a rigid body: L = 0 and no internal force (kinematics.hpp, InternalForce::
  // add_row); it still meets the sphere and rejoins the continuum once its row is sound again. Read
  // after build_row(p) (the criterion is that of the row as built).
  bool fragment(std::size_t p) const {
    if (row_size(p) < kMinContinuumRow) return true;
    if (!(fragment_rcond > 0.0)) return false;
    return info[p].path != rk::Path::Full || !(info[p].rcond >= fragment_rcond);
  }

  std::size_t fragments() const;  // rows that are fragments now
  // Whether it holds the rows of n points (none after a drop, before the first prepare).
  bool has_rows(std::size_t n) const { return (lazy() ? lazy_size_.size() : support.size()) == n && info.size() == n; }

  // Lazy rows as records, for a distributed run's particles that change rank (DistributedRun): row p
  // written at `out` as row_record_length(p) doubles (the first: that length), its nodes as their global
  // ids ids[node], returning the end; and a table of n rows made from such records (records[p]: row p's), the nodes mapped to this table's points by local_of (-1:
  // not here), or, where records[p] is null, row p kept as this table holds it (its slot included). A
  // row with a node not here is installed empty: a ghost's row no owned particle reads, made again when
  // it is next due. The rows then stand as after a prepare at the positions they came from.
  std::size_t row_record_length(std::size_t p) const;
  double* write_row(std::size_t p, const std::uint32_t* ids, double* out) const;
  void install_rows(std::size_t n, const std::vector<const double*>& records,
                    const std::function<std::int32_t(std::uint32_t)>& local_of, const SecondGradientOptions* second);

  // Lazy rows and p kept at this prepare (build_row(p) leaves it as it was).
  bool row_kept(std::size_t p) const { return lazy() && !due_[p]; }
  // Row p: its entries in psi/grad/hess start at row_begin(p); row_size(p) nodes, row_nodes(p).
  std::int64_t row_begin(std::size_t p) const { return lazy() ? lazy_offsets_[p] : support.begin(p); }
  std::int64_t row_size(std::size_t p) const { return lazy() ? lazy_size_[p] : support.count(p); }
  const std::int32_t* row_nodes(std::size_t p) const {
    return (lazy() ? lazy_nodes_.data() : support.indices.data()) + row_begin(p);
  }
};

}  // namespace uhpc::macro
