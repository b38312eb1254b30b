#include "enrichment.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "quadrature.hpp"

namespace uhpc::micro {

namespace {

struct EnrichedRef {
  std::int32_t crack;
  std::int32_t gnode;
};

// Per-point cache of H, R and grad R of each crack (cracks are few; stamps avoid clearing).
struct CrackCache {
  std::vector<int> stamp;
  std::vector<std::array<double, 4>> value;  // H, R, dR/dx, dR/dy
  std::vector<double> chi;                   // junction indicator
  int now = 0;
  explicit CrackCache(std::size_t n) : stamp(n, -1), value(n), chi(n, 1.0) {}
  const std::array<double, 4>& get(const std::vector<Crack>& cracks, std::int32_t c, const double* x) {
    if (stamp[c] != now) {
      stamp[c] = now;
      double g[2];
      const double r = crack_ramp(cracks[c], x, g);
      const double h = static_cast<double>(crack_side(cracks[c], x));
      const Crack& k = cracks[c];
      chi[c] = k.junction < 0 || crack_side(cracks[k.junction], x) == k.junction_side ? 1.0 : 0.0;
      value[c] = {h, r, g[0], g[1]};
    }
    return value[c];
  }
};

struct Builder {
  const std::vector<Crack>& cracks;
  std::size_t n;
  std::vector<std::vector<EnrichedRef>> node_refs;  // per RK node
  std::vector<double> node_side;                    // per gnode k: H_c(x_J)
  CrackCache cache;

