#pragma once
// The per-particle constitutive update of one step, generic over the law (instantiated once per
// alternative of MaterialSet, so the loop body calls the law directly):
//   D = sym L, W = skew L (from the velocity gradient at the mid-step configuration);
//   objective rotation split symmetrically around the law: sigma <- R sigma R^T, law update with
//   D dt, sigma <- R sigma R^T, where R = (I - W dt/4)^-1 (I + W dt/4) is the Cayley (Hughes-Winget)
//   rotation over half the step. R is exactly orthogonal and R(-W) = R(W)^T, so the update is
//   objective to second order and a step run backwards (L -> -L) undoes it to round-off;
//   V <- V exp(tr D dt) (exactly reversible too), rho = m / V;
//   bulk viscosity q and the particle's critical step from the new wave speed.
// The law rotates every objective tensor of its state (Law::rotate: the stress, and for AFC its
// effective and driver stresses), so the law itself stays a small-strain update.
// NSNI (when Particles::stress_grad is sized): each direction's stabilization stress gradient is
// rotated the same way, advanced with the law's isotropic moduli (the current tangent),
// dsigma_,d = C : sym(L_,d) dt, and returned with the stress by the law's return mapping
// (nsni_gradient_return.hpp); its power M sigma_,d : D_,d V-weighted like the stress power
// (M = V^(5/3) / 12). For a law that splits its stress (eq. 21, Particles::stress_grad_nominal sized)
// stress_grad is the effective gradient and the forces use its split, stress_grad_nominal.
// Each particle's stress work is also summed into Particles::work (its dissipation is that work minus
// the energy the law says it stores).
// Stress power is integrated with the trapezoid rule in the co-rotated frame, 0.5 (s_a + s_b) : D dt V_mid,
// which is exact for a linear law: the internal energy of an elastic body is then its strain energy.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include <Eigen/Dense>

#include "materials/material_step.hpp"
#include "solver/parallel.hpp"
#include "solver/bulk_viscosity.hpp"
#include "solver/nsni_gradient_return.hpp"
#include "solver/nsni_moment.hpp"
#include "solver/particles.hpp"

