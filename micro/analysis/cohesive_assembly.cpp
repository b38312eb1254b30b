#include "cohesive_assembly.hpp"

#include <algorithm>

#include "stiffness_assembly.hpp"

namespace uhpc::micro {

namespace {

// node -> (point, entry) incidence of a table (its transpose), as in stiffness_assembly.cpp, over
// generalized nodes.
struct Incidence {
  std::vector<std::int64_t> start, entry;
  std::vector<std::int32_t> point;  // point of each entry
};

Incidence transpose(const NeighbourList& s, std::size_t n) {
  Incidence inc;
  inc.start.assign(n + 1, 0);
  for (std::int32_t i : s.indices) ++inc.start[i + 1];
  for (std::size_t i = 0; i < n; ++i) inc.start[i + 1] += inc.start[i];
  inc.entry.resize(s.indices.size());
  std::vector<std::int64_t> fill(inc.start.begin(), inc.start.end() - 1);
  for (std::size_t e = 0; e < s.indices.size(); ++e) inc.entry[fill[s.indices[e]]++] = static_cast<std::int64_t>(e);
  inc.point.resize(s.indices.size());
  for (std::size_t q = 0; q < s.size(); ++q)
    for (std::int64_t e = s.begin(q); e < s.end(q); ++e) inc.point[e] = static_cast<std::int32_t>(q);
  return inc;
}

}  // namespace

FractureSystem::FractureSystem(const RkGalerkinModel& base, const EnrichedModel& em, const ElasticProblem& unit_problem,
                               BoundaryPart far, int axis)
    : base_(base), em_(em), problem_(unit_problem), far_(far), axis_(axis), D_(unit_problem.material.D()) {
  const std::size_t n = em.gnode_count();
  // Cohesive couplings as one more "table": the jump nodes of each cohesive point.
  NeighbourList coh;
  for (const CohesivePoint& p : em.cohesive) {
    coh.indices.insert(coh.indices.end(), em.jump_node.begin() + p.begin, em.jump_node.begin() + p.end);
    coh.offsets.push_back(static_cast<std::int64_t>(coh.indices.size()));
  }
  const std::vector<const NeighbourList*> lists = {&em.domain.support, &em.boundary.support, &em.constraints.support,
                                                   &coh};
  std::vector<Incidence> inc;
  for (const NeighbourList* l : lists) inc.push_back(transpose(*l, n));
  node_start_.assign(n + 1, 0);
  std::vector<std::int32_t> mark(n, -1), column;
  for (std::size_t j = 0; j < n; ++j) {
    column.clear();
    for (std::size_t s = 0; s < lists.size(); ++s)
      for (std::int64_t k = inc[s].start[j]; k < inc[s].start[j + 1]; ++k) {
        const std::int32_t q = inc[s].point[inc[s].entry[k]];
        for (std::int64_t e = lists[s]->begin(q); e < lists[s]->end(q); ++e) {
          const std::int32_t i = lists[s]->indices[e];
          if (mark[i] != static_cast<std::int32_t>(j)) {
            mark[i] = static_cast<std::int32_t>(j);
            column.push_back(i);
          }
        }
      }
    std::sort(column.begin(), column.end());
    node_rows_.insert(node_rows_.end(), column.begin(), column.end());
    node_start_[j + 1] = static_cast<std::int64_t>(node_rows_.size());
  }
  col_start_.assign(2 * n + 1, 0);
  for (std::size_t j = 0; j < n; ++j) {
    const int len = static_cast<int>(2 * (node_start_[j + 1] - node_start_[j]));
    col_start_[2 * j + 1] = col_start_[2 * j] + len;
    col_start_[2 * j + 2] = col_start_[2 * j + 1] + len;
  }
  rows_.resize(static_cast<std::size_t>(col_start_.back()));
  for (std::size_t j = 0; j < n; ++j)
    for (int c = 0; c < 2; ++c) {
      int at = col_start_[2 * j + c];
      for (std::int64_t k = node_start_[j]; k < node_start_[j + 1]; ++k) {
        rows_[at++] = 2 * node_rows_[k];
        rows_[at++] = 2 * node_rows_[k] + 1;
      }
    }
  lin_.assign(rows_.size(), 0.0);
  f_unit_ = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(2 * n));

