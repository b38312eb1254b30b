#pragma once
// Discretization of the porous cell (square minus disks) for the RKPM analysis: gmsh triangulates it
// with a size field that is fine at the pore boundaries and around the crack seeds and grows into the
// matrix. The mesh nodes become RK nodes, each with its own nodal spacing; the triangles become the
// integration cells. The result is plain data; gmsh stays inside cell_mesh.cpp.
#include <array>
#include <cstdint>
#include <vector>

#include "cell_geometry.hpp"

namespace uhpc::micro {

struct MeshOptions {
  double nominal_spacing_m = 50e-6;  // [choice] spacing in the matrix away from pores and seeds
  double boundary_ratio = 0.5;       // [choice] spacing at pore boundaries and seeds / nominal spacing
  int min_nodes_per_pore = 8;        // every pore boundary, the smallest (77 um) included, gets at least this
  double grading = 0.3;              // [choice] spacing growth per unit distance from a pore or seed
};

// Target element size at a point: min(nominal, min over pores of s_p + g d_p, min over seeds of
// s_f + g d_f), d the distance to the pore boundary (or seed segment), s_f = boundary_ratio x
// nominal, s_p = min(s_f, pi D_p / min_nodes_per_pore).
class CellSizeField {
 public:
  CellSizeField(const CellGeometry& cell, const MeshOptions& options);
  double operator()(double x, double y) const;
  // Number of segments (= nodes) on pore p's boundary: at least min_nodes_per_pore, a multiple of 4
  // (the circle is meshed as four arcs).
  int pore_boundary_segments(std::size_t p) const;
  double pore_boundary_size(std::size_t p) const { return pore_size_[p]; }

 private:
  // Features (pores, then seeds) matter only where their size s + g d is below the nominal spacing,
  // i.e. within reach_ of them: a uniform grid of buckets of edge reach_ lists, per bucket, the
  // features whose reach covers it, so a query visits a handful of features, not all of them.
  std::size_t bucket_of(double x, double y) const;

  const CellGeometry* cell_;
  MeshOptions options_;
  std::vector<double> pore_size_;
  double reach_ = 0.0;
  int buckets_ = 1;                       // per side
  std::vector<std::vector<int>> bucket_;  // feature ids: pore p -> p, seed s -> pores + s
};

// Bit flags of the cell edges a node lies on.
enum CellEdge : std::uint8_t { kEdgeLeft = 1, kEdgeRight = 2, kEdgeBottom = 4, kEdgeTop = 8 };

struct CellDiscretization {
  std::vector<std::array<double, 2>> nodes_m;      // RK node positions
  std::vector<double> spacing_m;                   // per node: mean length of its mesh edges
  std::vector<std::array<std::int32_t, 3>> triangles;  // integration cells, counter-clockwise
  std::vector<std::int32_t> node_pore;             // pore whose boundary holds the node, -1 if none
  std::vector<std::uint8_t> node_edges;            // CellEdge flags (corners carry two)
  std::vector<std::vector<std::int32_t>> pore_nodes;  // per pore: its boundary nodes, counter-clockwise
                                                      // from the point at angle 0
  std::array<std::vector<std::int32_t>, 4> edge_nodes;  // left, right, bottom, top; sorted along the edge

  std::size_t node_count() const { return nodes_m.size(); }
  std::size_t triangle_count() const { return triangles.size(); }
  double area_m2() const;  // sum of the triangle areas
  double triangle_area(std::size_t t) const;
};

// Meshes the cell. Not thread-safe: gmsh is one global state per process, so call it outside any
// OpenMP region (it initializes gmsh on first use, silenced, and keeps it for the process).
// Throws uhpc::NumericalError if gmsh fails or returns a degenerate mesh.
CellDiscretization mesh_cell(const CellGeometry& cell, const MeshOptions& options);

}  // namespace uhpc::micro