namespace uhpc::macro {

struct StressUpdateSums {
  double stress_work = 0.0;   // J, this step
  double viscous_work = 0.0;  // J, this step (>= 0)
  double stabilization_work = 0.0;  // J, this step (NSNI; part of the internal energy)
  double min_critical_step = std::numeric_limits<double>::infinity();  // s, before the CFL factor
  std::int64_t inverted = -1;  // a particle whose volume became non-positive or non-finite, else -1
};

// The update of particle i (reads p.vel_grad and, with NSNI, p.vel_grad_grad of i; writes its stress,
// stress gradient, volume, density, wave speed and bulk viscosity), its shares added to `sums` (a
// thread's running sums: the terms are added one by one, in the order of the particles).
template <class Block>
void update_stress(Block& block, Particles& p, std::int64_t i, double dt, const BulkViscosity& viscosity,
                   StressUpdateSums& sums) {
  const bool nsni = !p.stress_grad.empty();
  const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> L(p.vel_grad.data() + 9 * i);
  const Mat3 D = 0.5 * (L + L.transpose());
  const Mat3 W = 0.5 * (L - L.transpose());
  const Mat3 I = Mat3::Identity();
  const Mat3 R = (I - 0.25 * dt * W).inverse() * (I + 0.25 * dt * W);
  const double trD = D.trace();

  const double v_old = p.volume[i];
  const double v_new = v_old * std::exp(trD * dt);
  const double v_mid = v_old * std::exp(0.5 * trD * dt);
  if (!(v_new > 0.0) || !std::isfinite(v_new)) sums.inverted = std::max(sums.inverted, i);

  auto& state = block.state[static_cast<std::size_t>(i)];
  block.law.rotate(state, R);
  const Mat3 s_a = state.stress;
  MaterialStep step;
  step.strain_increment = D * dt;
  step.dt_s = dt;
  step.density_ratio = p.volume0[i] / v_new;
  step.spacing_m = p.spacing[i];
  block.law.update(state, step);
  const double work = 0.5 * (s_a + state.stress).cwiseProduct(D).sum() * dt * v_mid;
  sums.stress_work += work;
  p.work[i] += work;
  if (nsni) {
    // In the frame of the law's update (before the second half rotation), like the stress.
    const Moduli mod = block.law.moduli(state);
    const StressGradientReturn gradient_return(block.law.effective_stress(state), mod);
    const double lambda = mod.bulk_Pa - 2.0 / 3.0 * mod.shear_Pa;
    const double moment = nsni_moment(v_mid, p.nsni_moment_scale);
    const bool split = !p.stress_grad_nominal.empty();
    for (int d = 0; d < 3; ++d) {
      const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> G(p.vel_grad_grad.data() + 27 * i + 9 * d);
      Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> sg(p.stress_grad.data() + 27 * i + 9 * d);
      const Mat3 Dd = 0.5 * (G + G.transpose());
      const Mat3 g_a = R * sg * R.transpose();
      Mat3 g_b = g_a + (lambda * Dd.trace() * I + 2.0 * mod.shear_Pa * Dd) * dt;
      gradient_return.apply(g_b);
      sg = R * g_b * R.transpose();
      if (split) {  // the gradient the forces use: the split of the effective one
        Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> sn(p.stress_grad_nominal.data() + 27 * i + 9 * d);
        const Mat3 n_a = R * sn * R.transpose();
        const Mat3 n_b = gradient_return.nominal(g_b);
        sums.stabilization_work += moment * 0.5 * (n_a + n_b).cwiseProduct(Dd).sum() * dt;
        sn = R * n_b * R.transpose();
      } else {
        sums.stabilization_work += moment * 0.5 * (g_a + g_b).cwiseProduct(Dd).sum() * dt;
      }
    }
  }
  block.law.rotate(state, R);
  Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(p.stress.data() + 9 * i) = state.stress;

  p.volume[i] = v_new;
  p.density[i] = p.mass[i] / v_new;
  const double c = block.law.wave_speed(state, step.density_ratio);
  p.wave_speed[i] = c;
  const double h = stable_length(v_new, p.spacing[i]);
  const bool damped = viscosity.damp_stress_free_points || !block.law.stress_free(state, step.density_ratio);
  const double trD_damped = damped ? trD : 0.0;
  const double q = viscosity.pressure(p.density[i], h, c, trD_damped);
  p.bulk_q[i] = q;
  sums.viscous_work += -q * trD * dt * v_mid;
  sums.min_critical_step = std::min(sums.min_critical_step, viscosity.critical_step(h, c, trD_damped));
}

// Adds a thread's sums into the reduction variables of its parallel region (each starts at 0, so the
// result is that of reducing the terms directly).
inline void add_sums(const StressUpdateSums& s, double& work, double& visc, double& stab, double& dt_min,
                     std::int64_t& inverted) {
  work += s.stress_work;
  visc += s.viscous_work;
  stab += s.stabilization_work;
  dt_min = std::min(dt_min, s.min_critical_step);
  inverted = std::max(inverted, s.inverted);
}

template <class Block>
StressUpdateSums update_stresses(Block& block, Particles& p, double dt, const BulkViscosity& viscosity,
                                 const std::uint8_t* counted = nullptr) {
  const std::int64_t n = static_cast<std::int64_t>(p.n);
  double work = 0.0, visc = 0.0, stab = 0.0, dt_min = std::numeric_limits<double>::infinity();
  std::int64_t inverted = -1;
#pragma omp parallel reduction(+ : work, visc, stab) reduction(min : dt_min) reduction(max : inverted) if (n >= kParallelMinParticles)
  {
    StressUpdateSums sums, ghosts;  // ghosts: a ghost's shares, not counted
#pragma omp for schedule(static, kRowChunk)
    for (std::int64_t i = 0; i < n; ++i) update_stress(block, p, i, dt, viscosity, !counted || counted[i] ? sums : ghosts);
    add_sums(sums, work, visc, stab, dt_min, inverted);
  }
  return {work, visc, stab, dt_min, inverted};
}

}  // namespace uhpc::macro