  // Appends the row of point x (standard entries [b, e) of table t: an rk::ShapeTable, or the standard
  // part of a GeneralTable row); test gradients = trial ones here, the VCI correction is added once the
  // whole table is known (apply_vci).
  template <class Table>
  void row(GeneralTable& out, const double* x, const Table& t, std::int64_t b, std::int64_t e) {
    ++cache.now;
    for (std::int64_t k = b; k < e; ++k) {
      out.support.indices.push_back(t.support.indices[k]);
      out.psi.push_back(t.psi[k]);
      out.grad.push_back(t.grad[2 * k]);
      out.grad.push_back(t.grad[2 * k + 1]);
      out.test_grad.push_back(t.grad[2 * k]);
      out.test_grad.push_back(t.grad[2 * k + 1]);
    }
    for (std::int64_t k = b; k < e; ++k) {
      const std::int32_t i = t.support.indices[k];
      for (const EnrichedRef& r : node_refs[i]) {
        const auto& v = cache.get(cracks, r.crack, x);
        const double dh = (v[0] - node_side[r.gnode]) * cache.chi[r.crack];
        if (dh == 0.0) continue;  // same side as the node: the enrichment vanishes here
        const double E = dh * v[1];
        const double gx = t.grad[2 * k] * E + t.psi[k] * dh * v[2];
        const double gy = t.grad[2 * k + 1] * E + t.psi[k] * dh * v[3];
        if (E == 0.0 && gx == 0.0 && gy == 0.0) continue;
        out.support.indices.push_back(static_cast<std::int32_t>(n) + r.gnode);
        out.psi.push_back(t.psi[k] * E);
        out.grad.push_back(gx);
        out.grad.push_back(gy);
        out.test_grad.push_back(gx);
        out.test_grad.push_back(gy);
      }
    }
    out.support.offsets.push_back(static_cast<std::int64_t>(out.support.indices.size()));
  }
};

PointSet sample_flat(const RkGalerkinModel& base, const std::vector<double>& x) {
  std::vector<std::array<double, 2>> p(x.size() / 2);
  for (std::size_t i = 0; i < p.size(); ++i) p[i] = {x[2 * i], x[2 * i + 1]};
  return sample_points(base, p);
}

// Candidate enrichment: (crack, node) pairs whose support the active crack cuts.
std::vector<std::pair<std::int32_t, std::int32_t>> candidates(const RkGalerkinModel& base,
                                                              const std::vector<Crack>& cracks) {
  std::vector<std::pair<std::int32_t, std::int32_t>> out;
  const double amax = *std::max_element(base.support_radius.begin(), base.support_radius.end());
  for (std::size_t c = 0; c < cracks.size(); ++c) {
    const Crack& k = cracks[c];
    if (k.active == 0) continue;
    double lo[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    double hi[2] = {-lo[0], -lo[1]};
    for (std::size_t s = 0; s <= k.active; ++s) {
      lo[0] = std::min(lo[0], k.points[s].x);
      lo[1] = std::min(lo[1], k.points[s].y);
      hi[0] = std::max(hi[0], k.points[s].x);
      hi[1] = std::max(hi[1], k.points[s].y);
    }
    for (std::size_t i = 0; i < base.node_count(); ++i) {
      const double* x = &base.nodes[2 * i];
      if (x[0] < lo[0] - amax || x[0] > hi[0] + amax || x[1] < lo[1] - amax || x[1] > hi[1] + amax) continue;
      if (crack_distance(k, x) < base.support_radius[i])
        out.emplace_back(static_cast<std::int32_t>(c), static_cast<std::int32_t>(i));
    }
  }
  return out;
}

void setup(Builder& b, const RkGalerkinModel& base, const std::vector<std::pair<std::int32_t, std::int32_t>>& set) {
  b.node_refs.assign(b.n, {});
  b.node_side.clear();
  for (std::size_t k = 0; k < set.size(); ++k) {
    b.node_refs[set[k].second].push_back({set[k].first, static_cast<std::int32_t>(k)});
    b.node_side.push_back(crack_side(b.cracks[set[k].first], &base.nodes[2 * set[k].second]));
  }
}

// Variationally consistent integration on the cracked model (rk_galerkin_model.hpp explains VCI):
// for every generalized function f (standard and enriched) the constant xi_f on its support makes
//   sum_q grad~f(x_q) w_q = sum_b f(x_b) n_b w_b - sum_c [[f]](x_c) n_c w_c
// hold exactly, the last sum over the cohesive points (the crack faces are internal boundaries: the
// divergence theorem on each side gives the jump term, n_c pointing to the H = 1 side). The base
// model's constants cannot be reused: they make the test space's "rigid translation of one side of a
// crack" do spurious work of the order of f_t x crack length (measured 20 % in the strip test).
void apply_vci(EnrichedModel& em, const RkGalerkinModel& base) {
  const std::size_t n = em.gnode_count();
  std::vector<double> residual(2 * n, 0.0), weight(n, 0.0);
  const GeneralTable& bt = em.boundary;
  for (std::size_t p = 0; p < bt.size(); ++p) {
    const BoundarySegment& s = base.segments[base.boundary.segment[p]];
    for (std::int64_t e = bt.support.begin(p); e < bt.support.end(p); ++e) {
      const std::int32_t g = bt.support.indices[e];
      residual[2 * g] += bt.psi[e] * s.normal[0] * base.boundary.weight[p];
      residual[2 * g + 1] += bt.psi[e] * s.normal[1] * base.boundary.weight[p];
    }
  }
  for (const CohesivePoint& c : em.cohesive)
    for (std::int64_t e = c.begin; e < c.end; ++e) {
      const std::int32_t g = em.jump_node[e];
      residual[2 * g] -= em.jump_coefficient[e] * c.normal[0] * c.weight;
      residual[2 * g + 1] -= em.jump_coefficient[e] * c.normal[1] * c.weight;
    }
  GeneralTable& t = em.domain;
  for (std::size_t p = 0; p < t.size(); ++p)
    for (std::int64_t e = t.support.begin(p); e < t.support.end(p); ++e) {
      const std::int32_t g = t.support.indices[e];
      residual[2 * g] -= t.grad[2 * e] * em.weight[p];
      residual[2 * g + 1] -= t.grad[2 * e + 1] * em.weight[p];
      weight[g] += em.weight[p];
    }
  for (std::size_t e = 0; e < t.support.indices.size(); ++e) {
    const std::int32_t g = t.support.indices[e];
    if (!(weight[g] > 0.0)) continue;
    t.test_grad[2 * e] = t.grad[2 * e] + residual[2 * g] / weight[g];
    t.test_grad[2 * e + 1] = t.grad[2 * e + 1] + residual[2 * g + 1] / weight[g];
  }
}

}  // namespace

EnrichedModel build_enriched_model(const RkGalerkinModel& base, const CellDiscretization& mesh, const std::vector<Crack>& cracks,
                                   const std::vector<std::array<double, 2>>& constraint_points,
                                   const EnrichmentOptions& options) {
  EnrichedModel em;
  const std::size_t n = base.node_count();
  em.standard_nodes = n;

  // Domain points: base points of uncut triangles, new points in the pieces of cut ones.
  const std::vector<TrianglePoint>& rule = triangle_rule(base.options.triangle_points);
  const std::size_t per = rule.size();
  std::vector<std::int64_t> source;  // per domain point: base point index, or -(new index) - 1
  std::vector<double> new_x, new_w;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    std::array<std::array<double, 2>, 3> tri;
    for (int v = 0; v < 3; ++v) tri[v] = mesh.nodes_m[mesh.triangles[t][v]];
    const std::vector<SubTriangle> pieces = split_triangle(tri, cracks);
    if (pieces.empty()) {
      for (std::size_t q = 0; q < per; ++q) {
        const std::size_t p = t * per + q;
        source.push_back(static_cast<std::int64_t>(p));
        em.x.push_back(base.domain.x[2 * p]);
        em.x.push_back(base.domain.x[2 * p + 1]);
        em.weight.push_back(base.domain.weight[p]);
      }
      continue;
    }
    ++em.cut_triangles;
    for (const SubTriangle& s : pieces) {
      const double area = 0.5 * std::abs((s.v[1][0] - s.v[0][0]) * (s.v[2][1] - s.v[0][1]) -
                                         (s.v[1][1] - s.v[0][1]) * (s.v[2][0] - s.v[0][0]));
      for (const TrianglePoint& q : rule) {
        double x[2];
        for (int d = 0; d < 2; ++d)
          x[d] = q.barycentric[0] * s.v[0][d] + q.barycentric[1] * s.v[1][d] + q.barycentric[2] * s.v[2][d];
        source.push_back(-static_cast<std::int64_t>(new_w.size()) - 1);
        new_x.push_back(x[0]);
        new_x.push_back(x[1]);
        new_w.push_back(q.weight * area);
        em.x.push_back(x[0]);
        em.x.push_back(x[1]);
        em.weight.push_back(q.weight * area);
      }
    }
  }
  const PointSet fresh = sample_flat(base, new_x);

