#pragma once
// Cracks as polylines and the geometry the enrichment and the quadrature need: which side of a crack
// a point is on, the tip ramp, and triangles cut by cracks split into pieces that each lie on one
// side of every crack line that crosses them.
//
// A crack is a polyline points[0..] with a root (points[0], on a pore or the cell edge: a closed end)
// and a tip. Only the first `active` segments carry a cohesive crack (are enriched); the rest of the
// points are a planned path (a seed not yet activated), activated segment by segment by the growth
// criterion. Beyond the planned path a crack grows freely (crack_growth.hpp) until it stops at a pore,
// the cell edge or another crack.
//
// [choice] Tip enrichment "ramped": the Heaviside enrichment of a crack whose tip is open (inside the
// matrix) is multiplied by R(x) = clamp(1 - s/l, 0, 1), s the position along the last active segment
// (length l) measured from its start: the jump is full behind the last segment, falls linearly to
// zero at the tip and vanishes beyond it, so the displacement is continuous ahead of a cohesive tip
// without singular tip functions. (The visibility criterion was the alternative; the ramp needs no
// change to the RK functions themselves and keeps them smooth.)
#include <array>
#include <cstddef>
#include <vector>

#include "cell_geometry.hpp"

namespace uhpc::micro {

enum class CrackEnd : unsigned char { Open, Pore, Edge, Crack };

struct Crack {
  std::vector<Vec2> points;  // root first; points[active] is the current tip
  std::size_t active = 0;    // active (cohesive) segments
  CrackEnd root = CrackEnd::Pore;
  CrackEnd tip_end = CrackEnd::Open;  // what stopped growth once the planned path is exhausted
  int seed = -1;                      // the CellGeometry seed it started from (-1: none)
  // A tip that stopped on another crack B (tip_end == Crack): the enrichment of this crack is cut off
  // on the far side of B (junction indicator, Daux et al. 2000), so no spurious discontinuity runs on
  // beyond B. junction_side is B's side (crack_side) that this crack lies on.
  int junction = -1;
  int junction_side = 0;

  std::size_t planned_segments() const { return points.size() - 1; }
  bool has_planned() const { return active < planned_segments(); }
  // The tip is open (ramped, may grow) unless the whole path is active and growth stopped.
  bool tip_open() const { return has_planned() || tip_end == CrackEnd::Open; }
  bool stopped() const { return !has_planned() && tip_end != CrackEnd::Open; }
  const Vec2& tip() const { return points[active]; }
  Vec2 segment_direction(std::size_t s) const;  // unit vector of segment s
  double active_length() const;
};

// Side of the active polyline: 1 on the left of its direction (root -> tip), 0 on the right.
// (H in {0, 1}: the shifted enrichment H(x) - H(x_J) and the jump H+ - H- = 1.) At a kink the
// pseudo-normal of the two segments decides, which is the correct side in the reflex wedge.
int crack_side(const Crack& c, const double* x);
// Unsigned distance from x to the active polyline (infinite when nothing is active).
double crack_distance(const Crack& c, const double* x);

// Ramp of the enrichment and its gradient (1 and 0 when the tip is closed).
double crack_ramp(const Crack& c, const double* x, double* grad);

// Quadrature pieces of a triangle cut by cracks: the triangle clipped by the line of every active
// segment that crosses it, fanned into sub-triangles. Empty when no active segment crosses it.
struct SubTriangle {
  std::array<std::array<double, 2>, 3> v;
};
std::vector<SubTriangle> split_triangle(const std::array<std::array<double, 2>, 3>& tri,
                                        const std::vector<Crack>& cracks);

// Does segment [a, b] cross (or touch) the closed triangle?
bool segment_meets_triangle(const double* a, const double* b, const std::array<std::array<double, 2>, 3>& tri);

// Intersection parameter t in [0, 1] of segment p + t (q - p) with segment [a, b]; -1 if none.
double segment_intersection(const Vec2& p, const Vec2& q, const Vec2& a, const Vec2& b);

}  // namespace uhpc::micro
