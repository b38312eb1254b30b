#include "field_transfer.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

#include <Eigen/SparseCholesky>

namespace uhpc::micro {

namespace {

// The coefficients by (crack, node): standard ones as they are, enriched ones whose (crack, node)
// the old model had, new ones 0.
Eigen::VectorXd carried(const RkGalerkinModel& base, const EnrichedModel& from, const Eigen::VectorXd& d_from,
                        const EnrichedModel& to) {
  const std::size_t n = base.node_count();
  const auto key = [n](std::int32_t crack, std::int32_t node) {
    return static_cast<std::int64_t>(crack) * static_cast<std::int64_t>(n) + node;
  };
  Eigen::VectorXd d = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(to.dof_count()));
  d.head(static_cast<Eigen::Index>(2 * n)) = d_from.head(static_cast<Eigen::Index>(2 * n));
  std::unordered_map<std::int64_t, std::size_t> old;
  for (std::size_t k = 0; k < from.enriched_node.size(); ++k) old[key(from.enriched_crack[k], from.enriched_node[k])] = k;
  for (std::size_t k = 0; k < to.enriched_node.size(); ++k) {
    const auto it = old.find(key(to.enriched_crack[k], to.enriched_node[k]));
    if (it != old.end())
      d.segment(static_cast<Eigen::Index>(2 * (n + k)), 2) = d_from.segment(static_cast<Eigen::Index>(2 * (n + it->second)), 2);
  }
  return d;
}

// The field of coefficients d at the domain points of em.
std::vector<double> domain_displacement(const EnrichedModel& em, const Eigen::VectorXd& d) {
  const GeneralTable& t = em.domain;
  std::vector<double> u(2 * t.size(), 0.0);
  for (std::size_t p = 0; p < t.size(); ++p)
    for (std::int64_t e = t.support.begin(p); e < t.support.end(p); ++e) {
      const std::int32_t g = t.support.indices[static_cast<std::size_t>(e)];
      u[2 * p] += t.psi[static_cast<std::size_t>(e)] * d[2 * g];
      u[2 * p + 1] += t.psi[static_cast<std::size_t>(e)] * d[2 * g + 1];
    }
  return u;
}

}  // namespace

Eigen::VectorXd transfer_field(const RkGalerkinModel& base, const EnrichedModel& from,
                               const std::vector<Crack>& from_cracks, const Eigen::VectorXd& d_from,
                               const EnrichedModel& to, FieldTransfer method, TransferReport* report) {
  Eigen::VectorXd d = carried(base, from, d_from, to);
  TransferReport rep;
  if (method == FieldTransfer::Carry) {
    if (report) *report = rep;
    return d;
  }
  const GeneralTable& t = to.domain;
  const std::vector<double> u_old = enriched_displacement(base, from, from_cracks, t, to.x, d_from);
  const std::vector<double> u_new = domain_displacement(to, d);
  const std::size_t points = t.size();
  std::vector<double> delta(2 * points);
  double u_max = 0.0;
  for (std::size_t p = 0; p < points; ++p) {
    delta[2 * p] = u_old[2 * p] - u_new[2 * p];
    delta[2 * p + 1] = u_old[2 * p + 1] - u_new[2 * p + 1];
    u_max = std::max(u_max, std::hypot(u_old[2 * p], u_old[2 * p + 1]));
  }
  // Below this the two sums differ by their order only.
  const double round_off = 1e-10 * u_max;
  std::vector<std::int32_t> local(to.gnode_count(), -1);
  std::int32_t unknowns = 0;
  for (std::size_t p = 0; p < points; ++p) {
    const double miss = std::hypot(delta[2 * p], delta[2 * p + 1]);
    rep.missed_m = std::max(rep.missed_m, miss);
    if (miss <= round_off) {
      delta[2 * p] = delta[2 * p + 1] = 0.0;
      continue;
    }
    for (std::int64_t e = t.support.begin(p); e < t.support.end(p); ++e) {
      std::int32_t& l = local[static_cast<std::size_t>(t.support.indices[static_cast<std::size_t>(e)])];
      if (l < 0) l = unknowns++;
    }
  }
  if (unknowns == 0) {
    if (report) *report = rep;
    return d;
  }

  // M c = b over the unknowns: M_ab = sum_p w psi_a psi_b, b_a = sum_p w psi_a delta, over every point
  // whose row has an unknown (the points where delta is 0 hold the correction down there).
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(unknowns, 2);
  std::vector<std::size_t> used;
  std::vector<std::pair<std::int32_t, double>> row;
  for (std::size_t p = 0; p < points; ++p) {
    row.clear();
    for (std::int64_t e = t.support.begin(p); e < t.support.end(p); ++e) {
      const std::int32_t l = local[static_cast<std::size_t>(t.support.indices[static_cast<std::size_t>(e)])];
      if (l >= 0) row.emplace_back(l, t.psi[static_cast<std::size_t>(e)]);
    }
    if (row.empty()) continue;
    used.push_back(p);
    const double w = to.weight[p];
    for (const auto& [a, pa] : row) {
      b(a, 0) += w * pa * delta[2 * p];
      b(a, 1) += w * pa * delta[2 * p + 1];
      for (const auto& [c, pc] : row)
        if (c <= a) entries.emplace_back(a, c, w * pa * pc);
    }
  }
  Eigen::SparseMatrix<double> M(unknowns, unknowns);
  M.setFromTriplets(entries.begin(), entries.end());
  // Jacobi scaling (enriched functions that barely enter a support have tiny norms) and a relative
  // 1e-12 on the diagonal, so that nearly dependent functions cannot make the correction large.
  Eigen::VectorXd s = M.diagonal();
  for (Eigen::Index k = 0; k < unknowns; ++k) s[k] = s[k] > 0.0 ? 1.0 / std::sqrt(s[k]) : 1.0;
  M = s.asDiagonal() * M * s.asDiagonal();
  for (Eigen::Index k = 0; k < unknowns; ++k) M.coeffRef(k, k) += 1e-12;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower> ldlt(M);
  if (ldlt.info() != Eigen::Success) throw std::logic_error("field transfer: the projection's mass matrix is not positive definite");
  const Eigen::MatrixXd c = s.asDiagonal() * ldlt.solve(s.asDiagonal() * b);

  for (std::size_t g = 0; g < local.size(); ++g)
    if (local[g] >= 0) {
      d[static_cast<Eigen::Index>(2 * g)] += c(local[g], 0);
      d[static_cast<Eigen::Index>(2 * g + 1)] += c(local[g], 1);
    }
  for (const std::size_t p : used) {
    double r[2] = {delta[2 * p], delta[2 * p + 1]};
    for (std::int64_t e = t.support.begin(p); e < t.support.end(p); ++e) {
      const std::int32_t l = local[static_cast<std::size_t>(t.support.indices[static_cast<std::size_t>(e)])];
      if (l < 0) continue;
      r[0] -= t.psi[static_cast<std::size_t>(e)] * c(l, 0);
      r[1] -= t.psi[static_cast<std::size_t>(e)] * c(l, 1);
    }
    rep.residual_m = std::max(rep.residual_m, std::hypot(r[0], r[1]));
  }
  rep.projected_gnodes = static_cast<std::size_t>(unknowns);
  if (report) *report = rep;
  return d;
}

}  // namespace uhpc::micro
