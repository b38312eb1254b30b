#pragma once
// The boundary of the discretized cell as segments: mesh edges used by exactly one triangle. Each
// segment knows the part of the boundary it lies on (one of the four cell edges, or a pore), and its
// outward unit normal from the counter-clockwise orientation of its triangle. The Nitsche terms, the
// tractions and the variationally consistent correction integrate over these segments.
#include <array>
#include <cstdint>
#include <vector>

#include "cell_mesh.hpp"

namespace uhpc::micro {

// Where a boundary segment lies. The first four match the order of CellDiscretization::edge_nodes.
enum class BoundaryPart : std::uint8_t { Left = 0, Right = 1, Bottom = 2, Top = 3, Pore = 4 };
constexpr int kBoundaryParts = 5;

struct BoundarySegment {
  std::array<std::int32_t, 2> nodes;  // in the direction that keeps the domain on the left
  BoundaryPart part;
  std::int32_t pore = -1;             // the pore, for BoundaryPart::Pore
  std::array<double, 2> normal;       // outward unit normal
  double length_m;
};

// Throws uhpc::NumericalError when a boundary edge cannot be classified (its end nodes are not on a
// common cell edge or pore), which would mean the mesh and its node flags disagree.
std::vector<BoundarySegment> boundary_segments(const CellDiscretization& mesh);

}  // namespace uhpc::micro
