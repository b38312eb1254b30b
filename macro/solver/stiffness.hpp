#pragma once
// Linearised stiffness of direct nodal integration at a stress-free configuration, for the zero-energy
// mode analysis: with the strain at x_L, eps_L = sum_J sym(u_J (x) grad Psi_J(x_L)), and the isotropic
// elastic C,
//   K = sum_L V_L B_L^T C B_L,   u^T K u = sum_L V_L eps_L : C : eps_L.
// With `nsni` (shapes built with second gradients) the NSNI term is added:
//   K += sum_L M_L sum_d B_d,L^T C B_d,L,   M_L = V_L^(5/3) / 12 (nsni_moment.hpp with c = 1),
// B_d the strain-gradient operator eps_,d = sum_J sym(u_J (x) Psi^(d.)_J).
// `integration_points` (n flags, optional) restricts the sum to the flagged L: the energy of a mode in
// part of the body.
// Dense (3n x 3n): meant for a few hundred particles.
#include <cstddef>
#include <cstdint>

#include <Eigen/Core>

#include "solver/shape_cache.hpp"

namespace uhpc::macro {

Eigen::MatrixXd nodal_integration_stiffness(const ShapeCache& shapes, const double* volume, std::size_t n,
                                            double bulk_modulus, double shear_modulus, bool nsni = false,
                                            const std::uint8_t* integration_points = nullptr);

}  // namespace uhpc::macro
