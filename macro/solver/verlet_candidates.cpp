#include "solver/verlet_candidates.hpp"
#include "solver/parallel.hpp"

#include <algorithm>
#include <cstdint>

namespace uhpc::macro {

namespace {
// Beyond this share of fast particles a new outer search is cheaper than searching for them.
constexpr std::size_t kMaxFastShare = 8;  // 1/8 of the particles

template <class T>
void resize_with_headroom(std::vector<T>& v, std::size_t size) {
  if (v.capacity() < size) v.reserve(size + size / 4);
  v.resize(size);
}
}  // namespace

bool VerletCandidates::outer_valid(const double* x, const double* support, double s, std::size_t n) {
  if (outer_.size() != n || outer_x_.size() != 3 * n || !(outer_s_ == s)) return false;
  for (std::size_t i = 0; i < n; ++i)
    if (!(outer_support_[i] == support[i])) return false;
  // Fast: moved more than s/2 since the outer search (a hair less, against round-off in the bound).
  const double t = 0.5 * s * (1.0 - 1e-9), t2 = t * t;
  const std::int64_t nq = static_cast<std::int64_t>(n);
  fast_index_.resize(n);
  std::size_t count = 0;
#pragma omp parallel for schedule(static) reduction(+ : count) if (nq >= kParallelMinParticles)
  for (std::int64_t i = 0; i < nq; ++i) {
    double d2 = 0.0;
    for (int d = 0; d < 3; ++d) d2 += (x[3 * i + d] - outer_x_[3 * i + d]) * (x[3 * i + d] - outer_x_[3 * i + d]);
    const bool fast = !(d2 <= t2);  // (a non-finite position too)
    fast_index_[i] = fast ? 1 : -1;
    count += fast ? 1 : 0;
  }
  if (count > n / kMaxFastShare) return false;
  fast_.clear();
  for (std::size_t i = 0; i < n; ++i)
    if (fast_index_[i] >= 0) {
      fast_index_[i] = static_cast<std::int32_t>(fast_.size());
      fast_.push_back(static_cast<std::int32_t>(i));
    }
  return true;
}

void VerletCandidates::outer_search(const double* x, const double* support, double s, std::size_t n,
                                    NeighbourWorkspace<3>& workspace) {
  outer_radius_.resize(n);
  for (std::size_t i = 0; i < n; ++i) outer_radius_[i] = support[i] + 2.0 * s;
  nodes_covering<3>(x, n, x, outer_radius_.data(), n, outer_, workspace);
  if (outer_.indices.capacity() < outer_.indices.size() + outer_.indices.size() / 10)
    outer_.indices.reserve(outer_.indices.size() + outer_.indices.size() / 4);
  outer_x_.assign(x, x + 3 * n);
  outer_support_.assign(support, support + n);
  outer_s_ = s;
  fast_.clear();
  fast_index_.assign(n, -1);
  // The fast searches' memory at its largest (n / kMaxFastShare fast particles, rows no longer than the
  // outer ones), so that the partial searches until the next outer one allocate nothing.
  std::int64_t longest = 0;
  for (std::size_t i = 0; i < n; ++i) longest = std::max(longest, outer_.count(i));
  const std::size_t most = n / kMaxFastShare + 1, entries = most * static_cast<std::size_t>(longest);
  fast_.reserve(most);
  fast_x_.reserve(3 * most);
  fast_radius_.reserve(most);
  fast_rows_.offsets.reserve(most + 1);
  fast_rows_.indices.reserve(entries);
  fast_covering_.offsets.reserve(n + 1);
  fast_covering_.indices.reserve(2 * entries);  // (graded supports: a node may cover more points than its row holds)
  ++outer_searches;
}

void VerletCandidates::search(const double* x, const double* support, const double* radius, double s, std::size_t n,
                              NeighbourList& out, NeighbourWorkspace<3>& workspace) {
  if (outer_valid(x, support, s, n)) {
    ++partial_searches;
  } else {
    outer_search(x, support, s, n, workspace);
  }
  fast_particles = fast_.size();
  const std::size_t nf = fast_.size();
  if (nf > 0) {
    resize_with_headroom(fast_x_, 3 * nf);
    resize_with_headroom(fast_radius_, nf);
    for (std::size_t k = 0; k < nf; ++k) {
      const std::size_t j = static_cast<std::size_t>(fast_[k]);
      for (int d = 0; d < 3; ++d) fast_x_[3 * k + d] = x[3 * j + d];
      fast_radius_[k] = radius[j];
    }
    // The search's own test in both (d^2 < r_j^2, d^2 summed over the axes in order).
    nodes_covering<3>(x, n, fast_x_.data(), fast_radius_.data(), nf, fast_covering_, workspace);
    nodes_covering<3>(fast_x_.data(), nf, x, radius, n, fast_rows_, workspace);
  }
  // Pass 1: each slow row's outer candidates within r_j now (fast nodes left to fast_covering_), in
  // place in filtered_; the row lengths.
  const std::int64_t nq = static_cast<std::int64_t>(n);
  resize_with_headroom(filtered_, outer_.indices.size());
  out.offsets.resize(n + 1);
  out.offsets[0] = 0;
#pragma omp parallel for schedule(static) if (nq >= kParallelMinParticles)
  for (std::int64_t p = 0; p < nq; ++p) {
    if (nf > 0 && fast_index_[p] >= 0) {
      out.offsets[p + 1] = fast_rows_.count(static_cast<std::size_t>(fast_index_[p]));
      continue;
    }
    const std::int64_t m = covering_nodes(x + 3 * p, outer_.row(p), outer_.count(p), x, radius,
                                          filtered_.data() + outer_.begin(p),
                                          [&](std::int32_t j) { return nf == 0 || fast_index_[j] < 0; });  // slow nodes
    out.offsets[p + 1] = m + (nf > 0 ? fast_covering_.count(static_cast<std::size_t>(p)) : 0);
  }
  // (filtered rows hold m entries: the row length minus the fast nodes)
  for (std::size_t p = 0; p < n; ++p) out.offsets[p + 1] += out.offsets[p];
  resize_with_headroom(out.indices, static_cast<std::size_t>(out.offsets[n]));
  // Pass 2: fast rows copied, slow rows merged with their fast nodes (both ascending).
#pragma omp parallel for schedule(static) if (nq >= kParallelMinParticles)
  for (std::int64_t p = 0; p < nq; ++p) {
    std::int32_t* dst = out.indices.data() + out.offsets[p];
    if (nf > 0 && fast_index_[p] >= 0) {
      const std::size_t k = static_cast<std::size_t>(fast_index_[p]);
      std::copy(fast_rows_.row(k), fast_rows_.row(k) + fast_rows_.count(k), dst);
      continue;
    }
    const std::int64_t nfast = nf > 0 ? fast_covering_.count(static_cast<std::size_t>(p)) : 0;
    const std::int32_t* slow = filtered_.data() + outer_.begin(p);
    const std::int64_t nslow = out.offsets[p + 1] - out.offsets[p] - nfast;
    if (nfast == 0) {
      std::copy(slow, slow + nslow, dst);
      continue;
    }
    const std::int32_t* local = fast_covering_.row(static_cast<std::size_t>(p));
    std::int64_t a = 0, b = 0;
    while (a < nslow || b < nfast) {
      const std::int32_t fb = b < nfast ? fast_[static_cast<std::size_t>(local[b])] : INT32_MAX;
      if (a < nslow && slow[a] < fb) *dst++ = slow[a++];
      else {
        *dst++ = fb;
        ++b;
      }
    }
  }
}

}  // namespace uhpc::macro
