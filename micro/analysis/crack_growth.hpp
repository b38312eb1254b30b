#pragma once
// Crack initiation and growth (docs/physics.md section 2, [choice]): a tip advances by a fixed increment
// (about one nodal spacing) when the stress averaged over a half disc of radius ~2 spacings ahead of
// it reaches f_t. Along a planned path (a seed, or a prescribed crack path) the next segment is
// activated when the averaged normal stress across it reaches f_t; beyond the path the criterion is
// the maximum principal stress of the averaged stress tensor, and the crack turns normal to it.
// A crack stops when it reaches a pore, another crack (junction) or the cell edge. No remeshing and
// no particle deletion: only the crack polylines change.
#include <vector>

#include "cell_geometry.hpp"
#include "cell_mesh.hpp"
#include "crack_geometry.hpp"

namespace uhpc::micro {

struct GrowthOptions {
  double increment_spacings = 1.0;       // [choice] tip advance / local nodal spacing
  double average_radius_spacings = 2.0;  // [choice] radius of the averaging half disc / local spacing
  // [choice] a tip passing this close (x increment) to another crack joins it. Off by default: in the
  // one porous cell tried (3.0 mm, seed 1, 80 um) the joins made re-equilibration fail repeatedly and
  // the step shrink to nothing; without them two parallel cracks can overlap with an uncut sliver
  // between them (the residual ~2 MPa tail measured on that cell). Unfinished.
  double coalescence_spacings = 0.0;
};

// Cracks from the cell's seeds: each seed is a planned path from its root (on its pore, or on the cell
// edge when seed.pore < 0) to its tip, cut into segments of about one increment. Nothing is active.
std::vector<Crack> cracks_from_seeds(const CellGeometry& cell, const CellDiscretization& mesh,
                                     const GrowthOptions& options);

struct TipCriterion {
  double stress_Pa = 0.0;   // averaged normal (planned) or maximum principal (free) stress
  Vec2 direction{1.0, 0.0};  // direction the tip would advance in
  bool valid = false;        // false for stopped cracks (and when no sample point is in the matrix)
};

// Sample points of the averaging half disc of each crack (flattened x, y) and their crack; points
// inside pores or outside the cell are left out.
struct TipSamples {
  std::vector<double> x;
  std::vector<int> crack;
};
TipSamples tip_samples(const CellGeometry& cell, const CellDiscretization& mesh, const std::vector<Crack>& cracks,
                       const GrowthOptions& options);

// The criterion per crack from the stresses (xx, yy, xy) at the samples.
std::vector<TipCriterion> tip_criteria(const std::vector<Crack>& cracks, const TipSamples& samples,
                                       const std::vector<std::array<double, 3>>& stress);

// Advances crack `c` by one increment: activates its next planned segment, or adds a segment in
// `direction` (clipped at pores, the cell edge and other cracks, which stop it). Returns false when
// the crack could not advance.
bool advance_crack(std::vector<Crack>& cracks, std::size_t c, const Vec2& direction, const CellGeometry& cell,
                   const CellDiscretization& mesh, const GrowthOptions& options);

// Nodal spacing of the mesh node nearest to x.
double local_spacing(const CellDiscretization& mesh, const Vec2& x);

}  // namespace uhpc::micro
