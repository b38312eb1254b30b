#pragma once
// What one microcell analysis hands to energy bridging and the ensemble: the load path of the
// uniaxial tension test, one record per converged (accepted) state, in the order the solver reached
// them. Plain data: the fracture solver fills it, energy_bridging and the run/ensemble drivers read it.
//
// Units: per unit thickness (plane strain, 2D), SI. e_bar need not be monotone (snap-back is traced by
// path following), but the states are a continuous path from the unloaded cell to separation.
#include <cstddef>
#include <string>
#include <vector>

namespace uhpc::micro {

struct CellState {
  double strain = 0.0;               // e_bar = imposed far-face displacement / l_mic
  double sigma_bar_Pa = 0.0;         // far-face reaction / l_mic (per unit thickness)
  double bulk_energy_J_m = 0.0;      // 1/2 int_Omega eps : D : eps (matrix, pores excluded)
  double cohesive_energy_J_m = 0.0;  // 1/2 int_cracks t . [[u]]: recoverable by secant unloading (eq. 20)
  double dissipated_J_m = 0.0;       // cumulative energy dissipated by the cohesive cracks
  double external_work_J_m = 0.0;    // int sigma_bar l_mic d(e_bar l_mic): the work balance check
  double jump_dissipated_J_m = 0.0;  // cumulative energy released in jumps the path could not follow
                                     // quasi-statically (JumpFallback::Relax): work = stored + dissipated + this
  double max_opening_m = 0.0;        // largest normal opening on any crack
  std::size_t crack_segments = 0;    // segments of all crack polylines (seeds included)
  std::size_t open_segments = 0;     // segments with some opening > 0 (cohesive or traction-free)
  int newton_iterations = 0;         // iterations of the step that produced this state
  // Stored + dissipated + released in jumps: the external work, on a path in balance.
  double accounted_energy_J_m() const {
    return bulk_energy_J_m + cohesive_energy_J_m + dissipated_J_m + jump_dissipated_J_m;
  }
};

enum class CellStatus {
  Separated,   // the cell carries (almost) no load any more: the path reached full separation
  ReachedEnd,  // reached the loading path's planned end (the strain grid's end or max_steps) before separating
  Failed       // the solver failed; `diagnostic` says where and why
};

struct CellResponse {
  double side_m = 0.0;
  double E0_bar_Pa = 0.0;            // homogenized modulus of the same cell before any crack opens
  double porosity = 0.0;
  std::vector<CellState> states;     // states[0] is the unloaded cell (all zeros)
  CellStatus status = CellStatus::Failed;
  std::string diagnostic;            // empty unless Failed (or a note on ReachedEnd)
  std::size_t nodes = 0, dofs = 0, enriched_nodes = 0;
  std::size_t growth_unloads = 0;    // growth events passed by unloading to zero (GrowthFallback)
  std::size_t jumps = 0;             // jumps taken by relaxation (JumpFallback::Relax, GrowthFallback::Relax)
  std::size_t factorizations = 0;    // numeric LU factorizations of the Newton matrix (the main cost)
  std::size_t crack_geometries = 0;  // enriched models built (each crack geometry, and each restore of one)
  std::size_t krylov_corrections = 0;  // Newton corrections solved by GMRES with an earlier factorization
  std::size_t krylov_products = 0;     // GMRES iterations over all of them (one triangular solve each)
  // Largest |operator energy - (bulk + boundary energy)| over the states, relative to the largest
  // external work so far (FractureSystem::operator_energy): 1e-2 on the elastic branch (VCI's
  // asymmetry); far above that, the cracked operator has a spurious soft mode and the path is suspect.
  double operator_energy_mismatch = 0.0;
  double wall_s = 0.0;
};

inline const char* to_string(CellStatus s) {
  switch (s) {
    case CellStatus::Separated: return "separated";
    case CellStatus::ReachedEnd: return "reached_end";
    case CellStatus::Failed: return "failed";
  }
  return "failed";
}

}  // namespace uhpc::micro
