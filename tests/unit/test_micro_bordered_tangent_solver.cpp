// The Newton solver of the crack analysis (micro/analysis/bordered_tangent_solver.hpp): every
// correction solves the bordered system it was asked for, whichever way it went (a fresh LU, GMRES
// preconditioned with an older one, or the reused tangent at the start of a path step), and
// factorizations are spent only where the solver says they are.
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

struct Problem {
  Eigen::SparseMatrix<double> K = test::convection_diffusion(12);  // the "bulk" K_T  // 144 unknowns
  Eigen::VectorXd f = random_vector(144, 1), g = random_vector(144, 2), r = random_vector(144, 3);
  double c = 0.0;  // an opening hold
  double cres = 0.25;
  int assemblies = 0;
  BorderedTangentSolver::Assemble assemble() {
    return [this](double s) {
      ++assemblies;
      return bordered(K, f, g, c, s);
    };
  }
  // A change at a few "cohesive points" (a low-rank change of the tangent).
  void soften(int points) {
    for (int k = 0; k < points; ++k) K.coeffRef(17 * k + 5, 17 * k + 5) -= 1.5;
  }
};

TEST(microBorderedTangentSolver, AFreshTangentIsFactorizedAndItsCorrectionSolvesTheUnscaledSystem) {
  for (const double row_scale : {1.0, 1e6}) {
    Problem p;
    BorderedTangentSolver solver(16);
    const auto x = solver.solve(7, false, row_scale, p.assemble(), p.r, p.cres, 1e-9);
    ASSERT_TRUE(x.ok) << x.why;
    EXPECT_LE(system_residual(p.K, p.f, p.g, p.c, x.x, p.r, p.cres), 1e-10) << row_scale;
    EXPECT_EQ(solver.factorizations(), 1u);
    EXPECT_EQ(solver.krylov_corrections(), 0u);
    EXPECT_EQ(p.assemblies, 1);
  }
}

TEST(microBorderedTangentSolver, ALowRankChangeOfTheSamePatternIsSolvedByGmresWithoutAFactorization) {
  Problem p;
  BorderedTangentSolver solver(16);
  ASSERT_TRUE(solver.solve(7, false, 1.0, p.assemble(), p.r, p.cres, 1e-9).ok);
  p.soften(3);
  const double tolerance = 1e-9;
  const auto x = solver.solve(7, false, 1.0, p.assemble(), p.r, p.cres, tolerance);
  ASSERT_TRUE(x.ok) << x.why;
  EXPECT_EQ(solver.factorizations(), 1u);
  EXPECT_EQ(solver.krylov_corrections(), 1u);
  EXPECT_LE(solver.krylov_products(), 4u);  // rank 3 + 1
  EXPECT_LE(system_residual(p.K, p.f, p.g, p.c, x.x, p.r, p.cres), 0.01 * tolerance * 1.0001);
}

TEST(microBorderedTangentSolver, WithoutKrylovIterationsEveryNewTangentIsFactorized) {
  Problem p;
  BorderedTangentSolver solver(0);
  for (int it = 0; it < 3; ++it) {
    const auto x = solver.solve(7, false, 1.0, p.assemble(), p.r, p.cres, 1e-9);
    ASSERT_TRUE(x.ok) << x.why;
    EXPECT_LE(system_residual(p.K, p.f, p.g, p.c, x.x, p.r, p.cres), 1e-10);
    p.soften(1);
  }
  EXPECT_EQ(solver.factorizations(), 3u);
  EXPECT_EQ(solver.krylov_corrections(), 0u);
}

TEST(microBorderedTangentSolver, TheStartOfAPathStepReusesTheLastTangentWithoutAssemblingOne) {
  Problem p;
  BorderedTangentSolver solver(16);
  const Eigen::SparseMatrix<double> K_before = p.K;
  ASSERT_TRUE(solver.solve(7, false, 1.0, p.assemble(), p.r, p.cres, 1e-9).ok);
  p.soften(2);  // the state moved on: a fresh tangent would differ
  const Eigen::VectorXd r2 = random_vector(144, 9);
  const auto x = solver.solve(7, true, 1.0, p.assemble(), r2, -0.5, 1e-9);
  ASSERT_TRUE(x.ok) << x.why;
  EXPECT_EQ(p.assemblies, 1);
  EXPECT_EQ(solver.factorizations(), 1u);
  // The correction is that of the last tangent (the better predictor), to round-off.
  EXPECT_LE(system_residual(K_before, p.f, p.g, p.c, x.x, r2, -0.5), 1e-10);
  // A new pattern key is not reused: it is assembled and analysed anew.
  ASSERT_TRUE(solver.solve(8, true, 1.0, p.assemble(), r2, -0.5, 1e-9).ok);
  EXPECT_EQ(p.assemblies, 2);
  EXPECT_EQ(solver.factorizations(), 2u);
}

TEST(microBorderedTangentSolver, ASingularTangentIsReportedNotSolved) {
  Problem p;
  p.g.setZero();  // an opening hold whose row is empty: the bordered tangent is singular
  BorderedTangentSolver solver(16);
  const auto x = solver.solve(7, false, 1.0, p.assemble(), p.r, p.cres, 1e-9);
  EXPECT_FALSE(x.ok);
  EXPECT_NE(x.why.find("singular"), std::string::npos) << x.why;
  // It recovers on the next usable tangent.
  p.g = random_vector(144, 2);
  EXPECT_TRUE(solver.solve(7, false, 1.0, p.assemble(), p.r, p.cres, 1e-9).ok);
}

}  // namespace
}  // namespace uhpc::micro
