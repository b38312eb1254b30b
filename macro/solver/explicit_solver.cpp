#include "solver/explicit_solver.hpp"
#include "solver/parallel.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "solver/kinematics.hpp"
#include "solver/stress_update.hpp"

namespace uhpc::macro {

ExplicitSolver::ExplicitSolver(Particles particles, MaterialSet material, const SolverOptions& options)
    : p_(std::move(particles)), material_(std::move(material)), options_(options) {
  const std::size_t states = std::visit([](const auto& b) { return b.state.size(); }, material_);
  if (states != p_.n) throw std::invalid_argument("ExplicitSolver: one material state per particle is required");
  if (!(options_.cfl > 0 && options_.cfl <= 1)) throw std::invalid_argument("ExplicitSolver: cfl must be in (0, 1]");
  if (!(options_.support_factor > 1)) throw std::invalid_argument("ExplicitSolver: support_factor must be > 1");
  if (options_.viscosity.c_linear < 0 || options_.viscosity.c_quadratic < 0)
    throw std::invalid_argument("ExplicitSolver: bulk viscosity coefficients must be >= 0");
  f_ext_old_.assign(3 * p_.n, 0.0);
  if (options_.stabilization == Stabilization::Nsni) {
    p_.stress_grad.assign(27 * p_.n, 0.0);
    p_.vel_grad_grad.assign(27 * p_.n, 0.0);
  }
}

const SecondGradientOptions* ExplicitSolver::second_options() const {
  return options_.stabilization == Stabilization::Nsni ? &options_.second_gradients : nullptr;
}

void ExplicitSolver::initialize() {
  // Stresses from the states (zero for a body at rest), wave speeds at the reference density.
  std::visit(
      [&](auto& block) {
        double dt_min = std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i < p_.n; ++i) {
          Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(p_.stress.data() + 9 * i) = block.state[i].stress;
          p_.wave_speed[i] = block.law.wave_speed(block.state[i], p_.volume0[i] / p_.volume[i]);
          dt_min = std::min(dt_min, options_.viscosity.critical_step(std::cbrt(p_.volume[i]), p_.wave_speed[i], 0.0));
        }
        dt_ = options_.cfl * dt_min;
      },
      material_);
  constrain_velocities();
  p_.x_prev = p_.x;
  shapes_.rebuild(options_.rk, p_.x.data(), p_.support.data(), p_.n, second_options());
  compute_forces();
  f_ext_old_ = p_.f_ext;
  update_momentum_and_kinetic();
  ledger_.kinetic_initial = ledger_.kinetic;
  ledger_.momentum_initial = ledger_.momentum;
}

void ExplicitSolver::constrain_velocities() {
  for (const PrescribedVelocity& bc : prescribed_)
    for (const std::int32_t i : bc.particles)
      for (int d = 0; d < 3; ++d) p_.v[3 * static_cast<std::size_t>(i) + d] = bc.velocity[d];
}

void ExplicitSolver::compute_accelerations(double dt) {
  const std::int64_t n = static_cast<std::int64_t>(p_.n);
  const double* x_strain = p_.x.data();
  if (options_.strain_configuration == StrainConfiguration::Midpoint) {
#pragma omp parallel for schedule(static) if (n >= kParallelMinParticles)
    for (std::int64_t i = 0; i < 3 * n; ++i) p_.x_mid[i] = 0.5 * (p_.x_prev[i] + p_.x[i]);
    x_strain = p_.x_mid.data();
  }
  shapes_.rebuild(options_.rk, x_strain, p_.support.data(), p_.n, second_options());
  velocity_gradient(shapes_, p_.v.data(), p_.n, p_.vel_grad.data());
  if (second_options()) velocity_gradient_gradient(shapes_, p_.v.data(), p_.n, p_.vel_grad_grad.data());

  const StressUpdateSums sums =
      std::visit([&](auto& block) { return update_stresses(block, p_, dt, options_.viscosity); }, material_);
  ledger_.internal += sums.stress_work + sums.stabilization_work;
  ledger_.stabilization += sums.stabilization_work;
  ledger_.viscous += sums.viscous_work;
  dt_ = options_.cfl * sums.min_critical_step;
  if (sums.inverted >= 0) failure_ = sums.inverted;

  if (options_.strain_configuration == StrainConfiguration::Midpoint)
    shapes_.rebuild(options_.rk, p_.x.data(), p_.support.data(), p_.n, second_options());
  compute_forces();

  // External work and impulse by the trapezoid rule over the step.
  double work = 0.0, ix = 0.0, iy = 0.0, iz = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : work, ix, iy, iz) if (n >= kParallelMinParticles)
  for (std::int64_t i = 0; i < n; ++i) {
    double f[3];
    for (int d = 0; d < 3; ++d) f[d] = 0.5 * (f_ext_old_[3 * i + d] + p_.f_ext[3 * i + d]);
    for (int d = 0; d < 3; ++d) work += f[d] * (p_.x[3 * i + d] - p_.x_prev[3 * i + d]);
    ix += f[0] * dt;
    iy += f[1] * dt;
    iz += f[2] * dt;
  }
  ledger_.external += work;
  ledger_.external_impulse[0] += ix;
  ledger_.external_impulse[1] += iy;
  ledger_.external_impulse[2] += iz;
  std::copy(p_.f_ext.begin(), p_.f_ext.end(), f_ext_old_.begin());
}

