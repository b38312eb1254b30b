// The Newton solver of the crack analysis (micro/analysis/bordered_tangent_solver.hpp): every
// correction solves the bordered system it was asked for, whichever way it went (a fresh LU, a
// low-rank update of an older one or GMRES preconditioned with it, or the reused tangent at the start
// of a path step), and factorizations are spent only where the solver says they are.
#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "bordered_tangent_solver.hpp"
#include "sparse_test_matrices.hpp"

namespace uhpc::micro {
namespace {

using test::random_vector;

// [[K, -f], [s g^T, s c]] as FractureSystem::bordered builds it.
Eigen::SparseMatrix<double> bordered(const Eigen::SparseMatrix<double>& K, const Eigen::VectorXd& f,
                                     const Eigen::VectorXd& g, double c, double s) {
  const Eigen::Index n = K.rows();
  std::vector<Eigen::Triplet<double>> t;
  for (int k = 0; k < K.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(K, k); it; ++it) t.emplace_back(it.row(), it.col(), it.value());
  for (Eigen::Index i = 0; i < n; ++i) {
    t.emplace_back(i, n, -f[i]);
    if (g[i] != 0.0) t.emplace_back(n, i, s * g[i]);
  }
  t.emplace_back(n, n, s * c);
  Eigen::SparseMatrix<double> J(n + 1, n + 1);
  J.setFromTriplets(t.begin(), t.end());
  return J;
}

// The unscaled system's residual of a correction x for (r, cres): |[K, -f; g^T, c] x + (r, cres)|.
double system_residual(const Eigen::SparseMatrix<double>& K, const Eigen::VectorXd& f, const Eigen::VectorXd& g,
                       double c, const Eigen::VectorXd& x, const Eigen::VectorXd& r, double cres) {
  const Eigen::Index n = K.rows();
  Eigen::VectorXd e(n + 1);
  e.head(n) = K * x.head(n) - f * x[n] + r;
  e[n] = g.dot(x.head(n)) + c * x[n] + cres;
  return e.norm();
}

// A bordered tangent in the solver's parts: K = K_fixed + sum_p Q_p C_p Q_p^T over `points` "cohesive
// points", each coupling three unknowns through its two jump columns.
struct Problem : BorderedTangent {
  static constexpr int points = 8;
  Eigen::SparseMatrix<double> K_fixed = test::convection_diffusion(12);  // the "bulk", 144 unknowns
  Eigen::SparseMatrix<double> Q{144, 2 * points};
  std::vector<std::array<double, 4>> C = std::vector<std::array<double, 4>>(points, {0.4, 0.1, -0.2, 0.3});
  Eigen::VectorXd f = random_vector(144, 1), g = random_vector(144, 2), r = random_vector(144, 3);
  double c = 0.0;  // an opening hold
  double cres = 0.25;
  mutable int assemblies = 0;

