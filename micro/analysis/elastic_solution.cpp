#include "elastic_solution.hpp"

#include <chrono>

#include "stiffness_assembly.hpp"

namespace uhpc::micro {

namespace {

double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

PointField field_at(const rk::ShapeTable& t, std::size_t p, const Eigen::VectorXd& d, const std::array<double, 9>& D) {
  PointField f{{0.0, 0.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
  for (std::int64_t e = t.support.begin(p); e < t.support.end(p); ++e) {
    const std::int32_t i = t.support.indices[e];
    const double ux = d[2 * i], uy = d[2 * i + 1], gx = t.grad[2 * e], gy = t.grad[2 * e + 1];
    f.u[0] += t.psi[e] * ux;
    f.u[1] += t.psi[e] * uy;
    f.strain[0] += gx * ux;
    f.strain[1] += gy * uy;
    f.strain[2] += gy * ux + gx * uy;
  }
  f.stress = apply_D(D, f.strain);
  return f;
}

}  // namespace

ElasticSolution solve_elastic(const RkGalerkinModel& model, const ElasticProblem& problem) {
  ElasticSolution s;
  std::vector<std::array<double, 2>> xs;
  for (const PointConstraint& c : problem.points) xs.push_back(c.x_m);
  const PointSet constraints = sample_points(model, xs);
  auto t0 = std::chrono::steady_clock::now();
  const LinearSystem sys = assemble_elastic_system(model, problem, constraints);
  s.assembly_s = since(t0);
  t0 = std::chrono::steady_clock::now();
  s.d = solve_sparse(sys.K, sys.f, sys.symmetric, &s.solve);
  s.solve_s = since(t0);
  return s;
}

std::vector<PointField> fields_at(const PointSet& points, const Eigen::VectorXd& d, const PlaneStrain& material) {
  const std::array<double, 9> D = material.D();
  std::vector<PointField> out(points.size());
  for (std::size_t p = 0; p < points.size(); ++p) out[p] = field_at(points.table, p, d, D);
  return out;
}

std::array<double, 2> boundary_force(const RkGalerkinModel& model, const ElasticProblem& problem,
                                     const Eigen::VectorXd& d, BoundaryPart part) {
  const std::array<double, 9> D = problem.material.D();
  const BoundaryCondition& bc = problem.boundary[static_cast<int>(part)];
  const BoundaryPoints& bp = model.boundary;
  std::array<double, 2> force{0.0, 0.0};
  for (std::size_t p = 0; p < bp.size(); ++p) {
    const std::size_t s = static_cast<std::size_t>(bp.segment[p]);
    const BoundarySegment& seg = model.segments[s];
    if (seg.part != part) continue;
    const double* x = &bp.x[2 * p];
    const PointField f = field_at(bp.table, p, d, D);
    const std::array<double, 2> t = traction(f.stress, seg.normal.data());
    const std::array<double, 2> g = (bc.prescribed[0] || bc.prescribed[1]) ? bc.displacement(x)
                                                                           : std::array<double, 2>{0.0, 0.0};
    const std::array<double, 2> tb =
        bc.traction ? bc.traction(x, seg.normal.data()) : std::array<double, 2>{0.0, 0.0};
    const double beta = nitsche_beta(model, problem, s);
    for (int c = 0; c < 2; ++c)
      force[c] += bp.weight[p] * (bc.prescribed[c] ? t[c] - beta * (f.u[c] - g[c]) : tb[c]);
  }
  return force;
}

double strain_energy(const RkGalerkinModel& model, const Eigen::VectorXd& d, const PlaneStrain& material) {
  const std::array<double, 9> D = material.D();
  double energy = 0.0;
#pragma omp parallel for reduction(+ : energy) schedule(static)
  for (std::int64_t p = 0; p < static_cast<std::int64_t>(model.domain.size()); ++p) {
    const PointField f = field_at(model.domain.table, static_cast<std::size_t>(p), d, D);
    energy += 0.5 * model.domain.weight[p] *
              (f.strain[0] * f.stress[0] + f.strain[1] * f.stress[1] + f.strain[2] * f.stress[2]);
  }
  return energy;
}

}  // namespace uhpc::micro
