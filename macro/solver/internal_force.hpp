#pragma once
// Internal forces by direct nodal integration: every particle L is an integration point of volume V_L,
//   f_I = - sum_L V_L (sigma_L - q_L I) grad Psi_I(x_L).
// Since sum_I grad Psi_I(x_L) = 0 (RK implicit gradients, to round-off), sum_I f_I = 0: linear momentum
// is conserved exactly; with symmetric stress and linear reproduction sum_I x_I (x) grad Psi_I = I also
// angular momentum. The rows of the shape table are scattered, so each thread adds into its own
// buffer (kept between calls) and the buffers are summed; the result does not depend on scheduling
// for a fixed thread count.
#include <cstddef>
#include <vector>

#include "solver/shape_cache.hpp"

namespace uhpc::macro {

class InternalForce {
 public:
  // f (3n) from the stress (9n), bulk viscosity pressure (n, may be null) and volumes (n). With
  // `stress_grad` (27n, NSNI; shapes must hold second gradients) adds the stabilization force
  //   f_Ij -= sum_L M_L sum_d sum_k dsigma_jk/dx_d (x_L) Psi^(dk)_I(x_L),   M_L = V_L^(5/3) / 12,
  // the second moment of a cube of volume V_L about its centre in each direction.
  void compute(const ShapeCache& shapes, const double* stress, const double* bulk_q, const double* volume,
               std::size_t n, double* f, const double* stress_grad = nullptr);

 private:
  std::vector<std::vector<double>> buffers_;
};

}  // namespace uhpc::macro
