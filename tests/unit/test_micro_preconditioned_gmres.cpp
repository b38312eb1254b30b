// Right-preconditioned GMRES (micro/analysis/preconditioned_gmres.hpp), on the property the Newton
// solver relies on: with the exact factorization of a matrix M as preconditioner, A = M + (rank k)
// is solved in at most k + 1 iterations; unpreconditioned, a diagonal matrix with m distinct entries
// takes exactly m; the residual it reports is the true one, also when it stops unconverged.
#include <Eigen/SparseLU>
#include <gtest/gtest.h>

#include "preconditioned_gmres.hpp"
#include "sparse_test_matrices.hpp"

namespace uhpc::micro {
namespace {

using test::convection_diffusion;
using test::random_vector;

TEST(microPreconditionedGmres, ExactPreconditionerOfALowRankChangeConvergesInRankPlusOne) {
  const Eigen::SparseMatrix<double> M = convection_diffusion(20);  // 400 unknowns
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(M);
  ASSERT_EQ(lu.info(), Eigen::Success);
  const Preconditioner P = [&lu](const Eigen::VectorXd& v, Eigen::VectorXd& z) { z = lu.solve(v); };
  const Eigen::VectorXd b = random_vector(M.rows(), 1);
  for (int rank : {1, 3, 6}) {
    // A = M + sum of `rank` sparse outer products u e_j^T (like cohesive points changing branch).
    Eigen::SparseMatrix<double> A = M;
    for (int k = 0; k < rank; ++k) {
      const int i = 37 * k + 11, j = 53 * k + 5;
      A.coeffRef(i, j) += 2.0 + k;
      A.coeffRef(i + 1, j) -= 1.5;
      A.coeffRef(i + 7, j) += 0.5 * k;
    }
    Eigen::VectorXd x;
    const double tolerance = 1e-12 * b.norm();
    const GmresResult r = preconditioned_gmres(A, P, b, tolerance, 50, x);
    EXPECT_TRUE(r.converged) << rank;
    EXPECT_LE(r.iterations, rank + 1) << rank;
    EXPECT_LE((b - A * x).norm(), 2.0 * tolerance) << rank;  // the reported residual is the true one
    Eigen::SparseLU<Eigen::SparseMatrix<double>> direct(A);
    EXPECT_LE((x - direct.solve(b)).norm(), 1e-10 * x.norm()) << rank;
  }
}

TEST(microPreconditionedGmres, UnpreconditionedDiagonalTakesOneIterationPerDistinctEntry) {
  const int n = 60, distinct = 7;
  Eigen::SparseMatrix<double> A(n, n);
  for (int i = 0; i < n; ++i) A.insert(i, i) = 1.0 + (i % distinct);
  const Preconditioner identity = [](const Eigen::VectorXd& v, Eigen::VectorXd& z) { z = v; };
  const Eigen::VectorXd b = random_vector(n, 2);
  Eigen::VectorXd x;
  const double tolerance = 1e-11 * b.norm();
  const GmresResult r = preconditioned_gmres(A, identity, b, tolerance, 40, x);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.iterations, distinct);
  for (int i = 0; i < n; ++i) EXPECT_NEAR(x[i], b[i] / (1.0 + (i % distinct)), 1e-10);
  // One iteration short of that it cannot converge, and says so with its true residual.
  const GmresResult s = preconditioned_gmres(A, identity, b, tolerance, distinct - 1, x);
  EXPECT_FALSE(s.converged);
  EXPECT_EQ(s.iterations, distinct - 1);
  EXPECT_GT(s.residual_norm, tolerance);
  EXPECT_NEAR((b - A * x).norm(), s.residual_norm, 1e-9 * b.norm());
}

TEST(microPreconditionedGmres, ZeroRightHandSideGivesZeroWithoutIterating) {
  const Eigen::SparseMatrix<double> A = convection_diffusion(4);
  const Preconditioner identity = [](const Eigen::VectorXd& v, Eigen::VectorXd& z) { z = v; };
  Eigen::VectorXd x = Eigen::VectorXd::Ones(A.rows());
  const GmresResult r = preconditioned_gmres(A, identity, Eigen::VectorXd::Zero(A.rows()), 1e-12, 10, x);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.iterations, 0);
  EXPECT_EQ(x.norm(), 0.0);
}

}  // namespace
}  // namespace uhpc::micro
