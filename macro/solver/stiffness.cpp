#include "solver/stiffness.hpp"

#include "solver/nsni_moment.hpp"

#include <cstdint>
#include <vector>

namespace uhpc::macro {

Eigen::MatrixXd nodal_integration_stiffness(const ShapeCache& shapes, const double* volume, std::size_t n,
                                            double bulk_modulus, double shear_modulus, bool nsni,
                                            const std::uint8_t* integration_points) {
  // Voigt form: eps = (e11, e22, e33, 2e23, 2e13, 2e12); C the isotropic elasticity matrix.
  Eigen::Matrix<double, 6, 6> C = Eigen::Matrix<double, 6, 6>::Zero();
  const double lambda = bulk_modulus - 2.0 / 3.0 * shear_modulus;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) C(i, j) = lambda;
    C(i, i) += 2.0 * shear_modulus;
    C(3 + i, 3 + i) = shear_modulus;
  }
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(3 * n, 3 * n);
  // The strain operator of one integration point from per-node "gradient" vectors g (3 per node).
  auto strain_operator = [](const double* g_of, std::int64_t count, auto&& g_at) {
    Eigen::MatrixXd B = Eigen::MatrixXd::Zero(6, 3 * count);
    for (std::int64_t k = 0; k < count; ++k) {
      double g[3];
      g_at(g_of, k, g);
      const Eigen::Index c = 3 * k;
      B(0, c) = g[0];
      B(1, c + 1) = g[1];
      B(2, c + 2) = g[2];
      B(3, c + 1) = g[2];
      B(3, c + 2) = g[1];
      B(4, c) = g[2];
      B(4, c + 2) = g[0];
      B(5, c) = g[1];
      B(5, c + 1) = g[0];
    }
    return B;
  };
  for (std::size_t L = 0; L < n; ++L) {
    if (integration_points && !integration_points[L]) continue;
    const std::int64_t count = shapes.row_size(L), b = shapes.row_begin(L);
    const Eigen::MatrixXd B = strain_operator(shapes.grad.data() + 3 * b, count, [](const double* base, std::int64_t k, double* g) {
      for (int d = 0; d < 3; ++d) g[d] = base[3 * k + d];
    });
    Eigen::MatrixXd KL = volume[L] * B.transpose() * C * B;
    if (nsni) {
      const double moment = nsni_moment(volume[L], 1.0);
      for (int d = 0; d < 3; ++d) {
        const Eigen::MatrixXd Bd = strain_operator(shapes.hess.data() + 6 * b, count, [d](const double* base, std::int64_t k, double* g) {
          for (int c = 0; c < 3; ++c) g[c] = base[6 * k + sym_index(d, c)];
        });
        KL += moment * Bd.transpose() * C * Bd;
      }
    }
    const std::int32_t* row = shapes.row_nodes(L);
    for (std::int64_t k = 0; k < count; ++k)
      for (std::int64_t m = 0; m < count; ++m)
        K.block<3, 3>(3 * static_cast<Eigen::Index>(row[k]), 3 * static_cast<Eigen::Index>(row[m])) +=
            KL.block<3, 3>(3 * k, 3 * m);
  }
  return K;
}

}  // namespace uhpc::macro
