#pragma once
// An SVG picture of a cell (the paper's Fig. 5): the square, the pores, the crack seeds and,
// optionally, the mesh. Produces a string; the driver writes it.
#include <string>

#include "cell_geometry.hpp"
#include "cell_mesh.hpp"

namespace uhpc::micro {

struct PictureOptions {
  int size_px = 800;        // width and height of the picture
  bool show_mesh = false;   // draw the triangles and the RK nodes
  std::string caption;      // printed under the cell ("" for none)
};

// `mesh` may be nullptr (geometry only); it is drawn only when options.show_mesh is set.
std::string cell_svg(const CellGeometry& cell, const CellDiscretization* mesh, const PictureOptions& options);

}  // namespace uhpc::micro
