#pragma once
// Plane-strain linear elasticity of the matrix (docs/physics.md section 2, Table 2), Voigt notation
// [xx, yy, xy] with engineering shear strain. Small inline helpers: they sit in the assembly loops.
#include <array>

namespace uhpc::micro {

struct PlaneStrain {
  double youngs_modulus_Pa = 0.0;
  double poissons_ratio = 0.0;

  // The 2D Young's modulus E' = E / (1 - nu^2): the uniaxial-stress modulus of a plane-strain body
  // with free lateral faces, i.e. E0_bar of a cell without pores.
  double plane_modulus_Pa() const { return youngs_modulus_Pa / (1.0 - poissons_ratio * poissons_ratio); }

  std::array<double, 9> D() const {
    const double nu = poissons_ratio;
    const double c = youngs_modulus_Pa / ((1.0 + nu) * (1.0 - 2.0 * nu));
    return {c * (1.0 - nu), c * nu, 0.0, c * nu, c * (1.0 - nu), 0.0, 0.0, 0.0, c * 0.5 * (1.0 - 2.0 * nu)};
  }
};

// Strain of the displacement e_k Psi (k = 0: x, 1: y) with gradient g of Psi.
inline std::array<double, 3> unit_strain(int k, const double* g) {
  return k == 0 ? std::array<double, 3>{g[0], 0.0, g[1]} : std::array<double, 3>{0.0, g[1], g[0]};
}

inline std::array<double, 3> apply_D(const std::array<double, 9>& D, const std::array<double, 3>& e) {
  return {D[0] * e[0] + D[1] * e[1] + D[2] * e[2], D[3] * e[0] + D[4] * e[1] + D[5] * e[2],
          D[6] * e[0] + D[7] * e[1] + D[8] * e[2]};
}

// Traction sigma n on a surface with unit normal n.
inline std::array<double, 2> traction(const std::array<double, 3>& s, const double* n) {
  return {s[0] * n[0] + s[2] * n[1], s[2] * n[0] + s[1] * n[1]};
}

}  // namespace uhpc::micro
