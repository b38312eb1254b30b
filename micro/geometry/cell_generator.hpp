#pragma once
// Random porous microcells (docs/physics.md section 1): pore diameters drawn from the truncated Burr XII
// law until the target area porosity is met, placed largest first by random sequential addition,
// with a minimum ligament between pores and to the cell edges, and crack seeds at the points where
// uniaxial tension concentrates the hoop stress. Deterministic for a given seed. No I/O.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "burr.hpp"
#include "cell_geometry.hpp"

namespace uhpc::micro {

struct PorosityOptions {
  double target = 0.034;       // area porosity (eq. 32)
  double tolerance = 0.0005;   // [choice] stop when |phi - target| <= tolerance (absolute)
  long long max_draws = 1000000;  // give up (unreachable porosity) after this many Burr draws
};

struct PlacementOptions {
  double min_ligament_m = 150e-6;   // [choice] matrix between two pores and between a pore and an edge
  long long max_attempts_per_pore = 100000;  // random positions tried before the pore counts as unplaceable
};

struct SeedOptions {
  // [choice] seeds per pore at the hoop-stress maxima of uniaxial tension (the two points of the pore
  // whose outward normal is perpendicular to the load): 2 = both, 1 = one of them at random, 0 = none.
  int per_pore = 2;
  double length_m = 50e-6;  // [choice] about one nodal spacing
  // [choice] 0 = normal to the load (radially outward at those points); otherwise the seed is turned
  // by this angle (counter-clockwise, radians) about its root. |tilt| < pi/2.
  double tilt_rad = 0.0;
};

struct CellOptions {
  double side_m = 0.003;
  BurrParameters burr;
  double truncation_m = 1.3e-3;  // [choice] the fit's upper bound
  PorosityOptions porosity;
  PlacementOptions placement;
  SeedOptions seeds;
  LoadAxis load = LoadAxis::X;
};

// What happened while generating (for statistics and diagnostics, not part of the geometry).
struct GenerationRecord {
  std::vector<double> drawn_diameters_m;  // every Burr draw, accepted or not, in draw order
  long long rejected_draws = 0;            // draws that would have overshot the porosity budget
  long long placement_attempts = 0;        // random positions tried in total
};

struct GeneratedCell {
  CellGeometry geometry;
  GenerationRecord record;
  std::uint64_t seed = 0;
};

// Why a cell cannot be generated with the given options (the driver turns it into an input error
// naming the responsible key).
class CellGenerationError : public std::runtime_error {
 public:
  enum class Reason { CellTooSmall, UnreachablePorosity, PlacementFailed, BadOption };
  CellGenerationError(Reason reason, const std::string& message) : std::runtime_error(message), reason_(reason) {}
  Reason reason() const { return reason_; }

 private:
  Reason reason_;
};

// Checks option combinations that make generation impossible before drawing anything (cell smaller
// than the smallest pore plus two ligaments, porosity band below one smallest pore, seeds longer than
// half a ligament, ...). Throws CellGenerationError.
void check_cell_options(const CellOptions& options);

GeneratedCell generate_cell(const CellOptions& options, std::uint64_t seed);

// Seed of realization `realization` of size `size_index` in an ensemble with `base_seed`: a
// SplitMix64 hash chain, kept below 2^53 so that JSON readers that use doubles hold it exactly.
std::uint64_t derive_cell_seed(std::uint64_t base_seed, std::uint64_t size_index, std::uint64_t realization);

// The unit vector normal to the load (the direction of the seeds at tilt 0).
Vec2 load_normal(LoadAxis load);

}  // namespace uhpc::micro