void ExplicitSolver::compute_forces() {
  force_.compute(shapes_, p_.stress.data(), p_.bulk_q.data(), p_.volume.data(), p_.n, p_.f_int.data(),
                 p_.stress_grad.empty() ? nullptr : p_.stress_grad.data());
  const std::int64_t n = static_cast<std::int64_t>(p_.n);
  double wall_total = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : wall_total) if (n >= kParallelMinParticles)
  for (std::int64_t i = 0; i < n; ++i) {
    double* fe = p_.f_ext.data() + 3 * i;
    fe[0] = fe[1] = fe[2] = 0.0;
    for (const Wall& w : walls_) {
      const double* x = p_.x.data() + 3 * i;
      double gap = 0.0;
      for (int d = 0; d < 3; ++d) gap += (x[d] - w.point[d]) * w.normal[d];
      const double delta = 0.5 * p_.spacing[i] - gap;
      if (delta <= 0.0) continue;
      const double k = w.penalty_scale * p_.density[i] * p_.wave_speed[i] * p_.wave_speed[i] * p_.spacing[i];
      for (int d = 0; d < 3; ++d) fe[d] += k * delta * w.normal[d];
      wall_total += k * delta;
    }
  }
  wall_force_ = wall_total;
  // Prescribed velocities: the reaction cancels every other force (constant velocity, a = 0), so the
  // external force on such a particle is -f_int.
  for (const PrescribedVelocity& bc : prescribed_)
    for (const std::int32_t j : bc.particles)
      for (int d = 0; d < 3; ++d) p_.f_ext[3 * static_cast<std::size_t>(j) + d] = -p_.f_int[3 * static_cast<std::size_t>(j) + d];
#pragma omp parallel for schedule(static) if (n >= kParallelMinParticles)
  for (std::int64_t i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) p_.a[3 * i + d] = (p_.f_int[3 * i + d] + p_.f_ext[3 * i + d]) / p_.mass[i];
}

void ExplicitSolver::update_momentum_and_kinetic() {
  const std::int64_t n = static_cast<std::int64_t>(p_.n);
  double ke = 0.0, px = 0.0, py = 0.0, pz = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : ke, px, py, pz) if (n >= kParallelMinParticles)
  for (std::int64_t i = 0; i < n; ++i) {
    const double* v = p_.v.data() + 3 * i;
    ke += 0.5 * p_.mass[i] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    px += p_.mass[i] * v[0];
    py += p_.mass[i] * v[1];
    pz += p_.mass[i] * v[2];
  }
  ledger_.kinetic = ke;
  ledger_.momentum = {px, py, pz};
  ledger_.material_dissipated = std::visit(
      [&](const auto& block) {
        double sum = 0.0;
        for (std::size_t i = 0; i < p_.n; ++i) sum += block.law.dissipated_energy(block.state[i]) * p_.volume0[i];
        return sum;
      },
      material_);
}

bool ExplicitSolver::step() {
  const double h = dt();
  velocity_verlet_step(*this, h);
  time_ += h;
  ++steps_;
  update_momentum_and_kinetic();
  if (failure_ < 0 && !std::isfinite(ledger_.kinetic))  // name the first particle that went non-finite
    for (std::size_t i = 0; i < p_.n && failure_ < 0; ++i)
      if (!std::isfinite(p_.v[3 * i]) || !std::isfinite(p_.v[3 * i + 1]) || !std::isfinite(p_.v[3 * i + 2]))
        failure_ = static_cast<std::int64_t>(i);
  return failure_ < 0;
}

}  // namespace uhpc::macro
