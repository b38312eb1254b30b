// gmsh triangulation of the porous cell. gmsh is a global singleton: it is initialized once per
// process (silenced) and every call builds, meshes and removes its own model.
#include "cell_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include <fmt/format.h>
#include <gmsh.h>

#include "uhpc/errors.hpp"

namespace uhpc::micro {

namespace {

// Initializes gmsh on first use and finalizes it at process exit.
class GmshSession {
 public:
  static void ensure() { static GmshSession session; }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

 private:
  GmshSession() {
    gmsh::initialize(0, nullptr, false);  // no user config files: results must not depend on ~/.gmsh-options
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::option::setNumber("General.Verbosity", 1);
    gmsh::option::setNumber("General.NumThreads", 1);  // deterministic meshes
    warm_up();
  }
  // gmsh's first mesh in a process differs from every later one of the same geometry (measured: 13 447
  // against 13 437 nodes on a 5.0 mm cell, whatever was meshed in between), so an ensemble's cells
  // would depend on their order and `run` would not reproduce them. One throwaway mesh first makes
  // every cell's mesh the same (tests/verification/test_micro_cell_mesh.cpp).
  static void warm_up() {
    namespace geo = gmsh::model::geo;
    gmsh::model::add("uhpc_micro_warm_up");
    const double L = 1e-3;
    const int a = geo::addPoint(0, 0, 0), b = geo::addPoint(L, 0, 0), c = geo::addPoint(L, L, 0), d = geo::addPoint(0, L, 0);
    geo::addPlaneSurface({geo::addCurveLoop({geo::addLine(a, b), geo::addLine(b, c), geo::addLine(c, d), geo::addLine(d, a)})});
    geo::synchronize();
    gmsh::model::mesh::setSizeCallback([](int, int, double, double, double) -> double { return 2e-4; });
    gmsh::model::mesh::generate(2);
    gmsh::model::mesh::removeSizeCallback();
    gmsh::model::remove();
  }
  ~GmshSession() { gmsh::finalize(); }
};

// Builds the geometry (built-in kernel: the disks do not overlap, so no boolean operations are
// needed) and returns the curve tags of each pore and of the four edges.
struct GeometryTags {
  std::vector<std::vector<int>> pore_curves;
  std::array<int, 4> edge_curves{};  // left, right, bottom, top
};

GeometryTags build_geometry(const CellGeometry& cell, const CellSizeField& field) {
  namespace geo = gmsh::model::geo;
  GeometryTags tags;
  const double L = cell.side_m;
  const int p00 = geo::addPoint(0, 0, 0), p10 = geo::addPoint(L, 0, 0);
  const int p11 = geo::addPoint(L, L, 0), p01 = geo::addPoint(0, L, 0);
  const int bottom = geo::addLine(p00, p10), right = geo::addLine(p10, p11);
  const int top = geo::addLine(p11, p01), left = geo::addLine(p01, p00);
  tags.edge_curves = {left, right, bottom, top};
  std::vector<int> loops{geo::addCurveLoop({bottom, right, top, left})};
  for (std::size_t p = 0; p < cell.pores.size(); ++p) {
    const Pore& pore = cell.pores[p];
    const double cx = pore.center_m.x, cy = pore.center_m.y, r = pore.radius_m();
    const int c = geo::addPoint(cx, cy, 0);
    const int q[4] = {geo::addPoint(cx + r, cy, 0), geo::addPoint(cx, cy + r, 0), geo::addPoint(cx - r, cy, 0),
                      geo::addPoint(cx, cy - r, 0)};
    std::vector<int> arcs;
    for (int a = 0; a < 4; ++a) arcs.push_back(geo::addCircleArc(q[a], c, q[(a + 1) % 4]));
    loops.push_back(geo::addCurveLoop(arcs));
    tags.pore_curves.push_back(arcs);
  }
  geo::addPlaneSurface(loops);
  geo::synchronize();
  // Pore boundaries get an exact node count (at least min_nodes_per_pore, so the smallest pore is
  // resolved however coarse the nominal spacing); edges and the interior follow the size field.
  for (std::size_t p = 0; p < cell.pores.size(); ++p) {
    const int per_arc = field.pore_boundary_segments(p) / 4;
    for (int arc : tags.pore_curves[p]) gmsh::model::mesh::setTransfiniteCurve(arc, per_arc + 1);
  }
  return tags;
}

std::vector<std::size_t> curve_node_tags(int curve) {
  std::vector<std::size_t> tags;
  std::vector<double> coord, param;
  gmsh::model::mesh::getNodes(tags, coord, param, 1, curve, true, false);
  return tags;
}

void compute_spacing(CellDiscretization& mesh) {
  std::vector<std::pair<std::int32_t, std::int32_t>> edges;
  edges.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles)
    for (int e = 0; e < 3; ++e) edges.emplace_back(std::minmax(t[e], t[(e + 1) % 3]));
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<double> sum(mesh.node_count(), 0.0);
  std::vector<int> count(mesh.node_count(), 0);
  for (const auto& [a, b] : edges) {
    const double l = std::hypot(mesh.nodes_m[a][0] - mesh.nodes_m[b][0], mesh.nodes_m[a][1] - mesh.nodes_m[b][1]);
    sum[a] += l, sum[b] += l;
    ++count[a], ++count[b];
  }
  mesh.spacing_m.resize(mesh.node_count());
  for (std::size_t i = 0; i < mesh.node_count(); ++i) mesh.spacing_m[i] = sum[i] / count[i];
}

CellDiscretization extract_mesh(const CellGeometry& cell, const GeometryTags& geometry) {
  std::vector<std::size_t> node_tags, element_tags, element_nodes;
  std::vector<double> coord, param;
  gmsh::model::mesh::getNodes(node_tags, coord, param, -1, -1, false, false);
  gmsh::model::mesh::getElementsByType(2, element_tags, element_nodes);  // 3-node triangles
  if (element_tags.empty()) throw NumericalError("gmsh produced no triangles for the cell");

  // Keep only nodes used by triangles (the pores' centre points are geometry, not mesh), numbered in
  // gmsh's tag order so the numbering is reproducible.
  std::map<std::size_t, std::size_t> position;  // gmsh tag -> index into coord
  for (std::size_t i = 0; i < node_tags.size(); ++i) position[node_tags[i]] = i;
  std::map<std::size_t, std::int32_t> index;  // gmsh tag -> our node
  for (std::size_t tag : element_nodes) index.emplace(tag, 0);
  CellDiscretization mesh;
  for (auto& [tag, i] : index) {
    i = static_cast<std::int32_t>(mesh.nodes_m.size());
    const std::size_t k = position.at(tag);
    mesh.nodes_m.push_back({coord[3 * k], coord[3 * k + 1]});
  }
  for (std::size_t e = 0; e < element_tags.size(); ++e) {
    std::array<std::int32_t, 3> t{index.at(element_nodes[3 * e]), index.at(element_nodes[3 * e + 1]),
                                  index.at(element_nodes[3 * e + 2])};
    mesh.triangles.push_back(t);
    const double a = mesh.triangle_area(mesh.triangles.size() - 1);
    if (a < 0.0) std::swap(mesh.triangles.back()[1], mesh.triangles.back()[2]);
    if (!(std::fabs(a) > 0.0)) throw NumericalError(fmt::format("gmsh produced a degenerate triangle ({})", e));
  }

  mesh.node_pore.assign(mesh.node_count(), -1);
  mesh.node_edges.assign(mesh.node_count(), 0);
  mesh.pore_nodes.resize(cell.pores.size());
  for (std::size_t p = 0; p < cell.pores.size(); ++p) {
    auto& list = mesh.pore_nodes[p];
    for (int curve : geometry.pore_curves[p])
      for (std::size_t tag : curve_node_tags(curve)) list.push_back(index.at(tag));
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    const Vec2 c = cell.pores[p].center_m;
    auto angle = [&](std::int32_t n) {
      const double a = std::atan2(mesh.nodes_m[n][1] - c.y, mesh.nodes_m[n][0] - c.x);
      return a < 0.0 ? a + 2.0 * M_PI : a;
    };
    std::sort(list.begin(), list.end(), [&](std::int32_t a, std::int32_t b) { return angle(a) < angle(b); });
    for (std::int32_t n : list) mesh.node_pore[n] = static_cast<std::int32_t>(p);
  }
  for (int e = 0; e < 4; ++e) {
    auto& list = mesh.edge_nodes[e];
    for (std::size_t tag : curve_node_tags(geometry.edge_curves[e])) list.push_back(index.at(tag));
    const int axis = e < 2 ? 1 : 0;  // left/right run along y, bottom/top along x
    std::sort(list.begin(), list.end(),
              [&](std::int32_t a, std::int32_t b) { return mesh.nodes_m[a][axis] < mesh.nodes_m[b][axis]; });
    for (std::int32_t n : list) mesh.node_edges[n] |= static_cast<std::uint8_t>(1u << e);
  }
  compute_spacing(mesh);
  return mesh;
}

}  // namespace

