#include "rk_galerkin_model.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "quadrature.hpp"
#include "uhpc/errors.hpp"

namespace uhpc::micro {

namespace {

rk::Options rk_options(const RkGalerkinOptions& o) {
  rk::Options r;
  r.kernel = o.kernel;
  r.basis = rk::Basis::Linear;
  r.gradients = true;
  r.derivatives = o.derivatives;
  return r;
}

void evaluate(const RkGalerkinModel& m, PointSet& set, const char* what) {
  set.table = rk::build_shape_table<2>(rk_options(m.options), set.x.data(), set.size(), m.nodes.data(),
                                       m.support_radius.data(), m.node_count());
  for (std::size_t p = 0; p < set.size(); ++p)
    if (set.table.info[p].path == rk::Path::Empty)
      throw NumericalError(fmt::format("{} point ({:g}, {:g}) m is covered by no RK node", what, set.x[2 * p],
                                       set.x[2 * p + 1]));
}

// xi_I = (boundary integral of Psi_I n - domain sum of grad Psi_I w) / (sum of the weights on I's
// support); the test gradients get + xi_I wherever Psi_I is evaluated.
void apply_vci(RkGalerkinModel& m) {
  const std::size_t n = m.node_count();
  std::vector<double> residual(2 * n, 0.0), support_weight(n, 0.0);
  const auto& bt = m.boundary.table;
  for (std::size_t p = 0; p < m.boundary.size(); ++p) {
    const BoundarySegment& s = m.segments[m.boundary.segment[p]];
    for (std::int64_t e = bt.support.begin(p); e < bt.support.end(p); ++e) {
      const std::int32_t i = bt.support.indices[e];
      residual[2 * i] += bt.psi[e] * s.normal[0] * m.boundary.weight[p];
      residual[2 * i + 1] += bt.psi[e] * s.normal[1] * m.boundary.weight[p];
    }
  }
  const auto& dt = m.domain.table;
  for (std::size_t p = 0; p < m.domain.size(); ++p)
    for (std::int64_t e = dt.support.begin(p); e < dt.support.end(p); ++e) {
      const std::int32_t i = dt.support.indices[e];
      residual[2 * i] -= dt.grad[2 * e] * m.domain.weight[p];
      residual[2 * i + 1] -= dt.grad[2 * e + 1] * m.domain.weight[p];
      support_weight[i] += m.domain.weight[p];
    }
  std::vector<double> xi(2 * n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    if (!(support_weight[i] > 0.0)) continue;  // a node no domain point sees has no test function to correct
    xi[2 * i] = residual[2 * i] / support_weight[i];
    xi[2 * i + 1] = residual[2 * i + 1] / support_weight[i];
    m.vci_max_correction = std::max(m.vci_max_correction, std::hypot(xi[2 * i], xi[2 * i + 1]) * m.support_radius[i]);
  }
  for (std::size_t e = 0; e < dt.support.indices.size(); ++e) {
    const std::int32_t i = dt.support.indices[e];
    m.test_grad[2 * e] += xi[2 * i];
    m.test_grad[2 * e + 1] += xi[2 * i + 1];
  }
}

}  // namespace

RkGalerkinModel build_rk_galerkin_model(const CellDiscretization& mesh, const RkGalerkinOptions& options) {
  RkGalerkinModel m;
  m.options = options;
  const std::size_t n = mesh.node_count();
  m.nodes.resize(2 * n);
  m.support_radius.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    m.nodes[2 * i] = mesh.nodes_m[i][0];
    m.nodes[2 * i + 1] = mesh.nodes_m[i][1];
    m.support_radius[i] = options.support_factor * mesh.spacing_m[i];
  }

  const std::vector<TrianglePoint>& tri = triangle_rule(options.triangle_points);
  m.domain.x.reserve(2 * tri.size() * mesh.triangle_count());
  m.domain.weight.reserve(tri.size() * mesh.triangle_count());
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const double area = mesh.triangle_area(t);
    const auto& v = mesh.triangles[t];
    for (const TrianglePoint& q : tri) {
      for (int d = 0; d < 2; ++d)
        m.domain.x.push_back(q.barycentric[0] * mesh.nodes_m[v[0]][d] + q.barycentric[1] * mesh.nodes_m[v[1]][d] +
                             q.barycentric[2] * mesh.nodes_m[v[2]][d]);
      m.domain.weight.push_back(q.weight * area);
    }
  }
  evaluate(m, m.domain, "domain");

  m.segments = boundary_segments(mesh);
  const std::vector<LinePoint>& line = line_rule(options.segment_points);
  for (std::size_t s = 0; s < m.segments.size(); ++s) {
    const auto& a = mesh.nodes_m[m.segments[s].nodes[0]];
    const auto& b = mesh.nodes_m[m.segments[s].nodes[1]];
    for (const LinePoint& q : line) {
      m.boundary.x.push_back((1.0 - q.t) * a[0] + q.t * b[0]);
      m.boundary.x.push_back((1.0 - q.t) * a[1] + q.t * b[1]);
      m.boundary.weight.push_back(q.weight * m.segments[s].length_m);
      m.boundary.segment.push_back(static_cast<std::int32_t>(s));
    }
  }
  evaluate(m, m.boundary, "boundary");

  m.test_grad = m.domain.table.grad;
  if (options.correction == IntegrationCorrection::Vci) apply_vci(m);
  return m;
}

PointSet sample_points(const RkGalerkinModel& model, const std::vector<std::array<double, 2>>& points) {
  PointSet set;
  for (const auto& p : points) {
    set.x.push_back(p[0]);
    set.x.push_back(p[1]);
    set.weight.push_back(0.0);
  }
  evaluate(model, set, "sample");
  return set;
}

}  // namespace uhpc::micro
