#include "stiffness_assembly.hpp"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace uhpc::micro {

namespace {

// Node-level sparsity in compressed columns: rows of node column J are rows[start[J] .. start[J+1]),
// ascending.
struct NodePattern {
  std::vector<std::int64_t> start;
  std::vector<std::int32_t> rows;
};

// node -> entries (point, position in the point's row) of a shape table: the transpose of its rows.
struct Incidence {
  std::vector<std::int64_t> start;
  std::vector<std::int64_t> entry;  // index into table.support.indices
};

Incidence transpose(const rk::ShapeTable& t, std::size_t n_nodes) {
  Incidence inc;
  inc.start.assign(n_nodes + 1, 0);
  for (std::int32_t i : t.support.indices) ++inc.start[i + 1];
  for (std::size_t i = 0; i < n_nodes; ++i) inc.start[i + 1] += inc.start[i];
  inc.entry.resize(t.support.indices.size());
  std::vector<std::int64_t> fill(inc.start.begin(), inc.start.end() - 1);
  for (std::size_t e = 0; e < t.support.indices.size(); ++e) inc.entry[fill[t.support.indices[e]]++] = static_cast<std::int64_t>(e);
  return inc;
}

// The point of each entry of a table (rows are contiguous, so a binary search on offsets would do;
// a flat array is simpler and the tables are built once).
std::vector<std::int32_t> entry_points(const rk::ShapeTable& t) {
  std::vector<std::int32_t> p(t.support.indices.size());
  for (std::size_t q = 0; q < t.support.size(); ++q)
    for (std::int64_t e = t.support.begin(q); e < t.support.end(q); ++e) p[e] = static_cast<std::int32_t>(q);
  return p;
}

NodePattern node_pattern(const std::vector<const rk::ShapeTable*>& tables, std::size_t n) {
  std::vector<Incidence> inc;
  std::vector<std::vector<std::int32_t>> pts;
  for (const rk::ShapeTable* t : tables) {
    inc.push_back(transpose(*t, n));
    pts.push_back(entry_points(*t));
  }
  NodePattern pat;
  pat.start.assign(n + 1, 0);
  std::vector<std::int32_t> mark(n, -1), column;
  for (std::size_t j = 0; j < n; ++j) {
    column.clear();
    for (std::size_t s = 0; s < tables.size(); ++s)
      for (std::int64_t k = inc[s].start[j]; k < inc[s].start[j + 1]; ++k) {
        const std::int32_t q = pts[s][inc[s].entry[k]];
        const rk::ShapeTable& t = *tables[s];
        for (std::int64_t e = t.support.begin(q); e < t.support.end(q); ++e) {
          const std::int32_t i = t.support.indices[e];
          if (mark[i] != static_cast<std::int32_t>(j)) {
            mark[i] = static_cast<std::int32_t>(j);
            column.push_back(i);
          }
        }
      }
    std::sort(column.begin(), column.end());
    pat.rows.insert(pat.rows.end(), column.begin(), column.end());
    pat.start[j + 1] = static_cast<std::int64_t>(pat.rows.size());
  }
  return pat;
}

// DOF-level compressed columns from the node pattern: column 2J + c holds rows 2I, 2I + 1 for every I
// of node column J, so entry (2I + r, 2J + c) sits at col_start[2J + c] + 2 k + r, k = I's position.
struct DofMatrix {
  std::vector<int> col_start, rows;
  std::vector<double> values;
};

DofMatrix dof_matrix(const NodePattern& p, std::size_t n) {
  DofMatrix m;
  m.col_start.assign(2 * n + 1, 0);
  for (std::size_t j = 0; j < n; ++j) {
    const int len = static_cast<int>(2 * (p.start[j + 1] - p.start[j]));
    m.col_start[2 * j + 1] = m.col_start[2 * j] + len;
    m.col_start[2 * j + 2] = m.col_start[2 * j + 1] + len;
  }
  m.rows.resize(static_cast<std::size_t>(m.col_start.back()));
  for (std::size_t j = 0; j < n; ++j)
    for (int c = 0; c < 2; ++c) {
      int at = m.col_start[2 * j + c];
      for (std::int64_t k = p.start[j]; k < p.start[j + 1]; ++k) {
        m.rows[at++] = 2 * p.rows[k];
        m.rows[at++] = 2 * p.rows[k] + 1;
      }
    }
  m.values.assign(m.rows.size(), 0.0);
  return m;
}

// Position k of node i in node column j (serial parts only; the domain loop uses a marker array).
std::int64_t find(const NodePattern& p, std::int32_t j, std::int32_t i) {
  const auto first = p.rows.begin() + p.start[j], last = p.rows.begin() + p.start[j + 1];
  return std::lower_bound(first, last, i) - first;
}

void add_block(DofMatrix& m, const NodePattern& p, std::int32_t i, std::int32_t j, const double b[2][2]) {
  const std::int64_t k = find(p, j, i);
  for (int c = 0; c < 2; ++c)
    for (int r = 0; r < 2; ++r) m.values[m.col_start[2 * j + c] + 2 * k + r] += b[r][c];
}

void assemble_domain(const RkGalerkinModel& model, const std::array<double, 9>& D, const NodePattern& pat,
                     DofMatrix& m) {
  const rk::ShapeTable& t = model.domain.table;
  const std::size_t n = model.node_count();
  const Incidence inc = transpose(t, n);
  const std::vector<std::int32_t> pts = entry_points(t);
#pragma omp parallel
  {
    std::vector<std::int32_t> local(n, -1);  // per thread, once: position of node i in the current column
#pragma omp for schedule(dynamic, 64)
    for (std::int64_t jj = 0; jj < static_cast<std::int64_t>(n); ++jj) {
      const auto j = static_cast<std::int32_t>(jj);
      for (std::int64_t k = pat.start[j]; k < pat.start[j + 1]; ++k)
        local[pat.rows[k]] = static_cast<std::int32_t>(k - pat.start[j]);
      double* col[2] = {m.values.data() + m.col_start[2 * j], m.values.data() + m.col_start[2 * j + 1]};
      for (std::int64_t a = inc.start[j]; a < inc.start[j + 1]; ++a) {
        const std::int64_t ej = inc.entry[a];
        const std::int32_t q = pts[ej];
        const double w = model.domain.weight[q];
        const std::array<double, 3> s[2] = {apply_D(D, unit_strain(0, &t.grad[2 * ej])),
                                            apply_D(D, unit_strain(1, &t.grad[2 * ej]))};
        for (std::int64_t e = t.support.begin(q); e < t.support.end(q); ++e) {
          const double* g = &model.test_grad[2 * e];
          const std::int32_t pos = 2 * local[t.support.indices[e]];
          for (int c = 0; c < 2; ++c) {
            col[c][pos] += w * (g[0] * s[c][0] + g[1] * s[c][2]);
            col[c][pos + 1] += w * (g[1] * s[c][1] + g[0] * s[c][2]);
          }
        }
      }
    }
  }
}

void assemble_boundary(const RkGalerkinModel& model, const ElasticProblem& problem, const std::array<double, 9>& D,
                       const NodePattern& pat, DofMatrix& m, Eigen::VectorXd& f) {
  const BoundaryPoints& bp = model.boundary;
  const rk::ShapeTable& t = bp.table;
  std::vector<std::array<double, 4>> T;  // per node of the point: traction of e_k Psi, T[r][k] at 2 r + k
  for (std::size_t p = 0; p < bp.size(); ++p) {
    const std::size_t s = static_cast<std::size_t>(bp.segment[p]);
    const BoundarySegment& seg = model.segments[s];
    const BoundaryCondition& bc = problem.boundary[static_cast<int>(seg.part)];
    const double* x = &bp.x[2 * p];
    const double w = bp.weight[p];
    const std::int64_t b0 = t.support.begin(p), b1 = t.support.end(p);
    const double P[2] = {bc.prescribed[0] ? 1.0 : 0.0, bc.prescribed[1] ? 1.0 : 0.0};
    if (bc.traction && !(bc.prescribed[0] && bc.prescribed[1])) {
      const std::array<double, 2> tb = bc.traction(x, seg.normal.data());
      for (std::int64_t e = b0; e < b1; ++e)
        for (int r = 0; r < 2; ++r) f[2 * t.support.indices[e] + r] += w * t.psi[e] * (1.0 - P[r]) * tb[r];
    }
    if (!bc.prescribed[0] && !bc.prescribed[1]) continue;
    const std::array<double, 2> g = bc.displacement(x);
    const double beta = nitsche_beta(model, problem, s);
    T.resize(static_cast<std::size_t>(b1 - b0));
    for (std::int64_t e = b0; e < b1; ++e)
      for (int k = 0; k < 2; ++k) {
        const std::array<double, 2> tr = traction(apply_D(D, unit_strain(k, &t.grad[2 * e])), seg.normal.data());
        T[e - b0][k] = tr[0];
        T[e - b0][2 + k] = tr[1];
      }
    for (std::int64_t ei = b0; ei < b1; ++ei) {
      const std::int32_t i = t.support.indices[ei];
      const double* Ti = T[ei - b0].data();
      for (int r = 0; r < 2; ++r)
        f[2 * i + r] += w * (-(Ti[r] * P[0] * g[0] + Ti[2 + r] * P[1] * g[1]) + beta * t.psi[ei] * P[r] * g[r]);
      for (std::int64_t ej = b0; ej < b1; ++ej) {
        const std::int32_t j = t.support.indices[ej];
        const double* Tj = T[ej - b0].data();
        double blk[2][2];
        for (int r = 0; r < 2; ++r)
          for (int k = 0; k < 2; ++k)
            blk[r][k] = w * (-t.psi[ei] * P[r] * Tj[2 * r + k] - Ti[2 * k + r] * P[k] * t.psi[ej] +
                             (r == k ? beta * t.psi[ei] * t.psi[ej] * P[r] : 0.0));
        add_block(m, pat, i, j, blk);
      }
    }
  }
}

void assemble_points(const ElasticProblem& problem, const PointSet& cp, const NodePattern& pat, DofMatrix& m,
                     Eigen::VectorXd& f) {
  const double penalty = problem.nitsche_factor * problem.material.plane_modulus_Pa();
  const rk::ShapeTable& t = cp.table;
  for (std::size_t p = 0; p < problem.points.size(); ++p) {
    const int c = problem.points[p].component;
    for (std::int64_t ei = t.support.begin(p); ei < t.support.end(p); ++ei) {
      const std::int32_t i = t.support.indices[ei];
      f[2 * i + c] += penalty * t.psi[ei] * problem.points[p].value_m;
      for (std::int64_t ej = t.support.begin(p); ej < t.support.end(p); ++ej) {
        double blk[2][2] = {{0.0, 0.0}, {0.0, 0.0}};
        blk[c][c] = penalty * t.psi[ei] * t.psi[ej];
        add_block(m, pat, i, t.support.indices[ej], blk);
      }
    }
  }
}

}  // namespace