  // Domain: column j (trial gnode) in parallel; test functions on the rows.
  const GeneralTable& t = em.domain;
  const Incidence& dinc = inc[0];
#pragma omp parallel
  {
    std::vector<std::int32_t> local(n, -1);
#pragma omp for schedule(dynamic, 64)
    for (std::int64_t jj = 0; jj < static_cast<std::int64_t>(n); ++jj) {
      const auto j = static_cast<std::int32_t>(jj);
      for (std::int64_t k = node_start_[j]; k < node_start_[j + 1]; ++k)
        local[node_rows_[k]] = static_cast<std::int32_t>(k - node_start_[j]);
      double* col[2] = {lin_.data() + col_start_[2 * j], lin_.data() + col_start_[2 * j + 1]};
      for (std::int64_t a = dinc.start[j]; a < dinc.start[j + 1]; ++a) {
        const std::int64_t ej = dinc.entry[a];
        const std::int32_t q = dinc.point[ej];
        const double w = em.weight[q];
        const std::array<double, 3> s[2] = {apply_D(D_, unit_strain(0, &t.grad[2 * ej])),
                                            apply_D(D_, unit_strain(1, &t.grad[2 * ej]))};
        for (std::int64_t e = t.support.begin(q); e < t.support.end(q); ++e) {
          const double* g = &t.test_grad[2 * e];
          const std::int32_t pos = 2 * local[t.support.indices[e]];
          for (int c = 0; c < 2; ++c) {
            col[c][pos] += w * (g[0] * s[c][0] + g[1] * s[c][2]);
            col[c][pos + 1] += w * (g[1] * s[c][1] + g[0] * s[c][2]);
          }
        }
      }
    }
  }

  // Nitsche terms on the prescribed faces (the same formulas as stiffness_assembly.cpp, on the
  // enriched functions too, since a crack may reach a loaded face).
  const GeneralTable& bt = em.boundary;
  std::vector<std::array<double, 4>> T;
  for (std::size_t p = 0; p < bt.size(); ++p) {
    const std::size_t s = static_cast<std::size_t>(base.boundary.segment[p]);
    const BoundarySegment& seg = base.segments[s];
    const BoundaryCondition& bc = problem_.boundary[static_cast<int>(seg.part)];
    if (!bc.prescribed[0] && !bc.prescribed[1]) continue;  // free faces and pores: traction free
    const double* x = &base.boundary.x[2 * p];
    const double w = base.boundary.weight[p];
    const std::int64_t b0 = bt.support.begin(p), b1 = bt.support.end(p);
    const double P[2] = {bc.prescribed[0] ? 1.0 : 0.0, bc.prescribed[1] ? 1.0 : 0.0};
    const std::array<double, 2> g = bc.displacement(x);
    const double beta = nitsche_beta(base, problem_, s);
    T.resize(static_cast<std::size_t>(b1 - b0));
    for (std::int64_t e = b0; e < b1; ++e)
      for (int k = 0; k < 2; ++k) {
        const std::array<double, 2> tr = traction(apply_D(D_, unit_strain(k, &bt.grad[2 * e])), seg.normal.data());
        T[e - b0][k] = tr[0];
        T[e - b0][2 + k] = tr[1];
      }
    for (int r = 0; r < 2; ++r) k_lambda_ += w * beta * P[r] * g[static_cast<std::size_t>(r)] * g[static_cast<std::size_t>(r)];
    for (std::int64_t ei = b0; ei < b1; ++ei) {
      const std::int32_t i = bt.support.indices[ei];
      const double* Ti = T[ei - b0].data();
      for (int r = 0; r < 2; ++r)
        f_unit_[2 * i + r] += w * (-(Ti[r] * P[0] * g[0] + Ti[2 + r] * P[1] * g[1]) + beta * bt.psi[ei] * P[r] * g[r]);
      for (std::int64_t ej = b0; ej < b1; ++ej) {
        const std::int32_t j = bt.support.indices[ej];
        const double* Tj = T[ej - b0].data();
        double blk[2][2];
        for (int r = 0; r < 2; ++r)
          for (int k = 0; k < 2; ++k)
            blk[r][k] = w * (-bt.psi[ei] * P[r] * Tj[2 * r + k] - Ti[2 * k + r] * P[k] * bt.psi[ej] +
                             (r == k ? beta * bt.psi[ei] * bt.psi[ej] * P[r] : 0.0));
        add_block(lin_, i, j, blk);
      }
    }
  }
  // Point penalties (homogeneous: the rigid transverse translation only).
  const double penalty = problem_.nitsche_factor * problem_.material.plane_modulus_Pa();
  const GeneralTable& ct = em.constraints;
  for (std::size_t p = 0; p < problem_.points.size(); ++p) {
    const int c = problem_.points[p].component;
    for (std::int64_t ei = ct.support.begin(p); ei < ct.support.end(p); ++ei)
      for (std::int64_t ej = ct.support.begin(p); ej < ct.support.end(p); ++ej) {
        double blk[2][2] = {{0.0, 0.0}, {0.0, 0.0}};
        blk[c][c] = penalty * ct.psi[ei] * ct.psi[ej];
        add_block(lin_, ct.support.indices[ei], ct.support.indices[ej], blk);
      }
  }
  values_ = lin_;
}

