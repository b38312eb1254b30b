#include "boundary_segments.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "uhpc/errors.hpp"

namespace uhpc::micro {

std::vector<BoundarySegment> boundary_segments(const CellDiscretization& mesh) {
  // Every directed edge (a, b) of a counter-clockwise triangle; an interior edge also appears as (b, a).
  struct Edge {
    std::int32_t lo, hi, a, b;
  };
  std::vector<Edge> edges;
  edges.reserve(3 * mesh.triangle_count());
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const std::int32_t a = t[k], b = t[(k + 1) % 3];
      edges.push_back({std::min(a, b), std::max(a, b), a, b});
    }
  std::sort(edges.begin(), edges.end(),
            [](const Edge& x, const Edge& y) { return std::make_pair(x.lo, x.hi) < std::make_pair(y.lo, y.hi); });

  std::vector<BoundarySegment> out;
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i + 1;
    while (j < edges.size() && edges[j].lo == edges[i].lo && edges[j].hi == edges[i].hi) ++j;
    if (j - i == 1) {
      const Edge& e = edges[i];
      BoundarySegment s{};
      s.nodes = {e.a, e.b};
      const auto& pa = mesh.nodes_m[e.a];
      const auto& pb = mesh.nodes_m[e.b];
      const double dx = pb[0] - pa[0], dy = pb[1] - pa[1];
      s.length_m = std::hypot(dx, dy);
      s.normal = {dy / s.length_m, -dx / s.length_m};  // right of a -> b: outward for a CCW triangle
      const std::uint8_t common = mesh.node_edges[e.a] & mesh.node_edges[e.b];
      if (mesh.node_pore[e.a] >= 0 && mesh.node_pore[e.a] == mesh.node_pore[e.b]) {
        s.part = BoundaryPart::Pore;
        s.pore = mesh.node_pore[e.a];
      } else if (common != 0) {
        // A corner carries two flags; the common flag of both ends is the edge (one bit for a segment).
        int bit = 0;
        while (!(common & (1u << bit))) ++bit;
        s.part = static_cast<BoundaryPart>(bit);
      } else {
        throw NumericalError(fmt::format("boundary edge ({}, {}) lies on no cell edge or pore", e.a, e.b));
      }
      out.push_back(s);
    } else if (j - i > 2) {
      throw NumericalError(fmt::format("mesh edge ({}, {}) is shared by {} triangles", edges[i].lo, edges[i].hi, j - i));
    }
    i = j;
  }
  return out;
}

}  // namespace uhpc::micro
