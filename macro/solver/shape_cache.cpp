#include "solver/shape_cache.hpp"
#include "solver/parallel.hpp"

#include "solver/kinematics.hpp"
#include "uhpc/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace uhpc::macro {

namespace {
// Grow with headroom so that the slow drift of neighbour counts during a run does not reallocate.
void resize_with_headroom(std::vector<double>& v, std::size_t size) {
  if (v.capacity() < size) v.reserve(size + size / 5);
  v.resize(size);
}
}  // namespace

void ShapeCache::rebuild(const rk::Options& options, const double* x, const double* support_radius, std::size_t n,
                         const SecondGradientOptions* second, const RowVelocityGradients* gradients) {
  prepare(options, x, support_radius, n, second);
  const std::int64_t nq = static_cast<std::int64_t>(n);
#pragma omp parallel if (nq >= kParallelMinParticles)
  {
    double* scratch = thread_scratch();
#pragma omp for schedule(dynamic, 128)
    for (std::int64_t p = 0; p < nq; ++p) {
      build_row(p, scratch);
      if (gradients) {
        const std::int64_t b = row_begin(p);
        const bool with_g = second && gradients->G;
        point_velocity_gradients(fragment(p), row_nodes(p), row_size(p), grad.data() + 3 * b,
                                 with_g ? hess.data() + 6 * b : nullptr, gradients->v, p, gradients->L + 9 * p,
                                 with_g ? gradients->G + 27 * p : nullptr);
      }
    }
  }
}

bool ShapeCache::prepare(const rk::Options& options, const double* x, const double* support_radius, std::size_t n,
                         const SecondGradientOptions* second, const RowVelocityGradients* old_rows) {
  std::size_t entries = 0;
  bool old_rows_done = false;
  auto gradients_of_old_rows = [&]() {
    if (!old_rows || old_rows_done) return;
    if ((lazy() ? lazy_size_.size() : support.size()) != n)
      throw std::logic_error("ShapeCache::prepare: old_rows needs the rows of an earlier prepare");
    velocity_gradients(*this, old_rows->v, n, old_rows->L, has_second_gradients() ? old_rows->G : nullptr);
    old_rows_done = true;
  };
  if (lazy()) {
    if (!(skin > 0.0)) throw std::invalid_argument("ShapeCache: lazy rows (reuse_tolerance > 0) need a Verlet skin");
    update_candidates(x, support_radius, n);
    x_ = x;
    support_radius_ = support_radius;
    const std::int64_t nq = static_cast<std::int64_t>(n);
    // A new layout when there is none yet, for another kind of row (second gradients or not), or when
    // a row to rebuild has outgrown its slot: every row is then built.
    bool fresh = lazy_size_.size() != n || (second != nullptr) != (second_ != nullptr);
    if (!fresh) {
      bool overflow = false;
#pragma omp parallel for schedule(static, kRowChunk) reduction(|| : overflow) if (nq >= kParallelMinParticles)
      for (std::int64_t p = 0; p < nq; ++p) {
        const bool due = row_due(p);
        due_[p] = due ? 1 : 0;
        if (due && members_now(p) > lazy_offsets_[p + 1] - lazy_offsets_[p]) {
          if (!counted || counted[p]) overflow = true;
          else due_[p] = 0;  // a ghost's row no owned particle reads (counted, above)
        }
      }
      fresh = overflow;
    }
    if (any_rank) fresh = any_rank(fresh);
    if (fresh) {
      gradients_of_old_rows();
      // Slots with room for the neighbour counts to grow (compression) before the next new layout.
      lazy_offsets_.resize(n + 1);
      lazy_offsets_[0] = 0;
#pragma omp parallel for schedule(static) if (nq >= kParallelMinParticles)
      for (std::int64_t p = 0; p < nq; ++p) {
        const std::int64_t c = members_now(p);
        lazy_offsets_[p + 1] = c + c / 8 + 4;
      }
      for (std::size_t p = 0; p < n; ++p) lazy_offsets_[p + 1] += lazy_offsets_[p];
      const std::size_t slots = static_cast<std::size_t>(lazy_offsets_[n]);
      if (lazy_nodes_.capacity() < slots) lazy_nodes_.reserve(slots + slots / 5);
      lazy_nodes_.resize(slots);
      if (built_offset_.capacity() < 3 * slots) built_offset_.reserve(3 * slots + 3 * slots / 5);
      built_offset_.resize(3 * slots);
      lazy_size_.assign(n, 0);
      due_.assign(n, 1);
      ++layouts;
    }
    entries = static_cast<std::size_t>(lazy_offsets_[n]);
    const std::size_t due = static_cast<std::size_t>(std::count(due_.begin(), due_.end(), std::uint8_t{1}));
    rows_built += due;
    rows_kept += n - due;
  } else {
    gradients_of_old_rows();
    if (skin > 0.0) {
      find_with_skin(x, support_radius, n);
    } else {
      nodes_covering<3>(x, n, x, support_radius, n, support, workspace);
      ++searches;
    }
    entries = support.indices.size();
    // The search sizes its lists exactly; give them (and its per-thread buffers) headroom so that the
    // slow growth of neighbour counts does not reallocate on the next steps.
    if (support.indices.capacity() < entries + entries / 10) support.indices.reserve(entries + entries / 4);
    for (auto& block : workspace.blocks)
      if (block.capacity() < block.size() + block.size() / 10) block.reserve(block.size() + block.size() / 4);
  }
  longest_ = 0;
  if (!keep_psi)
    for (std::size_t p = 0; p < n; ++p)
      longest_ = std::max(longest_, lazy() ? lazy_offsets_[p + 1] - lazy_offsets_[p] : support.count(p));
  if (keep_psi) resize_with_headroom(psi, entries);
  resize_with_headroom(grad, 3 * entries);
  info.resize(n);
  if (second) {
    resize_with_headroom(hess, 6 * entries);
    hess_path.resize(n);
  } else {
    hess.clear();
  }
  options_ = options;
  options_.gradients = true;
  second_ = second;
  x_ = x;
  support_radius_ = support_radius;
  return old_rows_done;
}

