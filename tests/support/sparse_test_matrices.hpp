#pragma once
// Test matrices for the sparse solvers of the crack analysis (GMRES, the bordered tangent solver).
#include <random>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Sparse>

namespace uhpc::test {

// A non-symmetric, diagonally dominant 2D five-point operator (convection-diffusion) on an n x n grid:
// n^2 unknowns, the shape of a bulk stiffness without its symmetry.
inline Eigen::SparseMatrix<double> convection_diffusion(int n) {
  std::vector<Eigen::Triplet<double>> t;
  const auto id = [n](int i, int j) { return i * n + j; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      t.emplace_back(id(i, j), id(i, j), 4.5);
      if (i > 0) t.emplace_back(id(i, j), id(i - 1, j), -1.3);
      if (i < n - 1) t.emplace_back(id(i, j), id(i + 1, j), -0.7);
      if (j > 0) t.emplace_back(id(i, j), id(i, j - 1), -1.1);
      if (j < n - 1) t.emplace_back(id(i, j), id(i, j + 1), -0.9);
    }
  Eigen::SparseMatrix<double> A(n * n, n * n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

// Entries uniform in [-1, 1], reproducible by seed.
inline Eigen::VectorXd random_vector(Eigen::Index n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i) v[i] = u(rng);
  return v;
}

}  // namespace uhpc::test
