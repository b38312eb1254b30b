#pragma once
// Energy bridging (docs/physics.md section 2, eq. 15-23): from one cell's load path (CellResponse) to its
// damage. Pure functions, no I/O.
//
// Per state (whole cell, pores included, per unit thickness; A = side^2):
//   Psi_bar  = (bulk + cohesive energy) / A                 (eq. 20, secant unloading)
//   Psi_0    = 1/2 E0_bar e^2
//   d_energy = 1 - Psi_bar / Psi_0                           (the paper's definition, eq. 23)
//   d_force  = 1 - sigma_bar / (E0_bar e)                    (the same through Hill-Mandel)
// Both are exactly 0 at e = 0 and in every state before a crack opens (open_segments == 0): there the
// ratios only measure the discretization's Hill-Mandel error, not damage. Their difference is the
// built-in consistency check (the issue asks for 1 %).
//
// The path may snap back (e_bar not monotone). A strain-controlled test cannot follow a snap-back: it
// jumps. [choice] StrainControl::FirstPassage (default): the curve d(e) is the state reached by
// increasing e monotonically, i.e. the first point of the path where the strain reaches e, with the
// damage taken as the running maximum along the path up to there (damage is irreversible). At the
// largest strain before a snap-back the curve jumps vertically to the state where the path first
// exceeds that strain again; after separation d = 1 and the stress is 0.
// StrainControl::MaxBelow: d(e) = max damage of the path states with e_i <= e (an envelope over the
// states only). On a snap-back it puts the jump at the smallest strain the snap-back reaches, i.e.
// before the peak strain, which a strain-controlled test never sees; kept as the alternative.
// On either curve the stress follows the path where the path is followed and is (1 - d) E0_bar e
// where the damage is held (the jumped and clipped parts).
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "cell_response.hpp"

namespace uhpc::micro {

enum class StrainControl { FirstPassage, MaxBelow };
// [choice] which damage drives the curves: the energy definition (eq. 23, default) or the force one.
enum class DamageMeasure { Energy, Force };

struct BridgingOptions {
  StrainControl strain_control = StrainControl::FirstPassage;
  DamageMeasure damage_measure = DamageMeasure::Energy;
};

const char* to_string(StrainControl c);
const char* to_string(DamageMeasure m);
std::optional<StrainControl> strain_control_from_name(std::string_view name);
std::optional<DamageMeasure> damage_measure_from_name(std::string_view name);

// The per-state quantities, one entry per CellState.
struct BridgedPath {
  double cell_area_m2 = 0.0;
  std::vector<double> psi_bar_J_m3;  // (bulk + cohesive) / A (J/m^3 = J/m per m^2 of the cell)
  std::vector<double> psi_0_J_m3;    // 1/2 E0_bar e^2
  std::vector<double> d_energy;      // raw (not clipped): the consistency check needs the raw values
  std::vector<double> d_force;
  std::vector<bool> cracked;         // open_segments > 0 and e != 0
  double max_abs_difference = 0.0;   // max |d_energy - d_force| over the states
  std::size_t max_difference_state = 0;
};

// Throws std::invalid_argument for a response that cannot be bridged (no states, side or E0_bar
// not positive, a non-finite value); the message names the state.
BridgedPath bridge_energy(const CellResponse& response);

// The damage of state i under `measure`, clipped to [0, 1] ([choice]: slightly negative values are
// round-off before the first crack grows, values above 1 a compressive residual at separation).
double bridged_damage(const BridgedPath& path, std::size_t i, DamageMeasure measure);

// The strain-controlled curve: vertices in non-decreasing strain (equal strains = a vertical jump),
// linear in between. `separated`: after the last vertex d = 1 and stress = 0; otherwise the data end
// at the last vertex.
struct ControlledCurve {
  std::vector<double> strain;
  std::vector<double> damage;     // in [0, 1], non-decreasing
  std::vector<double> stress_Pa;
  bool separated = false;
  std::size_t jumps = 0;          // vertical jumps inside the curve (snap-backs the path recovered from)
  bool snap_back = false;         // the path's strain fell back somewhere (also when it never recovered,
                                  // e.g. a snap-back straight to separation: the jump is then the end)
};

ControlledCurve strain_controlled_curve(const CellResponse& response, const BridgedPath& path,
                                        const BridgingOptions& options);

// The curve on a strain grid (ascending). At a vertical jump exactly on a grid strain the value
// before the jump is taken (the state a test at that strain holds). Beyond the end of a separated
// curve d = 1, stress 0; beyond the end of an unseparated one the last damage is held with stress
// (1 - d) E0_bar e, and `valid_points` says how many grid points the data cover. Never NaN.
struct ResampledCurve {
  std::vector<double> damage;
  std::vector<double> stress_Pa;
  std::size_t valid_points = 0;   // grid points with strain <= the curve's end (all when separated)
  bool complete = false;          // every grid point is covered by data
};

ResampledCurve resample(const ControlledCurve& curve, const std::vector<double>& grid, double E0_bar_Pa);

// Figures of one cell.
struct CurveFeatures {
  double peak_stress_Pa = 0.0;          // max sigma_bar over the path
  double strain_at_peak = 0.0;
  std::optional<double> strain_at_half_damage;  // first strain of the controlled curve with d >= 0.5
  double dissipated_J_m = 0.0;          // at the last state
  double dissipated_per_area_J_m3 = 0.0;
  double max_strain = 0.0;              // largest strain of the path
};

CurveFeatures curve_features(const CellResponse& response, const BridgedPath& path, const ControlledCurve& curve);

}  // namespace uhpc::micro