bool ShapeCache::row_due(std::int64_t p) const {
  const double* xp = x_ + 3 * p;
  const double lim = reuse_tolerance * support_radius_[p], lim2 = lim * lim;
  const std::int32_t* cand = candidates.row(p);
  const std::int64_t ncand = candidates.count(p), b = lazy_offsets_[p];
  const std::int32_t* nodes = lazy_nodes_.data() + b;
  const float* built = built_offset_.data() + 3 * b;
  const std::int64_t size = lazy_size_[p];
  // Both lists ascend (the search's order), so one merge walk pairs the row's nodes with candidates.
  std::int64_t m = 0;
  for (std::int64_t k = 0; k < ncand; ++k) {
    const std::int32_t j = cand[k];
    const double* xj = x_ + 3 * static_cast<std::int64_t>(j);
    const double r[3] = {xj[0] - xp[0], xj[1] - xp[1], xj[2] - xp[2]};
    if (m < size && nodes[m] == j) {  // a node of the row: has it moved relative to the point?
      const double e0 = r[0] - built[3 * m], e1 = r[1] - built[3 * m + 1], e2 = r[2] - built[3 * m + 2];
      if (!(e0 * e0 + e1 * e1 + e2 * e2 <= lim2)) return true;  // (a non-finite position too)
      ++m;
    } else {  // outside the support at the build: has it come in by more than the tolerance?
      const double inner = support_radius_[j] - lim;
      if (!(r[0] * r[0] + r[1] * r[1] + r[2] * r[2] >= inner * inner)) return true;
    }
  }
  return m < size;  // a node no longer among the candidates (searched again since) has moved far
}

bool ShapeCache::covers(std::int64_t p, std::int32_t j, double* r) const {
  const double* xp = x_ + 3 * p;
  const double* xj = x_ + 3 * static_cast<std::int64_t>(j);
  for (int d = 0; d < 3; ++d) r[d] = xj[d] - xp[d];
  return r[0] * r[0] + r[1] * r[1] + r[2] * r[2] < support_radius_[j] * support_radius_[j];
}

