#pragma once
// The RK Galerkin discretization of a cell: RK nodes = mesh nodes with support radius
// a_I = support_factor x spacing_I, Gauss points in every triangle (domain) and on every boundary
// segment, and the RK shape functions with implicit gradients at all of them (common/rk_shape).
//
// Variationally consistent integration (Chen, Hillman and Rueter 2013, "VCI"): Gauss quadrature of
// RK functions does not satisfy the integration constraint sum_q grad Psi_I(x_q) w_q =
// sum_b Psi_I(x_b) n_b w_b that the linear patch test needs (the implicit gradients are not even the
// exact derivatives of Psi_I). The correction adds a constant xi_I per node to the *test* gradients
// on its support so that the constraint holds exactly with the quadrature used; the trial gradients
// stay the implicit ones, which reproduce linear fields exactly. The scheme is Petrov-Galerkin, so the
// stiffness matrix is not symmetric (the solver follows that, sparse_solver.hpp).
#include <array>
#include <cstdint>
#include <vector>

#include "boundary_segments.hpp"
#include "cell_mesh.hpp"
#include "uhpc/rk_shape.hpp"

namespace uhpc::micro {

enum class IntegrationCorrection : std::uint8_t { None, Vci };

struct RkGalerkinOptions {
  double support_factor = 2.0;      // [choice] a_I / spacing_I (docs/physics.md: 1.5 .. 2.0)
  KernelType kernel = KernelType::CubicBSpline;
  int triangle_points = 6;          // [choice] Dunavant rule: 1, 3, 6, 7 or 12 points
  int segment_points = 3;           // [choice] Gauss-Legendre points per boundary segment, 1..5
  IntegrationCorrection correction = IntegrationCorrection::Vci;  // [choice]
  // [choice] trial and test gradients before the correction: the direct derivatives of Psi_I (default)
  // or the implicit RK gradients (rk_shape.hpp). See the header: with implicit ones the VCI constants
  // are large and the Petrov-Galerkin operator of a cracked porous cell can lose definiteness.
  rk::Derivatives derivatives = rk::Derivatives::Direct;
};

// Points with their shape functions, in compressed rows (table.support.row(p) = nodes of point p).
struct PointSet {
  std::vector<double> x;       // 2 per point
  std::vector<double> weight;  // quadrature weight (area or length), 0 for sample points
  rk::ShapeTable table;        // psi and implicit (trial) gradients
  std::size_t size() const { return weight.size(); }
};

struct BoundaryPoints : PointSet {
  std::vector<std::int32_t> segment;  // the BoundarySegment of each point
};

struct RkGalerkinModel {
  RkGalerkinOptions options;
  std::vector<double> nodes;           // 2 per node
  std::vector<double> support_radius;  // per node
  PointSet domain;
  std::vector<double> test_grad;       // domain test gradients (2 per entry of domain.table), VCI-corrected
  std::vector<BoundarySegment> segments;
  BoundaryPoints boundary;
  double vci_max_correction = 0.0;     // max |xi_I| a_I (dimensionless), 0 without VCI

  std::size_t node_count() const { return support_radius.size(); }
  std::size_t dof_count() const { return 2 * node_count(); }
};

// Builds the model; throws uhpc::NumericalError when a quadrature point has no covering node or an
// invalid option reaches it (the settings validate options first).
RkGalerkinModel build_rk_galerkin_model(const CellDiscretization& mesh, const RkGalerkinOptions& options);

// Shape functions at arbitrary points of the cell (stress sampling, point constraints); weights 0.
PointSet sample_points(const RkGalerkinModel& model, const std::vector<std::array<double, 2>>& points);

}  // namespace uhpc::micro