  Builder b{cracks, n, {}, {}, CrackCache(cracks.size())};
  auto domain_table = [&](GeneralTable& out) {
    out = GeneralTable{};
    for (std::size_t p = 0; p < source.size(); ++p) {
      if (source[p] >= 0) {
        const std::size_t q = static_cast<std::size_t>(source[p]);
        const rk::ShapeTable& t = base.domain.table;
        b.row(out, &em.x[2 * p], t, t.support.begin(q), t.support.end(q));
      } else {
        const std::size_t q = static_cast<std::size_t>(-source[p] - 1);
        b.row(out, &em.x[2 * p], fresh.table, fresh.table.support.begin(q), fresh.table.support.end(q));
      }
    }
  };

  // Pass 1: every candidate; keep those whose enriched function is not negligible on its support.
  const auto cand = candidates(base, cracks);
  setup(b, base, cand);
  GeneralTable trial;
  domain_table(trial);
  std::vector<double> num(cand.size(), 0.0), den(n, 0.0);
  for (std::size_t p = 0; p < trial.size(); ++p)
    for (std::int64_t e = trial.support.begin(p); e < trial.support.end(p); ++e) {
      const std::int32_t g = trial.support.indices[e];
      const double v = em.weight[p] * trial.psi[e] * trial.psi[e];
      if (g < static_cast<std::int32_t>(n)) den[g] += v;
      else num[g - n] += v;
    }
  std::vector<std::pair<std::int32_t, std::int32_t>> kept;
  for (std::size_t k = 0; k < cand.size(); ++k)
    if (num[k] >= options.min_enrichment_ratio * den[cand[k].second]) kept.push_back(cand[k]);
  setup(b, base, kept);
  for (const auto& [c, i] : kept) {
    em.enriched_crack.push_back(c);
    em.enriched_node.push_back(i);
  }
  domain_table(em.domain);

  // Boundary and constraint points.
  const rk::ShapeTable& bt = base.boundary.table;
  for (std::size_t p = 0; p < base.boundary.size(); ++p)
    b.row(em.boundary, &base.boundary.x[2 * p], bt, bt.support.begin(p), bt.support.end(p));
  const PointSet cp = sample_points(base, constraint_points);
  for (std::size_t p = 0; p < cp.size(); ++p)
    b.row(em.constraints, &cp.x[2 * p], cp.table, cp.table.support.begin(p), cp.table.support.end(p));