void FractureSystem::add_block(std::vector<double>& v, std::int32_t i, std::int32_t j, const double b[2][2]) const {
  const auto first = node_rows_.begin() + node_start_[j], last = node_rows_.begin() + node_start_[j + 1];
  const std::int64_t k = std::lower_bound(first, last, i) - first;
  for (int c = 0; c < 2; ++c)
    for (int r = 0; r < 2; ++r) v[col_start_[2 * j + c] + 2 * k + r] += b[r][c];
}

void FractureSystem::evaluate(const Eigen::VectorXd& d, double lambda, const CohesiveLaw& law,
                              const std::vector<CohesiveHistory>& committed, bool tangent, Eigen::VectorXd& residual,
                              CohesiveEvaluation& eval, const OpeningViscosity* viscosity) {
  const auto N = static_cast<Eigen::Index>(dofs());
  const Eigen::Map<const Eigen::SparseMatrix<double>> K(N, N, static_cast<Eigen::Index>(lin_.size()), col_start_.data(),
                                                        rows_.data(), lin_.data());
  residual = K * d - lambda * f_unit_;
  if (tangent) values_ = lin_;
  const std::size_t m = em_.cohesive.size();
  eval.trial.resize(m);
  eval.opening.resize(m);
  eval.traction.resize(m);
  for (std::size_t p = 0; p < m; ++p) {
    const CohesivePoint& q = em_.cohesive[p];
    double jump[2] = {0.0, 0.0};
    for (std::int64_t e = q.begin; e < q.end; ++e) {
      const std::int32_t g = em_.jump_node[e];
      jump[0] += em_.jump_coefficient[e] * d[2 * g];
      jump[1] += em_.jump_coefficient[e] * d[2 * g + 1];
    }
    const double n[2] = {q.normal[0], q.normal[1]};
    const double s[2] = {n[1], -n[0]};  // the segment direction
    const double wn = n[0] * jump[0] + n[1] * jump[1], wt = s[0] * jump[0] + s[1] * jump[1];
    const CohesiveResponse r = cohesive_response(law, wn, wt, committed[p].kappa);
    eval.opening[p] = {wn, wt};
    eval.traction[p] = r.t;
    eval.trial[p] = committed[p];
    if (r.kappa > committed[p].kappa && law.mode == CohesiveMode::ModeI) {
      // Mode I: the sliding energy 1/2 S w_t^2 released as the secant stiffness falls, -1/2 dS w_t^2,
      // with w_t^2 by the midpoint rule over the step (zero in pure opening). In mixed mode sliding
      // drives kappa and D(kappa) is exact.
      const double S0 = law.envelope(committed[p].kappa) / committed[p].kappa, S1 = law.envelope(r.kappa) / r.kappa;
      const double w0 = committed[p].sliding;
      eval.trial[p].shear_dissipated += 0.25 * (S0 - S1) * (w0 * w0 + wt * wt);
    }
    eval.trial[p].sliding = wt;
    eval.trial[p].kappa = r.kappa;
    double t[2] = {r.t[0], r.t[1]};
    const double kv = viscosity ? viscosity->stiffness_Pa_m : 0.0;
    if (viscosity) {
      const std::array<double, 2>& w0 = (*viscosity->reference)[p];
      t[0] += kv * (wn - w0[0]);
      t[1] += kv * (wt - w0[1]);
    }
    const double tg[2] = {t[0] * n[0] + t[1] * s[0], t[0] * n[1] + t[1] * s[1]};
    for (std::int64_t e = q.begin; e < q.end; ++e) {
      const std::int32_t g = em_.jump_node[e];
      residual[2 * g] += q.weight * em_.jump_coefficient[e] * tg[0];
      residual[2 * g + 1] += q.weight * em_.jump_coefficient[e] * tg[1];
    }
    if (!tangent) continue;
    // Q C Q^T, Q = [n s].
    double C[2][2];
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) {
        const double Qa[2] = {n[a], s[a]}, Qb[2] = {n[b], s[b]};
        C[a][b] = a == b ? kv : 0.0;  // Q kv I Q^T = kv I
        for (int k = 0; k < 2; ++k)
          for (int l = 0; l < 2; ++l) C[a][b] += Qa[k] * r.tangent[2 * k + l] * Qb[l];
      }
    for (std::int64_t ei = q.begin; ei < q.end; ++ei)
      for (std::int64_t ej = q.begin; ej < q.end; ++ej) {
        const double f = q.weight * em_.jump_coefficient[ei] * em_.jump_coefficient[ej];
        const double blk[2][2] = {{f * C[0][0], f * C[0][1]}, {f * C[1][0], f * C[1][1]}};
        add_block(values_, em_.jump_node[ei], em_.jump_node[ej], blk);
      }
  }
}

