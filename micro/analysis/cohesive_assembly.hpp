#pragma once
// The nonlinear system of a cracked cell on an EnrichedModel, for the uniaxial test whose far face is
// displaced by lambda (metres): the residual
//   r(d, lambda) = K_lin d - lambda f_unit + f_coh(d),
// K_lin the bulk stiffness (VCI-corrected domain term over standard and enriched functions, Nitsche
// terms on the loaded faces, the transverse point penalty), f_unit the Nitsche load of a unit far-face
// displacement, f_coh the cohesive forces int [[v]] . t([[u]]) over the crack segments, and its
// consistent tangent K_T = K_lin + K_coh. The sparsity is fixed when the system is built (bulk and
// cohesive couplings); K_lin is assembled once per crack geometry, only the cohesive part per
// iteration (cohesive points are few), so nothing in the Newton loop rebuilds the pattern.
#include <Eigen/Sparse>
#include <vector>

#include "cohesive_law.hpp"
#include "elastic_problem.hpp"
#include "enrichment.hpp"

namespace uhpc::micro {

// Committed state of one cohesive point (indexed like EnrichedModel::cohesive).
struct CohesiveHistory {
  double kappa = 0.0;             // history maximum of the effective opening (starts at w0)
  double shear_dissipated = 0.0;  // J/m^2: sliding work lost while the secant stiffness fell
  double sliding = 0.0;           // w_t of the committed state (for the midpoint rule above)
};

struct CohesiveEvaluation {
  std::vector<CohesiveHistory> trial;  // updated history
  std::vector<std::array<double, 2>> opening;   // (w_n, w_t)
  std::vector<std::array<double, 2>> traction;  // (t_n, t_t)
};

// A viscous term on the crack openings, t += stiffness (w - reference) per cohesive point (local
// frame (w_n, w_t), indexed like EnrichedModel::cohesive): the implicit pseudo-time step of the
// relaxation that carries a cell through a jump it cannot follow quasi-statically (cell_analysis.cpp).
struct OpeningViscosity {
  double stiffness_Pa_m = 0.0;
  const std::vector<std::array<double, 2>>* reference = nullptr;
};

class FractureSystem {
 public:
  // `unit_problem`: the uniaxial ElasticProblem with far-face displacement 1 (uniaxial_problem with
  // strain 1/side); `far`/`axis`: the face and component whose reaction is sigma_bar.
  FractureSystem(const RkGalerkinModel& base, const EnrichedModel& em, const ElasticProblem& unit_problem,
                 BoundaryPart far, int axis);

  std::size_t dofs() const { return static_cast<std::size_t>(f_unit_.size()); }
  const Eigen::VectorXd& unit_load() const { return f_unit_; }

  // Residual (and, with `tangent`, the tangent into the internal value array) at (d, lambda), with the
  // viscous term when `viscosity` is given (eval.traction stays the cohesive law's own).
  void evaluate(const Eigen::VectorXd& d, double lambda, const CohesiveLaw& law,
                const std::vector<CohesiveHistory>& committed, bool tangent, Eigen::VectorXd& residual,
                CohesiveEvaluation& eval, const OpeningViscosity* viscosity = nullptr);

  // The bordered tangent [[K_T, -f_unit], [row^T, corner]] of the last evaluate(.., tangent = true).
  Eigen::SparseMatrix<double> bordered(const Eigen::VectorXd& row, double corner) const;

  // c(d) = sum over active cohesive points of w n . [[u]] (the crack-opening control), and its gradient.
  double opening_integral(const Eigen::VectorXd& d) const;
  Eigen::VectorXd opening_gradient() const;
  // The same sum over the cohesive points with selected[p] != 0 only (the process-zone control).
  Eigen::VectorXd opening_gradient(const std::vector<char>& selected) const;

  double reaction(const Eigen::VectorXd& d, double lambda) const;  // far-face force per unit thickness
  double bulk_energy(const Eigen::VectorXd& d) const;              // 1/2 int eps : D : eps
  // The Nitsche terms' and the point penalties' share of the stored energy (may be negative).
  double boundary_energy(const Eigen::VectorXd& d, double lambda) const;
  // The quadratic form of the linear operator, 1/2 d.K_lin d - lambda f_unit.d + 1/2 lambda^2 k: with
  // a symmetric positive K_lin it equals bulk + boundary energy. VCI makes K_lin non-symmetric; where
  // its symmetric part loses definiteness the two part ways (a consistency check of the discretization).
  double operator_energy(const Eigen::VectorXd& d, double lambda) const;

 private:
  const RkGalerkinModel& base_;
  const EnrichedModel& em_;
  ElasticProblem problem_;
  BoundaryPart far_;
  int axis_;
  std::array<double, 9> D_;
  // Compressed columns over DOFs (2 per generalized node), fixed pattern.
  std::vector<std::int64_t> node_start_;
  std::vector<std::int32_t> node_rows_;
  std::vector<int> col_start_, rows_;
  std::vector<double> lin_, values_;
  Eigen::VectorXd f_unit_;
  double k_lambda_ = 0.0;  // d reaction / d lambda at fixed d (the far face's Nitsche penalty)

  void add_block(std::vector<double>& v, std::int32_t i, std::int32_t j, const double b[2][2]) const;
  // Displacement and traction at boundary point p (of segment seg).
  void boundary_point(std::size_t p, const BoundarySegment& seg, const Eigen::VectorXd& d, std::array<double, 2>& u,
                      std::array<double, 2>& t) const;
};

}  // namespace uhpc::micro