  // Cohesive points along the active segments.
  const std::vector<LinePoint>& line = line_rule(options.crack_points);
  std::vector<double> cx;
  for (std::size_t c = 0; c < cracks.size(); ++c)
    for (std::size_t s = 0; s < cracks[c].active; ++s) {
      const Vec2& a = cracks[c].points[s];
      const Vec2& q = cracks[c].points[s + 1];
      const double len = std::hypot(q.x - a.x, q.y - a.y);
      for (std::size_t g = 0; g < line.size(); ++g) {
        CohesivePoint cpnt;
        cpnt.x = {a.x + line[g].t * (q.x - a.x), a.y + line[g].t * (q.y - a.y)};
        cpnt.weight = line[g].weight * len;
        cpnt.normal = {-(q.y - a.y) / len, (q.x - a.x) / len};
        cpnt.crack = static_cast<std::int32_t>(c);
        cpnt.segment = static_cast<std::int32_t>(s);
        cpnt.gauss = static_cast<std::int32_t>(g);
        em.cohesive.push_back(cpnt);
        cx.push_back(cpnt.x[0]);
        cx.push_back(cpnt.x[1]);
      }
    }
  const PointSet cs = sample_flat(base, cx);
  for (std::size_t p = 0; p < em.cohesive.size(); ++p) {
    CohesivePoint& q = em.cohesive[p];
    double g[2];
    const double R = crack_ramp(cracks[q.crack], q.x.data(), g);
    q.begin = static_cast<std::int64_t>(em.jump_node.size());
    for (std::int64_t e = cs.table.support.begin(p); e < cs.table.support.end(p); ++e)
      for (const EnrichedRef& r : b.node_refs[cs.table.support.indices[e]])
        if (r.crack == q.crack && R * cs.table.psi[e] != 0.0) {
          em.jump_node.push_back(static_cast<std::int32_t>(n) + r.gnode);
          em.jump_coefficient.push_back(R * cs.table.psi[e]);
        }
    q.end = static_cast<std::int64_t>(em.jump_node.size());
  }
  const bool cracked = std::any_of(cracks.begin(), cracks.end(), [](const Crack& c) { return c.active > 0; });
  if ((cracked ? options.cracked_correction : base.options.correction) == IntegrationCorrection::Vci) apply_vci(em, base);
  return em;
}

namespace {

// A Builder for the enriched functions of an existing model.
Builder builder_of(const RkGalerkinModel& base, const EnrichedModel& em, const std::vector<Crack>& cracks) {
  std::vector<std::pair<std::int32_t, std::int32_t>> set;
  for (std::size_t k = 0; k < em.enriched_node.size(); ++k) set.emplace_back(em.enriched_crack[k], em.enriched_node[k]);
  Builder b{cracks, base.node_count(), {}, {}, CrackCache(cracks.size())};
  setup(b, base, set);
  return b;
}

}  // namespace

GeneralTable enriched_table_at(const RkGalerkinModel& base, const EnrichedModel& em, const std::vector<Crack>& cracks,
                               const std::vector<double>& points) {
  Builder b = builder_of(base, em, cracks);
  const PointSet ps = sample_flat(base, points);
  GeneralTable out;
  for (std::size_t p = 0; p < ps.size(); ++p)
    b.row(out, &ps.x[2 * p], ps.table, ps.table.support.begin(p), ps.table.support.end(p));
  return out;
}

std::vector<double> enriched_displacement(const RkGalerkinModel& base, const EnrichedModel& em,
                                          const std::vector<Crack>& cracks, const GeneralTable& rows,
                                          const std::vector<double>& x, const Eigen::VectorXd& d) {
  const auto n = static_cast<std::int32_t>(base.node_count());
  Builder b = builder_of(base, em, cracks);
  std::vector<double> u(2 * rows.size(), 0.0);
  GeneralTable scratch;
  for (std::size_t p = 0; p < rows.size(); ++p) {
    std::int64_t e = rows.support.begin(p);
    while (e < rows.support.end(p) && rows.support.indices[static_cast<std::size_t>(e)] < n) ++e;
    scratch.support.offsets.assign(1, 0);
    scratch.support.indices.clear();
    scratch.psi.clear();
    scratch.grad.clear();
    scratch.test_grad.clear();
    b.row(scratch, &x[2 * p], rows, rows.support.begin(p), e);
    for (std::size_t k = 0; k < scratch.support.indices.size(); ++k) {
      const std::int32_t g = scratch.support.indices[k];
      u[2 * p] += scratch.psi[k] * d[2 * g];
      u[2 * p + 1] += scratch.psi[k] * d[2 * g + 1];
    }
  }
  return u;
}

}  // namespace uhpc::micro
