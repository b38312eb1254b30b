#pragma once
// The RK Galerkin model with Heaviside-enriched cracks (docs/physics.md section 2):
//   u^h(x) = sum_I Psi_I(x) d_I + sum_cracks sum_J Psi_J(x) [H(x) - H(x_J)] R(x) a_J,
// H the side of the crack (0/1), R the tip ramp (crack_geometry.hpp). Node J of crack c carries a_J
// when its support is cut by the active part of c and the enriched function is not negligible on
// the support (its squared L2 norm over the support is at least min_enrichment_ratio times that of
// Psi_J; a support that barely touches a crack would make the system nearly singular). A node left out
// keeps the two faces tied by a sliver of its support beyond the crack, which carries load after
// separation: with direct derivatives (whose kernel part falls off as (1 - z)^2 at the support edge,
// against (1 - z)^3 for the implicit gradients) the one-pore strip kept 1.5 % of its peak stress at
// 1e-4; 1e-6 leaves 0.02 %, 1e-8 0.001 % (tests/verification/test_micro_cohesive_strip.cpp).
//
// Enriched DOFs are "generalized nodes" n + k (2 DOFs each, like a node), so every point carries one
// compressed row of (generalized node, value, trial gradient, test gradient) and the assembly treats
// standard and enriched functions alike. Domain quadrature: the base model's points in uncut
// triangles, the triangle pieces on each side of the cracks in cut ones (split_triangle). With the
// base model's VCI option the test gradients of all functions, standard and enriched, get the VCI
// constant computed on this quadrature with the crack faces as internal boundaries (enrichment.cpp).
// Cohesive points: Gauss points along each active segment, with the jump operator
// [[u]](x) = sum_J Psi_J(x) R(x) a_J over the crack's enriched nodes (standard parts cancel).
#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "cell_mesh.hpp"
#include "crack_geometry.hpp"
#include "rk_galerkin_model.hpp"

namespace uhpc::micro {

struct GeneralTable {
  NeighbourList support;  // generalized node ids per point
  std::vector<double> psi, grad, test_grad;  // grad/test_grad: 2 per entry
  std::size_t size() const { return support.size(); }

  // Strain (xx, yy, engineering xy) at point p of the coefficients d (2 per generalized node), from the
  // trial gradients.
  template <class Vector>
  std::array<double, 3> strain(std::size_t p, const Vector& d) const {
    std::array<double, 3> eps{0.0, 0.0, 0.0};
    for (std::int64_t e = support.begin(p); e < support.end(p); ++e) {
      const std::int32_t i = support.indices[static_cast<std::size_t>(e)];
      eps[0] += grad[2 * e] * d[2 * i];
      eps[1] += grad[2 * e + 1] * d[2 * i + 1];
      eps[2] += grad[2 * e + 1] * d[2 * i] + grad[2 * e] * d[2 * i + 1];
    }
    return eps;
  }
};

struct CohesivePoint {
  std::array<double, 2> x;
  double weight;                    // length
  std::array<double, 2> normal;     // towards the H = 1 side
  std::int32_t crack, segment, gauss;
  std::int64_t begin, end;          // entries in EnrichedModel::jump (enriched gnode, coefficient)
};

// [choice] The integration correction of the cracked model (once a segment is active; before, the
// base model's RkGalerkinOptions::correction holds, so the elastic branch and E0_bar stay those of
// the patch-tested elastic analysis). None (default): plain Gauss on the cut pieces, a symmetric
// Galerkin operator. Vci: the VCI constants recomputed with the crack faces as internal boundaries
// (apply_vci in enrichment.cpp), the default before. Measured (micro/README.md, "The reload failure of
// 5.0 mm #3"): VCI's Petrov-Galerkin operator can lose definiteness on a cracked porous cell (on that
// reload 1/2 p.K_lin.p along Newton's directions fell to -1.3e3 where the bulk energy of the same p
// was +18, and Newton found no equilibrium at any load scale); with None the four cells of the
// 24-cell study that failed or broke a check finish clean. Its known weakness: the long strip under
// displacement control no longer re-equilibrates after growth at its peak (growth unloads, then a jump
// below the peak that releases 10 % too little; micro/README.md), so that test keeps Vci.
struct EnrichmentOptions {
  double min_enrichment_ratio = 1e-6;  // [choice] see above
  int crack_points = 4;                // Gauss points per crack segment (1..5)
  IntegrationCorrection cracked_correction = IntegrationCorrection::None;
};

struct EnrichedModel {
  std::size_t standard_nodes = 0;
  std::vector<std::int32_t> enriched_node;   // per enriched gnode k (id n + k): the RK node
  std::vector<std::int32_t> enriched_crack;  // and its crack
  std::vector<double> x, weight;             // domain points
  GeneralTable domain;
  GeneralTable boundary;                     // at the base model's boundary points (same order)
  GeneralTable constraints;                  // at the constraint points
  std::vector<CohesivePoint> cohesive;
  std::vector<std::int32_t> jump_node;       // enriched gnode ids
  std::vector<double> jump_coefficient;      // Psi_J R at the cohesive point
  std::size_t cut_triangles = 0;

  std::size_t gnode_count() const { return standard_nodes + enriched_node.size(); }
  std::size_t dof_count() const { return 2 * gnode_count(); }
};

EnrichedModel build_enriched_model(const RkGalerkinModel& base, const CellDiscretization& mesh, const std::vector<Crack>& cracks,
                                   const std::vector<std::array<double, 2>>& constraint_points,
                                   const EnrichmentOptions& options);

// Enriched shape functions at arbitrary points (stress sampling); test_grad = grad.
GeneralTable enriched_table_at(const RkGalerkinModel& base, const EnrichedModel& em, const std::vector<Crack>& cracks,
                               const std::vector<double>& points);

// The displacement (2 per point) of the coefficients d of model em (built on `cracks`) at the points x of
// `rows`, a GeneralTable on the same base model but possibly another crack geometry: only the
// standard entries of its rows are used, em's enrichment is evaluated anew (field_transfer.hpp).
std::vector<double> enriched_displacement(const RkGalerkinModel& base, const EnrichedModel& em,
                                          const std::vector<Crack>& cracks, const GeneralTable& rows,
                                          const std::vector<double>& x, const Eigen::VectorXd& d);

}  // namespace uhpc::micro