  Problem() {
    std::vector<Eigen::Triplet<double>> t;
    for (int p = 0; p < points; ++p)
      for (int a = 0; a < 2; ++a)
        for (int k = 0; k < 3; ++k) t.emplace_back(17 * p + 2 * k + a, 2 * p + a, 0.5 + 0.25 * k);
    Q.setFromTriplets(t.begin(), t.end());
  }
  Eigen::SparseMatrix<double> K() const {
    Eigen::MatrixXd k = K_fixed;
    for (int p = 0; p < points; ++p) {
      Eigen::Matrix2d Cp;
      Cp << C[p][0], C[p][1], C[p][2], C[p][3];
      const Eigen::MatrixXd Qp = Q.middleCols(2 * p, 2);
      k += Qp * Cp * Qp.transpose();
    }
    return k.sparseView();
  }
  Eigen::SparseMatrix<double> matrix(double s) const override {
    ++assemblies;
    return bordered(K(), f, g, c, s);
  }
  Eigen::VectorXd constraint_row() const override {
    Eigen::VectorXd row(145);
    row << g, c;
    return row;
  }
  const Eigen::SparseMatrix<double>& point_columns() const override { return Q; }
  const std::vector<std::array<double, 4>>& point_blocks() const override { return C; }
  // A change at the first `n` points (a low-rank change of the tangent, rank 2 each).
  void soften(int n) {
    for (int p = 0; p < n; ++p) {
      C[p][0] -= 1.5;
      C[p][3] -= 0.5;
    }
  }
  double residual_of(const Eigen::VectorXd& x, const Eigen::VectorXd& rr, double cr) const {
    return system_residual(K(), f, g, c, x, rr, cr);
  }
};

TangentSolverOptions low_rank(int max_rank = 64) { return {TangentUpdate::LowRank, max_rank, 16}; }
TangentSolverOptions gmres(int iterations = 16) { return {TangentUpdate::Gmres, 64, iterations}; }

class EitherUpdate : public ::testing::TestWithParam<TangentUpdate> {
 protected:
  TangentSolverOptions options() const { return GetParam() == TangentUpdate::LowRank ? low_rank() : gmres(); }
};

TEST_P(EitherUpdate, AFreshTangentIsFactorizedAndItsCorrectionSolvesTheUnscaledSystem) {
  for (const double row_scale : {1.0, 1e6}) {
    Problem p;
    BorderedTangentSolver solver(options());
    const auto x = solver.solve(7, false, row_scale, p, p.r, p.cres, 1e-9);
    ASSERT_TRUE(x.ok) << x.why;
    EXPECT_LE(p.residual_of(x.x, p.r, p.cres), 1e-10) << row_scale;
    EXPECT_EQ(solver.factorizations(), 1u);
    EXPECT_EQ(solver.krylov_corrections() + solver.update_corrections(), 0u);
    EXPECT_EQ(p.assemblies, 1);
  }
}

TEST_P(EitherUpdate, ALowRankChangeOfTheSamePatternIsSolvedWithoutAFactorization) {
  Problem p;
  BorderedTangentSolver solver(options());
  ASSERT_TRUE(solver.solve(7, false, 1.0, p, p.r, p.cres, 1e-9).ok);
  p.soften(3);
  const double tolerance = 1e-9;
  const auto x = solver.solve(7, false, 1.0, p, p.r, p.cres, tolerance);
  ASSERT_TRUE(x.ok) << x.why;
  EXPECT_EQ(solver.factorizations(), 1u);
  EXPECT_LE(p.residual_of(x.x, p.r, p.cres), 0.01 * tolerance * 1.0001);
  if (GetParam() == TangentUpdate::Gmres) {
    EXPECT_EQ(solver.krylov_corrections(), 1u);
    EXPECT_LE(solver.krylov_products(), 7u);  // rank 6 + 1
  } else {
    EXPECT_EQ(solver.update_corrections(), 1u);
    EXPECT_EQ(solver.update_columns(), 6u);  // two per changed point
  }
}

TEST_P(EitherUpdate, WithoutUpdatesEveryNewTangentIsFactorized) {
  Problem p;
  BorderedTangentSolver solver(GetParam() == TangentUpdate::LowRank ? low_rank(0) : gmres(0));
  for (int it = 0; it < 3; ++it) {
    const auto x = solver.solve(7, false, 1.0, p, p.r, p.cres, 1e-9);
    ASSERT_TRUE(x.ok) << x.why;
    EXPECT_LE(p.residual_of(x.x, p.r, p.cres), 1e-10);
    p.soften(1);
  }
  EXPECT_EQ(solver.factorizations(), 3u);
  EXPECT_EQ(solver.krylov_corrections() + solver.update_corrections(), 0u);
}

TEST_P(EitherUpdate, TheStartOfAPathStepReusesTheLastTangentWithoutAssemblingOne) {
  Problem p;
  BorderedTangentSolver solver(options());
  ASSERT_TRUE(solver.solve(7, false, 1.0, p, p.r, p.cres, 1e-9).ok);
  p.soften(1);  // a correction on a changed tangent (updated, not factorized) ...
  ASSERT_TRUE(solver.solve(7, false, 1.0, p, p.r, p.cres, 1e-9).ok);
  const Problem last = p;
  p.soften(2);  // ... then the state moved on: a fresh tangent would differ
  const Eigen::VectorXd r2 = random_vector(144, 9);
  const auto x = solver.solve(7, true, 1.0, p, r2, -0.5, 1e-9);
  ASSERT_TRUE(x.ok) << x.why;
  EXPECT_EQ(solver.factorizations(), 1u);
  // The correction is that of the last tangent (the better predictor), within the solver's accuracy.
  EXPECT_LE(last.residual_of(x.x, r2, -0.5), 1.0001e-11);
  // A new pattern key is not reused: it is assembled and analysed anew.
  const int assembled = p.assemblies;
  ASSERT_TRUE(solver.solve(8, true, 1.0, p, r2, -0.5, 1e-9).ok);
  EXPECT_EQ(p.assemblies, assembled + 1);
  EXPECT_EQ(solver.factorizations(), 2u);
}

TEST_P(EitherUpdate, ASingularTangentIsReportedNotSolved) {
  Problem p;
  p.g.setZero();  // an opening hold whose row is empty: the bordered tangent is singular
  BorderedTangentSolver solver(options());
  const auto x = solver.solve(7, false, 1.0, p, p.r, p.cres, 1e-9);
  EXPECT_FALSE(x.ok);
  EXPECT_NE(x.why.find("singular"), std::string::npos) << x.why;
  // It recovers on the next usable tangent.
  p.g = random_vector(144, 2);
  EXPECT_TRUE(solver.solve(7, false, 1.0, p, p.r, p.cres, 1e-9).ok);
}

INSTANTIATE_TEST_SUITE_P(microBorderedTangentSolver, EitherUpdate,
                         ::testing::Values(TangentUpdate::LowRank, TangentUpdate::Gmres),
                         [](const auto& param_info) { return param_info.param == TangentUpdate::LowRank ? "LowRank" : "Gmres"; });

// The low-rank update keeps A0^-1 of every column it solved until the next factorization: later
// corrections on the same points cost one triangular solve and no new column.
TEST(microBorderedTangentSolver, TheLowRankUpdateKeepsItsColumnsAcrossCorrections) {
  Problem p;
  BorderedTangentSolver solver(low_rank());
  ASSERT_TRUE(solver.solve(7, false, 1.0, p, p.r, p.cres, 1e-9).ok);
  for (int it = 0; it < 4; ++it) {
    p.soften(2);
    const auto x = solver.solve(7, false, 1.0, p, p.r, p.cres, 1e-9);
    ASSERT_TRUE(x.ok) << x.why;
    EXPECT_LE(p.residual_of(x.x, p.r, p.cres), 1.0001e-11);
  }
  EXPECT_EQ(solver.factorizations(), 1u);
  EXPECT_EQ(solver.update_corrections(), 4u);
  EXPECT_EQ(solver.update_columns(), 4u);
}

// A new constraint row scale on the same pattern (a new path step) is a rank-one change of the border.
TEST(microBorderedTangentSolver, TheLowRankUpdateFollowsANewConstraintRowScale) {
  Problem p;
  BorderedTangentSolver solver(low_rank());
  ASSERT_TRUE(solver.solve(7, false, 1.0, p, p.r, p.cres, 1e-9).ok);
  p.soften(1);
  const auto x = solver.solve(7, false, 1e4, p, p.r, p.cres, 1e-9);
  ASSERT_TRUE(x.ok) << x.why;
  EXPECT_EQ(solver.factorizations(), 1u);
  EXPECT_EQ(solver.update_columns(), 3u);  // the point's two and the border's one
  EXPECT_LE(p.residual_of(x.x, p.r, p.cres), 1.0001e-11);
}

// More changed columns than max_update_rank: the new tangent is factorized and the columns dropped.
TEST(microBorderedTangentSolver, ALowRankChangeAboveTheRankLimitIsFactorized) {
  Problem p;
  BorderedTangentSolver solver(low_rank(5));
  ASSERT_TRUE(solver.solve(7, false, 1.0, p, p.r, p.cres, 1e-9).ok);
  p.soften(2);  // rank 4: updated
  ASSERT_TRUE(solver.solve(7, false, 1.0, p, p.r, p.cres, 1e-9).ok);
  EXPECT_EQ(solver.factorizations(), 1u);
  p.soften(3);  // rank 6 > 5: factorized
  const auto x = solver.solve(7, false, 1.0, p, p.r, p.cres, 1e-9);
  ASSERT_TRUE(x.ok) << x.why;
  EXPECT_LE(p.residual_of(x.x, p.r, p.cres), 1e-10);
  EXPECT_EQ(solver.factorizations(), 2u);
  EXPECT_EQ(solver.update_corrections(), 1u);
}

}  // namespace
}  // namespace uhpc::micro