Eigen::SparseMatrix<double> FractureSystem::bordered(const Eigen::VectorXd& row, double corner) const {
  const auto N = static_cast<Eigen::Index>(dofs());
  std::vector<int> start(static_cast<std::size_t>(N) + 2, 0), rows;
  std::vector<double> vals;
  rows.reserve(rows_.size() + static_cast<std::size_t>(N));
  vals.reserve(rows_.size() + static_cast<std::size_t>(N));
  for (Eigen::Index j = 0; j < N; ++j) {
    for (int e = col_start_[j]; e < col_start_[j + 1]; ++e) {
      rows.push_back(rows_[e]);
      vals.push_back(values_[e]);
    }
    if (row[j] != 0.0) {
      rows.push_back(static_cast<int>(N));
      vals.push_back(row[j]);
    }
    start[j + 1] = static_cast<int>(rows.size());
  }
  for (Eigen::Index i = 0; i < N; ++i)
    if (f_unit_[i] != 0.0) {
      rows.push_back(static_cast<int>(i));
      vals.push_back(-f_unit_[i]);
    }
  rows.push_back(static_cast<int>(N));
  vals.push_back(corner);
  start[N + 1] = static_cast<int>(rows.size());
  return Eigen::Map<const Eigen::SparseMatrix<double>>(N + 1, N + 1, static_cast<Eigen::Index>(vals.size()),
                                                       start.data(), rows.data(), vals.data());
}

double FractureSystem::opening_integral(const Eigen::VectorXd& d) const { return opening_gradient().dot(d); }

Eigen::VectorXd FractureSystem::opening_gradient() const {
  return opening_gradient(std::vector<char>(em_.cohesive.size(), 1));
}

Eigen::VectorXd FractureSystem::opening_gradient(const std::vector<char>& selected) const {
  Eigen::VectorXd g = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(dofs()));
  for (std::size_t p = 0; p < em_.cohesive.size(); ++p) {
    if (!selected[p]) continue;
    const CohesivePoint& q = em_.cohesive[p];
    for (std::int64_t e = q.begin; e < q.end; ++e) {
      const std::int32_t k = em_.jump_node[e];
      g[2 * k] += q.weight * em_.jump_coefficient[e] * q.normal[0];
      g[2 * k + 1] += q.weight * em_.jump_coefficient[e] * q.normal[1];
    }
  }
  return g;
}

void FractureSystem::boundary_point(std::size_t p, const BoundarySegment& seg, const Eigen::VectorXd& d,
                                    std::array<double, 2>& u, std::array<double, 2>& t) const {
  const GeneralTable& bt = em_.boundary;
  u = {0.0, 0.0};
  std::array<double, 3> eps{0.0, 0.0, 0.0};
  for (std::int64_t e = bt.support.begin(p); e < bt.support.end(p); ++e) {
    const std::int32_t i = bt.support.indices[e];
    const double ux = d[2 * i], uy = d[2 * i + 1], gx = bt.grad[2 * e], gy = bt.grad[2 * e + 1];
    u[0] += bt.psi[e] * ux;
    u[1] += bt.psi[e] * uy;
    eps[0] += gx * ux;
    eps[1] += gy * uy;
    eps[2] += gy * ux + gx * uy;
  }
  t = traction(apply_D(D_, eps), seg.normal.data());
}