double CellDiscretization::triangle_area(std::size_t t) const {
  const auto& a = nodes_m[triangles[t][0]];
  const auto& b = nodes_m[triangles[t][1]];
  const auto& c = nodes_m[triangles[t][2]];
  return 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]));
}

double CellDiscretization::area_m2() const {
  double s = 0.0;
  for (std::size_t t = 0; t < triangles.size(); ++t) s += triangle_area(t);
  return s;
}

CellDiscretization mesh_cell(const CellGeometry& cell, const MeshOptions& options) {
  GmshSession::ensure();
  const CellSizeField field(cell, options);
  gmsh::model::add("uhpc_micro_cell");
  try {
    gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
    gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
    gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
    gmsh::option::setNumber("Mesh.Algorithm", 6);  // Frontal-Delaunay: well-shaped triangles
    gmsh::option::setNumber("Mesh.ElementOrder", 1);
    const GeometryTags geometry = build_geometry(cell, field);
    gmsh::model::mesh::setSizeCallback(
        [&field](int, int, double x, double y, double) -> double { return field(x, y); });
    gmsh::model::mesh::generate(2);
    gmsh::model::mesh::removeSizeCallback();
    CellDiscretization mesh = extract_mesh(cell, geometry);
    gmsh::model::remove();
    return mesh;
  } catch (const NumericalError&) {
    gmsh::model::mesh::removeSizeCallback();
    gmsh::model::remove();
    throw;
  } catch (const std::exception& e) {
    gmsh::model::mesh::removeSizeCallback();
    gmsh::model::remove();
    throw NumericalError(std::string("gmsh failed to mesh the cell: ") + e.what());
  }
}

}  // namespace uhpc::micro
