#include "uniaxial_cell.hpp"

#include <chrono>
#include <utility>

#include "elastic_solution.hpp"

namespace uhpc::micro {

namespace {

// Near and far faces of the load axis.
std::pair<BoundaryPart, BoundaryPart> loaded_faces(LoadAxis axis) {
  return axis == LoadAxis::X ? std::make_pair(BoundaryPart::Left, BoundaryPart::Right)
                             : std::make_pair(BoundaryPart::Bottom, BoundaryPart::Top);
}

}  // namespace

ElasticProblem uniaxial_problem(double side_m, LoadAxis axis, double strain, const PlaneStrain& material,
                                double nitsche_factor) {
  ElasticProblem p;
  p.material = material;
  p.nitsche_factor = nitsche_factor;
  const int a = axis == LoadAxis::X ? 0 : 1;
  const auto [near, far] = loaded_faces(axis);
  BoundaryCondition& n = p.boundary[static_cast<int>(near)];
  n.prescribed[a] = true;
  n.displacement = [](const double*) { return std::array<double, 2>{0.0, 0.0}; };
  BoundaryCondition& f = p.boundary[static_cast<int>(far)];
  f.prescribed[a] = true;
  const double u = strain * side_m;
  f.displacement = [a, u](const double*) {
    std::array<double, 2> g{0.0, 0.0};
    g[a] = u;
    return g;
  };
  PointConstraint c;
  c.x_m = a == 0 ? std::array<double, 2>{0.0, 0.5 * side_m} : std::array<double, 2>{0.5 * side_m, 0.0};
  c.component = 1 - a;
  p.points.push_back(c);
  return p;
}

UniaxialResult uniaxial_elastic_response(const CellDiscretization& mesh, double side_m, LoadAxis axis,
                                         const PlaneStrain& material, const UniaxialOptions& options) {
  UniaxialResult r;
  const auto t0 = std::chrono::steady_clock::now();
  const RkGalerkinModel model = build_rk_galerkin_model(mesh, options.rk);
  r.model_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const ElasticProblem problem = uniaxial_problem(side_m, axis, options.strain, material, options.nitsche_factor);
  const ElasticSolution s = solve_elastic(model, problem);
  r.assembly_s = s.assembly_s;
  r.solve_s = s.solve_s;
  r.solver = s.solve.solver;
  r.solver_relative_residual = s.solve.relative_residual;

  const int a = axis == LoadAxis::X ? 0 : 1;
  const auto [near, far] = loaded_faces(axis);
  r.strain = options.strain;
  r.far_face_force_N_m = boundary_force(model, problem, s.d, far)[a];
  r.near_face_force_N_m = boundary_force(model, problem, s.d, near)[a];
  r.sigma_bar_Pa = r.far_face_force_N_m / side_m;
  r.E0_bar_Pa = r.sigma_bar_Pa / options.strain;
  r.energy_density_J_m3 = strain_energy(model, s.d, material) / (side_m * side_m);
  r.half_sigma_e_J_m3 = 0.5 * r.sigma_bar_Pa * options.strain;
  r.hill_mandel_relative = (r.energy_density_J_m3 - r.half_sigma_e_J_m3) / r.half_sigma_e_J_m3;

  // Mean displacement of the far face, weighted by the boundary quadrature.
  const std::vector<PointField> bf = fields_at(model.boundary, s.d, material);
  double u = 0.0, len = 0.0;
  for (std::size_t p = 0; p < model.boundary.size(); ++p)
    if (model.segments[model.boundary.segment[p]].part == far) {
      u += model.boundary.weight[p] * bf[p].u[a];
      len += model.boundary.weight[p];
    }
  r.far_face_mean_displacement_m = u / len;

  const PointConstraint& c = problem.points.front();
  const std::vector<PointField> at = fields_at(sample_points(model, {c.x_m}), s.d, material);
  r.point_force_N_m = -problem.nitsche_factor * material.plane_modulus_Pa() * (at[0].u[c.component] - c.value_m);

  r.nodes = model.node_count();
  r.dofs = model.dof_count();
  r.domain_points = model.domain.size();
  r.boundary_points = model.boundary.size();
  r.quasi_linear_points = model.domain.table.count(rk::Path::QuasiLinear) + model.boundary.table.count(rk::Path::QuasiLinear);
  r.vci_max_correction = model.vci_max_correction;
  return r;
}

}  // namespace uhpc::micro