double FractureSystem::reaction(const Eigen::VectorXd& d, double lambda) const {
  const GeneralTable& bt = em_.boundary;
  const BoundaryCondition& bc = problem_.boundary[static_cast<int>(far_)];
  double force = 0.0;
  for (std::size_t p = 0; p < bt.size(); ++p) {
    const std::size_t s = static_cast<std::size_t>(base_.boundary.segment[p]);
    const BoundarySegment& seg = base_.segments[s];
    if (seg.part != far_) continue;
    std::array<double, 2> u, t;
    boundary_point(p, seg, d, u, t);
    const std::array<double, 2> g = bc.displacement(&base_.boundary.x[2 * p]);
    const double beta = nitsche_beta(base_, problem_, s);
    const auto a = static_cast<std::size_t>(axis_);
    force += base_.boundary.weight[p] * (t[a] - beta * (u[a] - lambda * g[a]));
  }
  return force;
}

double FractureSystem::operator_energy(const Eigen::VectorXd& d, double lambda) const {
  // 1/2 [d; lambda]^T H [d; lambda] with H the linear operator of the residual, r = K_lin d - lambda f_unit,
  // and its far-face entry k_lambda (the Nitsche penalty of a unit displacement): the energy whose
  // change the external work measures, since F = -f_unit . d + lambda k_lambda (reaction()).
  const auto N = static_cast<Eigen::Index>(dofs());
  const Eigen::Map<const Eigen::SparseMatrix<double>> K(N, N, static_cast<Eigen::Index>(lin_.size()), col_start_.data(),
                                                        rows_.data(), lin_.data());
  return 0.5 * d.dot(K * d) - lambda * f_unit_.dot(d) + 0.5 * lambda * lambda * k_lambda_;
}

double FractureSystem::boundary_energy(const Eigen::VectorXd& d, double lambda) const {
  // The energy whose derivatives are the Nitsche and point-penalty rows of K_lin and f_unit:
  // sum w (-t . P (u - lambda g) + beta/2 |P (u - lambda g)|^2) + penalty/2 u_c^2.
  const GeneralTable& bt = em_.boundary;
  double energy = 0.0;
  for (std::size_t p = 0; p < bt.size(); ++p) {
    const std::size_t s = static_cast<std::size_t>(base_.boundary.segment[p]);
    const BoundarySegment& seg = base_.segments[s];
    const BoundaryCondition& bc = problem_.boundary[static_cast<int>(seg.part)];
    if (!bc.prescribed[0] && !bc.prescribed[1]) continue;
    std::array<double, 2> u, t;
    boundary_point(p, seg, d, u, t);
    const std::array<double, 2> g = bc.displacement(&base_.boundary.x[2 * p]);
    const double beta = nitsche_beta(base_, problem_, s);
    for (int r = 0; r < 2; ++r) {
      if (!bc.prescribed[static_cast<std::size_t>(r)]) continue;
      const double gap = u[static_cast<std::size_t>(r)] - lambda * g[static_cast<std::size_t>(r)];
      energy += base_.boundary.weight[p] * (-t[static_cast<std::size_t>(r)] * gap + 0.5 * beta * gap * gap);
    }
  }
  const double penalty = problem_.nitsche_factor * problem_.material.plane_modulus_Pa();
  const GeneralTable& ct = em_.constraints;
  for (std::size_t p = 0; p < problem_.points.size(); ++p) {
    const int c = problem_.points[p].component;
    double u = 0.0;
    for (std::int64_t e = ct.support.begin(p); e < ct.support.end(p); ++e) u += ct.psi[e] * d[2 * ct.support.indices[e] + c];
    energy += 0.5 * penalty * u * u;
  }
  return energy;
}

double FractureSystem::bulk_energy(const Eigen::VectorXd& d) const {
  const GeneralTable& t = em_.domain;
  double energy = 0.0;
#pragma omp parallel for reduction(+ : energy) schedule(static)
  for (std::int64_t p = 0; p < static_cast<std::int64_t>(t.size()); ++p) {
    const std::array<double, 3> eps = t.strain(static_cast<std::size_t>(p), d);
    const std::array<double, 3> s = apply_D(D_, eps);
    energy += 0.5 * em_.weight[p] * (eps[0] * s[0] + eps[1] * s[1] + eps[2] * s[2]);
  }
  return energy;
}

}  // namespace uhpc::micro