double nitsche_beta(const RkGalerkinModel& model, const ElasticProblem& problem, std::size_t segment) {
  const BoundarySegment& s = model.segments[segment];
  const double h = 0.5 * (model.support_radius[s.nodes[0]] + model.support_radius[s.nodes[1]]) /
                   model.options.support_factor;
  return problem.nitsche_factor * problem.material.plane_modulus_Pa() / h;
}

LinearSystem assemble_elastic_system(const RkGalerkinModel& model, const ElasticProblem& problem,
                                     const PointSet& constraints) {
  const std::size_t n = model.node_count();
  const NodePattern pat = node_pattern({&model.domain.table, &model.boundary.table, &constraints.table}, n);
  DofMatrix m = dof_matrix(pat, n);
  LinearSystem sys;
  sys.f = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(2 * n));
  const std::array<double, 9> D = problem.material.D();
  assemble_domain(model, D, pat, m);
  assemble_boundary(model, problem, D, pat, m, sys.f);
  assemble_points(problem, constraints, pat, m, sys.f);
  const auto dofs = static_cast<Eigen::Index>(2 * n);
  sys.K = Eigen::Map<const Eigen::SparseMatrix<double>>(dofs, dofs, static_cast<Eigen::Index>(m.values.size()),
                                                        m.col_start.data(), m.rows.data(), m.values.data());
  sys.symmetric = model.options.correction == IntegrationCorrection::None;
  return sys;
}

}  // namespace uhpc::micro