std::int64_t ShapeCache::members_now(std::int64_t p) const {
  const std::int32_t* cand = candidates.row(p);
  const std::int64_t ncand = candidates.count(p);
  std::int64_t members = 0;
  double r[3];
  for (std::int64_t k = 0; k < ncand; ++k) members += covers(p, cand[k], r) ? 1 : 0;
  return members;
}

double* ShapeCache::thread_scratch() {
#pragma omp single
  if (!keep_psi) resize_with_headroom(psi, static_cast<std::size_t>(team_size() * longest_));
  // (the implicit barrier of single: psi has its final address)
  return keep_psi ? nullptr : psi.data() + team_index() * longest_;
}

void ShapeCache::build_row(std::int64_t p, double* scratch) {
  if (lazy()) {
    if (!due_[p]) return;  // kept: still within the tolerance of the configuration it was built in
    // The row's nodes: its candidates that cover x_p now (the search's own test), and where they are.
    const std::int64_t b = lazy_offsets_[p], ncand = candidates.count(p);
    const std::int32_t* cand = candidates.row(p);
    std::int32_t* nodes = lazy_nodes_.data() + b;
    float* built = built_offset_.data() + 3 * b;
    std::int32_t size = 0;
    double r[3];
    for (std::int64_t k = 0; k < ncand; ++k) {
      const std::int32_t j = cand[k];
      if (covers(p, j, r)) {
        for (int d = 0; d < 3; ++d) built[3 * size + d] = static_cast<float>(r[d]);
        nodes[size++] = j;
      }
    }
    lazy_size_[p] = size;
  }
  const std::int64_t b = row_begin(p);
  const std::int32_t* row = row_nodes(p);
  const int count = static_cast<int>(row_size(p));
  double* values = keep_psi ? psi.data() + b : scratch;
  if (second_) {
    hess_path[p] = shape_and_second_gradients(options_, *second_, x_ + 3 * p, x_, support_radius_, row, count, values,
                                              grad.data() + 3 * b, hess.data() + 6 * b, info[p]);
  } else {
    info[p] = shape_gradients(options_, x_ + 3 * p, x_, support_radius_, row, count, values, grad.data() + 3 * b);
  }
}

bool ShapeCache::update_candidates(const double* x, const double* support_radius, std::size_t n) {
  const std::int64_t nq = static_cast<std::int64_t>(n);
  bool valid = candidate_x.size() == 3 * n && candidates.size() == n;
  double s = 0.0;
  if (valid) {
    for (std::size_t i = 0; i < n && valid; ++i) valid = candidate_support[i] == support_radius[i];
  }
  if (n > 0) {
    double a_min = support_radius[0];
    for (std::size_t i = 1; i < n; ++i) a_min = std::min(a_min, support_radius[i]);
    s = skin * a_min;
  }
  if (valid) {
    double moved2 = 0.0;
#pragma omp parallel for schedule(static) reduction(max : moved2) if (nq >= kParallelMinParticles)
    for (std::int64_t i = 0; i < nq; ++i) {
      double d2 = 0.0;
      for (int d = 0; d < 3; ++d) d2 += (x[3 * i + d] - candidate_x[3 * i + d]) * (x[3 * i + d] - candidate_x[3 * i + d]);
      if (!(d2 < HUGE_VAL)) d2 = HUGE_VAL;  // a non-finite position forces a search (which rejects it)
      moved2 = std::max(moved2, d2);
    }
    // |x_L - x_J| >= |x0_L - x0_J| - 2 max|x - x0|: every J covering x_L was a candidate.
    valid = 4.0 * moved2 <= s * s;
  }
  if (!valid) {
    inflated_support.resize(n);
    for (std::size_t i = 0; i < n; ++i) inflated_support[i] = support_radius[i] + s;
    candidate_search.search(x, support_radius, inflated_support.data(), s, n, candidates, workspace);
    candidate_x.assign(x, x + 3 * n);
    candidate_support.assign(support_radius, support_radius + n);
    const std::size_t entries = candidates.indices.size();
    if (candidates.indices.capacity() < entries + entries / 10) candidates.indices.reserve(entries + entries / 4);
    for (auto& block : workspace.blocks)
      if (block.capacity() < block.size() + block.size() / 10) block.reserve(block.size() + block.size() / 4);
    ++searches;
  } else {
    ++reuses;
  }
  return !valid;
}

