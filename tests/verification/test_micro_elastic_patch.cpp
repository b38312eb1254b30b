// Linear patch tests of the RK Galerkin elastic solver (micro/analysis): a linear displacement field
// imposed on the whole outer boundary (Nitsche, both components) is reproduced to round-off, in the
// nodal coefficients and in the strains at every Gauss point, on a regular square mesh, on an irregular
// (perturbed) mesh, and on a cell with a pore whose boundary carries the exact traction. Without the
// variationally consistent correction the same test fails by orders of magnitude (Gauss quadrature of
// RK functions violates the integration constraint): that is why VCI is the default.
// Also: the uniaxial test of a cell without pores gives E0_bar = E / (1 - nu^2) to round-off.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "cell_mesh.hpp"
#include "elastic_solution.hpp"
#include "uniaxial_cell.hpp"

namespace uhpc::micro {
namespace {

const PlaneStrain kMatrix{4.4296e10, 0.2};  // Table 2

// u(x) = u0 + G x, G a general (non-symmetric) gradient of order 1e-4.
struct LinearField {
  std::array<double, 2> u0{1.0e-7, -2.0e-7};
  double G[2][2] = {{1.0e-4, 0.3e-4}, {-0.5e-4, -0.2e-4}};
  std::array<double, 2> u(const double* x) const {
    return {u0[0] + G[0][0] * x[0] + G[0][1] * x[1], u0[1] + G[1][0] * x[0] + G[1][1] * x[1]};
  }
  std::array<double, 3> strain() const { return {G[0][0], G[1][1], G[0][1] + G[1][0]}; }
};

ElasticProblem patch_problem(const LinearField& field) {
  ElasticProblem p;
  p.material = kMatrix;
  for (int part = 0; part < 4; ++part) {
    p.boundary[part].prescribed = {true, true};
    p.boundary[part].displacement = [field](const double* x) { return field.u(x); };
  }
  const std::array<double, 3> s = apply_D(kMatrix.D(), field.strain());
  p.boundary[static_cast<int>(BoundaryPart::Pore)].traction = [s](const double*, const double* n) {
    return traction(s, n);
  };
  return p;
}

struct PatchError {
  double coefficients = 0.0;  // max |d_I - u(x_I)| / max |u|
  double strain = 0.0;        // max |eps_h - eps| / max |eps|
};

PatchError patch_error(const CellDiscretization& mesh, IntegrationCorrection correction) {
  RkGalerkinOptions o;
  o.correction = correction;
  const RkGalerkinModel model = build_rk_galerkin_model(mesh, o);
  const LinearField field;
  const ElasticProblem problem = patch_problem(field);
  const ElasticSolution s = solve_elastic(model, problem);
  PatchError e;
  double umax = 0.0;
  for (std::size_t i = 0; i < model.node_count(); ++i) {
    const std::array<double, 2> u = field.u(&model.nodes[2 * i]);
    for (int c = 0; c < 2; ++c) {
      e.coefficients = std::max(e.coefficients, std::abs(s.d[2 * i + c] - u[c]));
      umax = std::max(umax, std::abs(u[c]));
    }
  }
  e.coefficients /= umax;
  const std::array<double, 3> exact = field.strain();
  const double emax = std::max({std::abs(exact[0]), std::abs(exact[1]), std::abs(exact[2])});
  for (const PointField& f : fields_at(model.domain, s.d, kMatrix))
    for (int k = 0; k < 3; ++k) e.strain = std::max(e.strain, std::abs(f.strain[k] - exact[k]) / emax);
  return e;
}

CellGeometry square(double side) {
  CellGeometry g;
  g.side_m = side;
  return g;
}

MeshOptions coarse(double spacing) {
  MeshOptions o;
  o.nominal_spacing_m = spacing;
  return o;
}

// Moves every interior node by up to `fraction` of its spacing (uniform random direction and length),
// keeping every triangle positively oriented: an irregular mesh with the same boundary.
CellDiscretization perturbed(CellDiscretization m, double fraction, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (std::size_t i = 0; i < m.node_count(); ++i) {
    if (m.node_edges[i] != 0 || m.node_pore[i] >= 0) continue;
    m.nodes_m[i][0] += fraction * m.spacing_m[i] * u(rng);
    m.nodes_m[i][1] += fraction * m.spacing_m[i] * u(rng);
  }
  for (std::size_t t = 0; t < m.triangle_count(); ++t) EXPECT_GT(m.triangle_area(t), 0.0) << "inverted triangle";
  return m;
}

TEST(microElasticPatch, SquareReproducesLinearField) {
  const CellDiscretization mesh = mesh_cell(square(1e-3), coarse(1e-4));
  const PatchError e = patch_error(mesh, IntegrationCorrection::Vci);
  std::printf("square, %zu nodes: coefficient error %.2e, strain error %.2e\n", mesh.node_count(), e.coefficients,
              e.strain);
  EXPECT_LT(e.coefficients, 1e-8);
  EXPECT_LT(e.strain, 1e-8);
}

TEST(microElasticPatch, IrregularMeshReproducesLinearField) {
  const CellDiscretization mesh = perturbed(mesh_cell(square(1e-3), coarse(1e-4)), 0.25, 11);
  const PatchError e = patch_error(mesh, IntegrationCorrection::Vci);
  std::printf("irregular square, %zu nodes: coefficient error %.2e, strain error %.2e\n", mesh.node_count(),
              e.coefficients, e.strain);
  EXPECT_LT(e.coefficients, 1e-8);
  EXPECT_LT(e.strain, 1e-8);
}

TEST(microElasticPatch, CellWithPoreReproducesLinearField) {
  CellGeometry g = square(1e-3);
  g.pores.push_back({{0.45e-3, 0.55e-3}, 0.3e-3});
  const CellDiscretization mesh = perturbed(mesh_cell(g, coarse(1e-4)), 0.2, 5);
  const PatchError e = patch_error(mesh, IntegrationCorrection::Vci);
  std::printf("cell with a pore, %zu nodes: coefficient error %.2e, strain error %.2e\n", mesh.node_count(),
              e.coefficients, e.strain);
  EXPECT_LT(e.coefficients, 1e-8);
  EXPECT_LT(e.strain, 1e-8);
}

TEST(microElasticPatch, PlainGaussQuadratureFailsThePatchTest) {
  // The reason for the correction: without it the integration constraint is violated and the linear
  // field is not the discrete solution.
  const CellDiscretization mesh = perturbed(mesh_cell(square(1e-3), coarse(1e-4)), 0.25, 11);
  const PatchError e = patch_error(mesh, IntegrationCorrection::None);
  std::printf("irregular square without VCI: coefficient error %.2e, strain error %.2e\n", e.coefficients, e.strain);
  EXPECT_GT(e.strain, 1e-6);
}

TEST(microElasticPatch, CellWithoutPoresHasThePlaneStrainModulus) {
  // Uniaxial stress in plane strain with free lateral faces: sigma = E / (1 - nu^2) e exactly, a linear
  // field, so the solver must reproduce it to round-off.
  const double side = 1e-3;
  const CellDiscretization mesh = perturbed(mesh_cell(square(side), coarse(0.8e-4)), 0.2, 3);
  const UniaxialResult r = uniaxial_elastic_response(mesh, side, LoadAxis::X, kMatrix, UniaxialOptions{});
  std::printf("no pores: E0_bar / E' - 1 = %.2e, energy check %.2e, reaction imbalance %.2e\n",
              r.E0_bar_Pa / kMatrix.plane_modulus_Pa() - 1.0, r.hill_mandel_relative,
              (r.far_face_force_N_m + r.near_face_force_N_m) / r.far_face_force_N_m);
  EXPECT_NEAR(r.E0_bar_Pa / kMatrix.plane_modulus_Pa(), 1.0, 1e-9);
  EXPECT_NEAR(r.hill_mandel_relative, 0.0, 1e-9);
  EXPECT_NEAR(r.near_face_force_N_m / r.far_face_force_N_m, -1.0, 1e-9);
  const UniaxialResult ry = uniaxial_elastic_response(mesh, side, LoadAxis::Y, kMatrix, UniaxialOptions{});
  EXPECT_NEAR(ry.E0_bar_Pa / kMatrix.plane_modulus_Pa(), 1.0, 1e-9);
}

}  // namespace
}  // namespace uhpc::micro
