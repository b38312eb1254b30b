#pragma once
// Internal forces by direct nodal integration: every particle L is an integration point of volume V_L,
//   f_I = - sum_L V_L (sigma_L - q_L I) grad Psi_I(x_L).
// Since sum_I grad Psi_I(x_L) = 0 (RK implicit gradients, to round-off), sum_I f_I = 0: linear momentum
// is conserved exactly; with symmetric stress and linear reproduction sum_I x_I (x) grad Psi_I = I also
// angular momentum. The rows of the shape table are scattered, so each thread adds into its own
// buffer (kept between calls) and the buffers are summed; the result does not depend on scheduling
// for a fixed thread count.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "solver/shape_cache.hpp"

namespace uhpc::macro {

class InternalForce {
 public:
  // f (3n) from the stress (9n), bulk viscosity pressure (n, may be null) and volumes (n). With
  // `stress_grad` (27n, NSNI; shapes must hold second gradients) adds the stabilization force
  //   f_Ij -= sum_L M_L sum_d sum_k dsigma_jk/dx_d (x_L) Psi^(dk)_I(x_L),   M_L = c V_L^(5/3) / 12,
  // the second moment of a cube of volume V_L about its centre in each direction times the NSNI
  // coefficient c (nsni_moment.hpp).
  void compute(const ShapeCache& shapes, const double* stress, const double* bulk_q, const double* volume,
               std::size_t n, double* f, const double* stress_grad = nullptr, double nsni_coefficient = 1.0);

  // The same in parts, for a caller that adds each row while the row's gradients are still in cache.
  // Inside a parallel region: begin on every thread (its zeroed buffer), add_row for the rows L of an
  // `omp for schedule(static, kRowChunk)` loop, then finish on every thread (f = the sum of the buffers). The
  // buffers then receive the rows as compute gives them: the same f, bitwise.
  double* begin(std::size_t n);
  static void add_row(const ShapeCache& shapes, std::int64_t L, const double* stress, const double* bulk_q,
                      const double* volume, const double* stress_grad, double* buf, double nsni_coefficient);
  void finish(std::size_t n, double* f);

 private:
  std::vector<std::vector<double>> buffers_;
};

}  // namespace uhpc::macro