void ShapeCache::find_with_skin(const double* x, const double* support_radius, std::size_t n) {
  const std::int64_t nq = static_cast<std::int64_t>(n);
  update_candidates(x, support_radius, n);
  // Filter each candidate row into `filtered` (same offsets), then compact into `support`.
  const std::size_t centries = candidates.indices.size();
  if (filtered.capacity() < centries) filtered.reserve(centries + centries / 4);
  filtered.resize(centries);
  support.offsets.resize(n + 1);
  support.offsets[0] = 0;
#pragma omp parallel for schedule(static) if (nq >= kParallelMinParticles)
  for (std::int64_t i = 0; i < nq; ++i) {
    support.offsets[i + 1] = covering_nodes(x + 3 * i, candidates.row(i), candidates.count(i), x, support_radius,
                                            filtered.data() + candidates.begin(i), [](std::int32_t) { return true; });
  }
  for (std::size_t i = 0; i < n; ++i) support.offsets[i + 1] += support.offsets[i];
  const std::size_t entries = static_cast<std::size_t>(support.offsets[n]);
  if (support.indices.capacity() < entries) support.indices.reserve(entries + entries / 4);
  support.indices.resize(entries);
#pragma omp parallel for schedule(static) if (nq >= kParallelMinParticles)
  for (std::int64_t i = 0; i < nq; ++i)
    std::copy(filtered.data() + candidates.begin(i), filtered.data() + candidates.begin(i) + support.count(i),
              support.indices.data() + support.begin(i));
}

// The record: its length in doubles, the slot, the size, info (path, basis, rcond), hess_path, then the
// nodes' ids, their build offsets (3 floats as doubles: exact), the gradients (3) and the second
// gradients (6, when kept) of every entry.
std::size_t ShapeCache::row_record_length(std::size_t p) const {
  if (!lazy()) throw std::logic_error("ShapeCache::row_record_length: for lazy rows");
  return static_cast<std::size_t>(7 + lazy_size_[p] * (has_second_gradients() ? 13 : 7));
}

double* ShapeCache::write_row(std::size_t p, const std::uint32_t* ids, double* out) const {
  const std::int64_t b = lazy_offsets_[p], size = lazy_size_[p];
  *out++ = static_cast<double>(row_record_length(p));
  *out++ = static_cast<double>(lazy_offsets_[p + 1] - b);
  *out++ = static_cast<double>(size);
  *out++ = static_cast<double>(static_cast<int>(info[p].path));
  *out++ = static_cast<double>(static_cast<int>(info[p].basis));
  *out++ = info[p].rcond;
  *out++ = has_second_gradients() ? static_cast<double>(static_cast<int>(hess_path[p])) : 0.0;
  for (std::int64_t k = 0; k < size; ++k) *out++ = static_cast<double>(ids[lazy_nodes_[b + k]]);
  out = std::copy(built_offset_.begin() + 3 * b, built_offset_.begin() + 3 * (b + size), out);
  out = std::copy(grad.begin() + 3 * b, grad.begin() + 3 * (b + size), out);
  if (has_second_gradients()) out = std::copy(hess.begin() + 6 * b, hess.begin() + 6 * (b + size), out);
  return out;
}

void ShapeCache::install_rows(std::size_t n, const std::vector<const double*>& records,
                              const std::function<std::int32_t(std::uint32_t)>& local_of,
                              const SecondGradientOptions* second) {
  if (!lazy() || records.size() != n) throw std::logic_error("ShapeCache::install_rows: lazy rows, one record a point");
  const bool keeps = std::find(records.begin(), records.end(), nullptr) != records.end();
  if (keeps && (!has_rows(n) || (second != nullptr) != (second_ != nullptr)))
    throw std::logic_error("ShapeCache::install_rows: a row kept where there is none of its kind");
  // The new table beside the old one, so that a kept row is copied straight from it.
  std::vector<std::int64_t> offsets(n + 1, 0);
  for (std::size_t p = 0; p < n; ++p)
    offsets[p + 1] = offsets[p] + (records[p] ? static_cast<std::int64_t>(records[p][1]) : lazy_offsets_[p + 1] - lazy_offsets_[p]);
  const std::size_t slots = static_cast<std::size_t>(offsets[n]);
  std::vector<std::int32_t> nodes(slots, 0), sizes(n, 0);
  std::vector<float> built_offset(3 * slots, 0.0f);
  std::vector<double> g(3 * slots, 0.0), h(second ? 6 * slots : 0, 0.0);
  std::vector<rk::PointResult> infos(n);
  std::vector<SecondGradientPath> paths(second ? n : 0, SecondGradientPath::Empty);
  for (std::size_t p = 0; p < n; ++p) {
    const double* r = records[p];
    const std::int64_t b = offsets[p];
    if (!r) {  // kept: its slot, nodes and values as they are
      const std::int64_t from = lazy_offsets_[p], size = lazy_size_[p];
      std::copy(lazy_nodes_.begin() + from, lazy_nodes_.begin() + from + size, nodes.begin() + b);
      std::copy(built_offset_.begin() + 3 * from, built_offset_.begin() + 3 * (from + size), built_offset.begin() + 3 * b);
      std::copy(grad.begin() + 3 * from, grad.begin() + 3 * (from + size), g.begin() + 3 * b);
      if (second) std::copy(hess.begin() + 6 * from, hess.begin() + 6 * (from + size), h.begin() + 6 * b);
      sizes[p] = static_cast<std::int32_t>(size);
      infos[p] = info[p];
      if (second) paths[p] = hess_path[p];
      continue;
    }
    const std::int64_t size = static_cast<std::int64_t>(r[2]);
    const double* ids = r + 7;
    bool whole = true;
    for (std::int64_t k = 0; k < size && whole; ++k) {
      const std::int32_t j = local_of(static_cast<std::uint32_t>(ids[k]));
      whole = j >= 0;
      nodes[b + k] = j;
    }
    if (!whole) continue;  // empty: made again when next due
    sizes[p] = static_cast<std::int32_t>(size);
    infos[p] = {static_cast<rk::Path>(static_cast<int>(r[3])), static_cast<rk::Basis>(static_cast<int>(r[4])), r[5]};
    if (second) paths[p] = static_cast<SecondGradientPath>(static_cast<int>(r[6]));
    const double* built = ids + size;
    const double* gr = built + 3 * size;
    for (std::int64_t e = 0; e < 3 * size; ++e) {
      built_offset[3 * b + e] = static_cast<float>(built[e]);
      g[3 * b + e] = gr[e];
    }
    if (second) std::copy(gr + 3 * size, gr + 9 * size, h.begin() + 6 * b);
  }
  lazy_offsets_ = std::move(offsets);
  lazy_nodes_ = std::move(nodes);
  lazy_size_ = std::move(sizes);
  built_offset_ = std::move(built_offset);
  grad = std::move(g);
  hess = std::move(h);
  info = std::move(infos);
  hess_path = std::move(paths);
  due_.assign(n, 0);
  second_ = second;
  longest_ = 0;
}

std::size_t ShapeCache::count(rk::Path path) const {
  return static_cast<std::size_t>(
      std::count_if(info.begin(), info.end(), [path](const rk::PointResult& r) { return r.path == path; }));
}

std::size_t ShapeCache::fragments() const {
  std::size_t k = 0;
  for (std::size_t p = 0; p < info.size(); ++p) k += fragment(p) ? 1 : 0;
  return k;
}

std::size_t ShapeCache::count(SecondGradientPath path) const {
  if (hess.empty()) return 0;
  return static_cast<std::size_t>(std::count(hess_path.begin(), hess_path.end(), path));
}

}  // namespace uhpc::macro
