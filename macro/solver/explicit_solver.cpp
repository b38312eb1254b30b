#include "solver/explicit_solver.hpp"
#include "solver/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <initializer_list>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include "solver/kinematics.hpp"
#include "solver/nsni_moment.hpp"
#include "solver/stress_update.hpp"

namespace uhpc::macro {

namespace {
// End-of-step strain (End, EndpointAverage), shapes prepared at x: the RK rows built one by one, and
// with each row while it is still in cache its velocity gradients (averaged with the start-of-step
// L_start, G_start when given), the stress update of its particle and its internal forces, instead of
// four passes over the stored table. The same values, bitwise, as those passes: every particle sees
// the same sums, and the same chunked static schedule (kRowChunk) gives each thread's force buffer the rows and the stress
// sums the terms in the order of InternalForce::compute and update_stresses.
// With L_start (EndpointAverage) and !start_done, the start-of-step gradients come from the old rows
// still in place (lazy rows, ShapeCache::prepare): a due row's are read before its rebuild, and a
// kept row has the same gradients at both ends (its L is already the average).
// counted (optional): only these particles' shares go into the sums (a distributed run's owned ones).
template <class Block>
StressUpdateSums rows_stresses_and_forces(ShapeCache& shapes, InternalForce& force, Block& block, Particles& p,
                                          const double* L_start, const double* G_start, bool start_done, double dt,
                                          const BulkViscosity& viscosity, const std::uint8_t* counted) {
  const std::int64_t n = static_cast<std::int64_t>(p.n);
  const bool nsni = shapes.has_second_gradients() && !p.stress_grad.empty();
  double work = 0.0, visc = 0.0, stab = 0.0, dt_min = std::numeric_limits<double>::infinity();
  std::int64_t inverted = -1;
#pragma omp parallel reduction(+ : work, visc, stab) reduction(min : dt_min) reduction(max : inverted) if (n >= kParallelMinParticles)
  {
    double* scratch = shapes.thread_scratch();
    double* buf = force.begin(p.n);
    StressUpdateSums sums, ghosts;  // ghosts: a ghost's shares, not counted
#pragma omp for schedule(static, kRowChunk)
    for (std::int64_t i = 0; i < n; ++i) {
      const double *Ls = nullptr, *Gs = nullptr;
      double L_old[9], G_old[27];
      if (L_start && start_done) {
        Ls = L_start + 9 * i;
        Gs = G_start ? G_start + 27 * i : nullptr;
      } else if (L_start && !shapes.row_kept(i)) {
        const std::int64_t b = shapes.row_begin(i);
        point_velocity_gradients(shapes.fragment(i), shapes.row_nodes(i), shapes.row_size(i), shapes.grad.data() + 3 * b,
                                 G_start ? shapes.hess.data() + 6 * b : nullptr, p.v.data(), i, L_old,
                                 G_start ? G_old : nullptr);
        Ls = L_old;
        Gs = G_start ? G_old : nullptr;
      }
      shapes.build_row(i, scratch);
      const std::int64_t b = shapes.row_begin(i);
      double* L = p.vel_grad.data() + 9 * i;
      double* G = nsni ? p.vel_grad_grad.data() + 27 * i : nullptr;
      point_velocity_gradients(shapes.fragment(i), shapes.row_nodes(i), shapes.row_size(i), shapes.grad.data() + 3 * b,
                               nsni ? shapes.hess.data() + 6 * b : nullptr, p.v.data(), i, L, G);
      if (Ls) {
        for (int m = 0; m < 9; ++m) L[m] = 0.5 * (Ls[m] + L[m]);
        if (G && Gs)
          for (int m = 0; m < 27; ++m) G[m] = 0.5 * (Gs[m] + G[m]);
      }
      update_stress(block, p, i, dt, viscosity, !counted || counted[i] ? sums : ghosts);
      InternalForce::add_row(shapes, i, p.stress.data(), p.bulk_q.data(), p.volume.data(),
                             nsni ? p.force_stress_grad().data() : nullptr, buf, p.nsni_moment_scale);
    }
    force.finish(p.n, p.f_int.data());
    add_sums(sums, work, visc, stab, dt_min, inverted);
  }
  return {work, visc, stab, dt_min, inverted};
}
}  // namespace

ExplicitSolver::ExplicitSolver(Particles particles, MaterialSet material, const SolverOptions& options)
    : p_(std::move(particles)), material_(std::move(material)), options_(options) {
  const std::size_t states = std::visit([](const auto& b) { return b.state.size(); }, material_);
  if (states != p_.n) throw std::invalid_argument("ExplicitSolver: one material state per particle is required");
  if (!(options_.cfl > 0 && options_.cfl <= 1)) throw std::invalid_argument("ExplicitSolver: cfl must be in (0, 1]");
  if (!(options_.support_factor > 1)) throw std::invalid_argument("ExplicitSolver: support_factor must be > 1");
  if (!(options_.nsni_coefficient > 0) || !std::isfinite(options_.nsni_coefficient))
    throw std::invalid_argument("ExplicitSolver: nsni_coefficient must be finite and > 0");
  if (options_.viscosity.c_linear < 0 || options_.viscosity.c_quadratic < 0)
    throw std::invalid_argument("ExplicitSolver: bulk viscosity coefficients must be >= 0");
  if (!(options_.dt_collapse_fraction >= 0 && options_.dt_collapse_fraction < 1))
    throw std::invalid_argument("ExplicitSolver: dt_collapse_fraction must be in [0, 1)");
  if (options_.max_step_repeats < 0) throw std::invalid_argument("ExplicitSolver: max_step_repeats must be >= 0");
  if (!(options_.energy_error_limit >= 0)) throw std::invalid_argument("ExplicitSolver: energy_error_limit must be >= 0");
  if (!(options_.domain_margin > 0)) throw std::invalid_argument("ExplicitSolver: domain_margin must be > 0");
  if (!(options_.neighbour_skin >= 0)) throw std::invalid_argument("ExplicitSolver: neighbour_skin must be >= 0");
  const double reuse = options_.shape_reuse_tolerance;
  if (reuse != 0 && !(reuse > 0 && reuse < 0.5 * options_.neighbour_skin))
    throw std::invalid_argument("ExplicitSolver: shape_reuse_tolerance must be 0 or in (0, neighbour_skin / 2)");
  if (!(options_.fragment_rcond >= 0 && options_.fragment_rcond < 1))
    throw std::invalid_argument("ExplicitSolver: fragment_rcond must be in [0, 1)");
  shapes_ = empty_shape_cache();
  st_.f_ext_old.assign(3 * p_.n, 0.0);
  st_.f_contact_old.assign(3 * p_.n, 0.0);
  if (p_.f_contact.size() != 3 * p_.n) p_.f_contact.assign(3 * p_.n, 0.0);
  if (options_.stabilization == Stabilization::Nsni) {
    p_.nsni_moment_scale = options_.nsni_coefficient;
    p_.stress_grad.assign(27 * p_.n, 0.0);
    p_.vel_grad_grad.assign(27 * p_.n, 0.0);
    if (std::visit([](const auto& b) { return b.law.splits_stress(); }, material_))
      p_.stress_grad_nominal.assign(27 * p_.n, 0.0);
  }
  if (options_.strain_configuration == StrainConfiguration::EndpointAverage) {
    vel_grad_start_.assign(9 * p_.n, 0.0);
    if (second_options()) vel_grad_grad_start_.assign(27 * p_.n, 0.0);
  }
}

ShapeCache ExplicitSolver::empty_shape_cache() const {
  ShapeCache cache;
  cache.skin = options_.neighbour_skin;
  cache.reuse_tolerance = options_.shape_reuse_tolerance;
  cache.fragment_rcond = options_.fragment_rcond;
  cache.keep_psi = false;  // the step reads only the gradients
  if (share_) {  // a rank's part: its own rows decide a new layout of lazy rows, with the other ranks
    cache.counted = share_->owned.data();
    cache.any_rank = [min = share_->min](bool mine) { return min(mine ? 0.0 : 1.0) == 0.0; };  // as ranks_any
  }
  return cache;
}

void ExplicitSolver::set_rank_share(RankShare share) {
  if (initialized_) throw std::logic_error("ExplicitSolver::set_rank_share: call before initialize()");
  if (share.owned.size() != p_.n || share.ids.size() != p_.n)
    throw std::invalid_argument("ExplicitSolver::set_rank_share: one owned flag and one id per particle are required");
  if (!share.min || !share.sum || !share.gather)
    throw std::invalid_argument("ExplicitSolver::set_rank_share: the ranks' min, sum and gather are required");
  if (!std::is_sorted(share.ids.begin(), share.ids.end()))
    throw std::invalid_argument("ExplicitSolver::set_rank_share: the particles must be in ascending global ids");
  share_ = std::move(share);
  shapes_ = empty_shape_cache();
  // The penalty contact's stiffness is the reference state's (SphereContact::initialize). One process
  // takes it from initialize(); a rank's solver made again from records (continue_from) takes it from
  // its states as made, before the records replace them.
  reference_wave_speed_.resize(p_.n);
  std::visit(
      [&](const auto& block) {
        for (std::size_t i = 0; i < p_.n; ++i)
          reference_wave_speed_[i] = block.law.wave_speed(block.state[i], p_.volume0[i] / p_.volume[i]);
      },
      material_);
}

std::size_t ExplicitSolver::row_record_length(std::size_t i) const {
  if (!share_ || !initialized_) throw std::logic_error("ExplicitSolver::row_record_length: for a distributed run's rank solvers");
  return shapes_.row_record_length(i);
}

double* ExplicitSolver::write_row(std::size_t i, double* out) const { return shapes_.write_row(i, share_->ids.data(), out); }

void ExplicitSolver::install_rows(const std::vector<const double*>& records,
                                  const std::function<std::int32_t(std::uint32_t)>& local_of) {
  if (!share_ || !initialized_) throw std::logic_error("ExplicitSolver::install_rows: after continue_from");
  shapes_.install_rows(p_.n, records, local_of, second_options());
  shapes_at_x_ = true;  // as the solver it replaces left them, at the positions of its last step
}

void ExplicitSolver::ranks_sum(std::initializer_list<double*> values) const {
  if (!share_) return;
  double sums[8];
  if (values.size() > std::size(sums)) throw std::logic_error("ExplicitSolver::ranks_sum: more values than it holds");
  std::size_t k = 0;
  for (const double* v : values) sums[k++] = *v;
  share_->sum(sums, static_cast<int>(k));
  k = 0;
  for (double* v : values) *v = sums[k++];
}

ExplicitSolver::RunState ExplicitSolver::run_state() const {
  if (!initialized_) throw std::logic_error("ExplicitSolver::run_state: the solver is not initialized");
  RunState run{st_, counters_, domain_};
  run.state.f_ext_old.clear();  // the particles' own, which travel in their records
  run.state.f_contact_old.clear();
  return run;
}

// The run's step state and counters from another solver or a checkpoint, keeping this solver's own
// particles' last forces (f_ext_old, f_contact_old: read_particle's, or the caller's to set).
void ExplicitSolver::take_run_state(const StepState& state, const StepCounters& counters) {
  std::vector<double> f_ext_old = std::move(st_.f_ext_old), f_contact_old = std::move(st_.f_contact_old);
  st_ = state;
  st_.f_ext_old = std::move(f_ext_old);
  st_.f_contact_old = std::move(f_contact_old);
  counters_ = counters;
}

void ExplicitSolver::continue_from(const RunState& run) {
  if (initialized_) throw std::logic_error("ExplicitSolver::continue_from: the solver is already initialized");
  if (!share_) throw std::logic_error("ExplicitSolver::continue_from: for a distributed run's rank solvers");
  if (st_.sphere.has_value() != run.state.sphere.has_value())
    throw std::invalid_argument("ExplicitSolver::continue_from: the solvers disagree on the sphere");
  take_run_state(run.state, run.counters);
  domain_ = run.domain;
  if (st_.sphere) sphere_contact_.initialize(*st_.sphere, p_, reference_wave_speed_.data(), &*share_);
  drop_shape_cache();
  save_state();
  initialized_ = true;
}

void ExplicitSolver::set_sphere(const RigidSphere& sphere) {
  if (initialized_) throw std::logic_error("ExplicitSolver::set_sphere: call before initialize()");
  sphere.validate();
  st_.sphere = sphere;
  st_.sphere->x_prev = st_.sphere->x;
}

double ExplicitSolver::stable_step(std::initializer_list<double> critical_steps) const {
  return options_.cfl * ranks_min(std::min(critical_steps));
}

double ExplicitSolver::travel_limit() const {
  return st_.sphere ? sphere_contact_.travel_limit(*st_.sphere) : std::numeric_limits<double>::infinity();
}

const SecondGradientOptions* ExplicitSolver::second_options() const {
  return options_.stabilization == Stabilization::Nsni ? &options_.second_gradients : nullptr;
}

void ExplicitSolver::rebuild_shapes(const double* x, double* L, double* G) {
  const RowVelocityGradients gradients{p_.v.data(), L, G};
  shapes_.rebuild(options_.rk, x, p_.support.data(), p_.n, second_options(), L ? &gradients : nullptr);
}

void ExplicitSolver::velocity_gradients(double* L, double* G) const {
  uhpc::macro::velocity_gradients(shapes_, p_.v.data(), p_.n, L, G);
}

void ExplicitSolver::initialize() {
  // Stresses from the states (zero for a body at rest), wave speeds at the reference density.
  double material_step = std::numeric_limits<double>::infinity();
  std::visit(
      [&](auto& block) {
        for (std::size_t i = 0; i < p_.n; ++i) {
          Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(p_.stress.data() + 9 * i) = block.state[i].stress;
          p_.wave_speed[i] = block.law.wave_speed(block.state[i], p_.volume0[i] / p_.volume[i]);
          if (counted(i)) material_step = std::min(material_step, options_.viscosity.critical_step(stable_length(p_.volume[i], p_.spacing[i]), p_.wave_speed[i], 0.0));
        }
      },
      material_);
  if (st_.sphere) sphere_contact_.initialize(*st_.sphere, p_, p_.wave_speed.data(), share_ ? &*share_ : nullptr);
  // The first contact forces are predicted over the first step: bound it by the travel before they are
  // computed, then by the contact they give.
  st_.dt_s = stable_step({material_step, travel_limit()});
  domain_ = options_.domain ? *options_.domain : default_domain();
  constrain_velocities();
  p_.x_prev = p_.x;
  rebuild_shapes(p_.x.data());
  shapes_at_x_ = true;
  compute_forces(0.0, dt());  // no step has produced this configuration yet
  if (st_.sphere) st_.dt_s = stable_step({material_step, travel_limit(), st_.contact.critical_step});
  st_.f_ext_old = p_.f_ext;
  st_.f_contact_old = p_.f_contact;
  if (st_.sphere) st_.sphere_force_old = st_.sphere->force;
  update_momentum_and_kinetic();
  st_.ledger.kinetic_initial = st_.ledger.kinetic;
  st_.ledger.momentum_initial = st_.ledger.momentum;
  st_.ledger.contact_stored = st_.contact.stored_energy;
  save_state();  // sizes the saved copy once, so the step loop only copies
  initialized_ = true;
}

Region ExplicitSolver::default_domain() const {
  Region box{{HUGE_VAL, HUGE_VAL, HUGE_VAL}, {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL}};
  auto grow = [&](const double* x, double r) {
    for (int d = 0; d < 3; ++d) {
      box.lo[d] = std::min(box.lo[d], x[d] - r);
      box.hi[d] = std::max(box.hi[d], x[d] + r);
    }
  };
  for (std::size_t i = 0; i < p_.n; ++i)
    if (counted(i)) grow(p_.x.data() + 3 * i, 0.5 * p_.spacing[i]);
  if (st_.sphere) grow(st_.sphere->x.data(), st_.sphere->radius_m);
  if (share_)  // the whole body's box
    for (int d = 0; d < 3; ++d) {
      box.lo[d] = ranks_min(box.lo[d]);
      box.hi[d] = -ranks_min(-box.hi[d]);
    }
  double extent = 0.0;
  for (int d = 0; d < 3; ++d) extent = std::max(extent, box.hi[d] - box.lo[d]);
  for (int d = 0; d < 3; ++d) {
    box.lo[d] -= options_.domain_margin * extent;
    box.hi[d] += options_.domain_margin * extent;
  }
  return box;
}

void ExplicitSolver::constrain_velocities() {
  for (const PrescribedVelocity& bc : prescribed_)
    for (const std::int32_t i : bc.particles)
      for (int d = 0; d < 3; ++d) p_.v[3 * static_cast<std::size_t>(i) + d] = bc.velocity[d];
}

void ExplicitSolver::compute_accelerations(double dt) {
  const std::int64_t n = static_cast<std::int64_t>(p_.n);
  if (st_.sphere) {  // the sphere drifts where the particles drift (velocity_verlet_step, before this call)
    RigidSphere& s = *st_.sphere;
    for (int d = 0; d < 3; ++d) {
      s.x_prev[d] = s.x[d];
      s.x[d] += dt * s.v[d];
    }
  }
  // A position that is not finite or, when the domain is the guard, outside it fails the step (attempt()
  // names it); stop here, before the neighbour search meets it.
  if (ranks_any(first_non_finite(p_, owned_flags()) >= 0 || (domain_is_guard() && first_outside(p_, domain_, owned_flags()) >= 0))) return;
  const StrainConfiguration config = options_.strain_configuration;
  const bool nsni = second_options() != nullptr;
  if (config == StrainConfiguration::EndpointAverage) {
    // The x_n gradients: those of the last force evaluation, unless a restored state left the failed
    // attempt's in shapes_ (x_prev is the restored x). The velocity gradient reads only the stored
    // lists and values, not the positions, so the drift above does not disturb them.
    if (!shapes_at_x_) rebuild_shapes(p_.x_prev.data());
  }
  const double* x_strain = p_.x.data();
  if (config == StrainConfiguration::Midpoint) {
#pragma omp parallel for schedule(static) if (n >= kParallelMinParticles)
    for (std::int64_t i = 0; i < 3 * n; ++i) p_.x_mid[i] = 0.5 * (p_.x_prev[i] + p_.x[i]);
    x_strain = p_.x_mid.data();
  }
  StressUpdateSums sums;
  if (config == StrainConfiguration::Midpoint) {
    // The strain-configuration gradients come out of the rebuild, row by row; the forces need the
    // shapes at x, rebuilt below.
    rebuild_shapes(x_strain, p_.vel_grad.data(), nsni ? p_.vel_grad_grad.data() : nullptr);
    shapes_at_x_ = false;
    sums = std::visit([&](auto& block) { return update_stresses(block, p_, dt, options_.viscosity, owned_flags()); }, material_);
  } else {
    const bool average = config == StrainConfiguration::EndpointAverage;
    // EndpointAverage: the x_n gradients of the rows before prepare replaces them (all of them here,
    // or row by row inside the loop below when lazy rows keep the old ones in place).
    const RowVelocityGradients start{p_.v.data(), vel_grad_start_.data(), nsni ? vel_grad_grad_start_.data() : nullptr};
    const bool start_done =
        shapes_.prepare(options_.rk, x_strain, p_.support.data(), p_.n, second_options(), average ? &start : nullptr);
    shapes_at_x_ = true;
    sums = std::visit(
        [&](auto& block) {
          return rows_stresses_and_forces(shapes_, force_, block, p_, average ? vel_grad_start_.data() : nullptr,
                                          average && nsni ? vel_grad_grad_start_.data() : nullptr, start_done, dt,
                                          options_.viscosity, owned_flags());
        },
        material_);
  }
  ranks_sum({&sums.stress_work, &sums.stabilization_work, &sums.viscous_work});
  st_.ledger.internal += sums.stress_work + sums.stabilization_work;
  st_.ledger.stabilization += sums.stabilization_work;
  st_.ledger.viscous += sums.viscous_work;
  if (sums.inverted >= 0) inverted_ = sums.inverted;

  if (config == StrainConfiguration::Midpoint) {
    rebuild_shapes(p_.x.data());
    shapes_at_x_ = true;
  }
  // The next step as far as it is known now (the kinematic contact predicts the next configuration
  // with it), then as the contact's forces bound it.
  const double dt_next =
      options_.fixed_dt_s > 0 ? options_.fixed_dt_s : stable_step({sums.min_critical_step, travel_limit()});
  compute_forces(dt, dt_next, config == StrainConfiguration::Midpoint);
  st_.dt_s = stable_step({sums.min_critical_step, st_.sphere ? st_.contact.critical_step : std::numeric_limits<double>::infinity()});
  if (st_.sphere) st_.ledger.contact_stored = st_.contact.stored_energy;

  // External work and impulse by the trapezoid rule over the step.
  double work = 0.0, ix = 0.0, iy = 0.0, iz = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : work, ix, iy, iz) if (n >= kParallelMinParticles)
  for (std::int64_t i = 0; i < n; ++i) {
    if (!counted(static_cast<std::size_t>(i))) continue;
    double f[3];
    for (int d = 0; d < 3; ++d) f[d] = 0.5 * (st_.f_ext_old[3 * i + d] + p_.f_ext[3 * i + d]);
    for (int d = 0; d < 3; ++d) work += f[d] * (p_.x[3 * i + d] - p_.x_prev[3 * i + d]);
    ix += f[0] * dt;
    iy += f[1] * dt;
    iz += f[2] * dt;
  }
  ranks_sum({&work, &ix, &iy, &iz});
  st_.ledger.external += work;
  st_.ledger.external_impulse[0] += ix;
  st_.ledger.external_impulse[1] += iy;
  st_.ledger.external_impulse[2] += iz;
  std::copy(p_.f_ext.begin(), p_.f_ext.end(), st_.f_ext_old.begin());
}

void ExplicitSolver::compute_forces(double dt, double dt_next, bool internal) {
  if (internal)
    force_.compute(shapes_, p_.stress.data(), p_.bulk_q.data(), p_.volume.data(), p_.n, p_.f_int.data(),
                   p_.stress_grad.empty() ? nullptr : p_.force_stress_grad().data(), p_.nsni_moment_scale);
  const std::int64_t n = static_cast<std::int64_t>(p_.n);
  double wall_total = 0.0;
  // The force of wall w on particle i (added to fe), its magnitude returned.
  const auto wall_force = [&](const Wall& w, std::size_t i, double* fe) {
    const double* x = p_.x.data() + 3 * i;
    double gap = 0.0;
    for (int d = 0; d < 3; ++d) gap += (x[d] - w.point[d]) * w.normal[d];
    const double delta = 0.5 * p_.spacing[i] - gap;
    if (delta <= 0.0) return 0.0;
    const double k = w.penalty_scale * p_.density[i] * p_.wave_speed[i] * p_.wave_speed[i] * p_.spacing[i];
    for (int d = 0; d < 3; ++d) fe[d] += k * delta * w.normal[d];
    return counted(i) ? k * delta : 0.0;
  };
#pragma omp parallel for schedule(static) reduction(+ : wall_total) if (n >= kParallelMinParticles)
  for (std::int64_t i = 0; i < n; ++i) {
    double* fe = p_.f_ext.data() + 3 * i;
    fe[0] = fe[1] = fe[2] = 0.0;
    for (const Wall& w : walls_)
      if (w.particles.empty()) wall_total += wall_force(w, static_cast<std::size_t>(i), fe);
  }
  for (const Wall& w : walls_)  // supports over part of the body, one wall after the other
    for (const std::int32_t j : w.particles)
      wall_total += wall_force(w, static_cast<std::size_t>(j), p_.f_ext.data() + 3 * static_cast<std::size_t>(j));
  ranks_sum({&wall_total});
  st_.wall_force_N = wall_total;
  if (st_.sphere) {
    st_.contact = sphere_contact_.compute(*st_.sphere, p_, dt, dt_next, p_.f_contact.data(), share_ ? &*share_ : nullptr);
    st_.sphere->force = st_.contact.force_on_sphere;
  }
  // Prescribed velocities: the reaction cancels every other force (constant velocity, a = 0), so the
  // external force on such a particle is -f_int.
  for (const PrescribedVelocity& bc : prescribed_)
    for (const std::int32_t j : bc.particles)
      for (int d = 0; d < 3; ++d) p_.f_ext[3 * static_cast<std::size_t>(j) + d] = -p_.f_int[3 * static_cast<std::size_t>(j) + d];
#pragma omp parallel for schedule(static) if (n >= kParallelMinParticles)
  for (std::int64_t i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d)
      p_.a[3 * i + d] = (p_.f_int[3 * i + d] + p_.f_ext[3 * i + d] + p_.f_contact[3 * i + d]) / p_.mass[i];
}

namespace {
// The particle fields a step changes and the next step reads before it rewrites them. Not copied:
// the constants of the step loop (mass, volume0, spacing, support) and the per-step scratch each
// step recomputes before use (x_prev, x_mid, vel_grad, vel_grad_grad).
struct EvolvingField {
  const char* name;
  std::vector<double> Particles::*field;
};
constexpr EvolvingField kEvolvingFields[] = {
    {"x", &Particles::x},           {"v", &Particles::v},
    {"a", &Particles::a},           {"f_int", &Particles::f_int},
    {"f_ext", &Particles::f_ext},   {"f_contact", &Particles::f_contact},
    {"volume", &Particles::volume}, {"density", &Particles::density},
    {"stress", &Particles::stress}, {"bulk_q", &Particles::bulk_q},
    {"wave_speed", &Particles::wave_speed}, {"work", &Particles::work},
    {"stress_grad", &Particles::stress_grad}, {"stress_grad_nominal", &Particles::stress_grad_nominal}};

// Where a field is in kEvolvingFields (and so in the saved copy).
constexpr std::size_t evolving_index(std::vector<double> Particles::*field) {
  std::size_t k = 0;
  while (kEvolvingFields[k].field != field) ++k;
  return k;
}
}  // namespace

// The work of the contact forces over the step, kick by kick: a half kick dt/2 f changes a body's
// kinetic energy by dt/2 f . (v_before + v_after) / 2 of its own velocities, so summed over the two
// half kicks this is the kinetic energy the contact gave, exactly, however impulsive its forces (the
// trapezoid of force times displacement is off by m dt^2 |a|^2 / 8 at each end of an impulse, which
// showed as one-step spikes of the balance). The velocities before each kick follow from the end
// velocities and the start- and end-of-step accelerations.
void ExplicitSolver::book_contact_work(double h) {
  const std::int64_t n = static_cast<std::int64_t>(p_.n);
  // The first half kick's accelerations (saved at the step's start).
  const double* a0 = saved_.particle_fields[evolving_index(&Particles::a)].data();
  double work = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : work) if (n >= kParallelMinParticles)
  for (std::int64_t k = 0; k < 3 * n; ++k) {
    const double f0 = st_.f_contact_old[k], f1 = p_.f_contact[k];
    if ((f0 == 0.0 && f1 == 0.0) || !counted(static_cast<std::size_t>(k / 3))) continue;
    const double v1 = p_.v[k], v_half = v1 - 0.5 * h * p_.a[k], v0 = v_half - 0.5 * h * a0[k];
    work += 0.25 * h * (f0 * (v0 + v_half) + f1 * (v_half + v1));
  }
  ranks_sum({&work});
  const RigidSphere& s = *st_.sphere;
  for (int d = 0; d < 3; ++d) {
    const double v1 = s.v[d], v_half = v1 - 0.5 * h * s.force[d] / s.mass_kg;
    const double v0 = v_half - 0.5 * h * st_.sphere_force_old[d] / s.mass_kg;
    work += 0.25 * h * (st_.sphere_force_old[d] * (v0 + v_half) + s.force[d] * (v_half + v1));
  }
  st_.ledger.contact -= work;  // the energy the contact takes
  std::copy(p_.f_contact.begin(), p_.f_contact.end(), st_.f_contact_old.begin());
  st_.sphere_force_old = s.force;
}

void ExplicitSolver::update_momentum_and_kinetic() {
  const std::int64_t n = static_cast<std::int64_t>(p_.n);
  double ke = 0.0, px = 0.0, py = 0.0, pz = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : ke, px, py, pz) if (n >= kParallelMinParticles)
  for (std::int64_t i = 0; i < n; ++i) {
    if (!counted(static_cast<std::size_t>(i))) continue;
    const double* v = p_.v.data() + 3 * i;
    ke += 0.5 * p_.mass[i] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    px += p_.mass[i] * v[0];
    py += p_.mass[i] * v[1];
    pz += p_.mass[i] * v[2];
  }
  ranks_sum({&ke, &px, &py, &pz});
  if (st_.sphere) {
    const RigidSphere& s = *st_.sphere;
    st_.ledger.kinetic_sphere = s.kinetic_energy();
    st_.ledger.momentum_sphere = {s.mass_kg * s.v[0], s.mass_kg * s.v[1], s.mass_kg * s.v[2]};
    ke += st_.ledger.kinetic_sphere;
    px += st_.ledger.momentum_sphere[0];
    py += st_.ledger.momentum_sphere[1];
    pz += st_.ledger.momentum_sphere[2];
  }
  st_.ledger.kinetic = ke;
  st_.ledger.momentum = {px, py, pz};
  update_material_books();
}

void ExplicitSolver::update_material_books() {
  const std::int64_t n = static_cast<std::int64_t>(p_.n);
  const bool nsni = !p_.stress_grad.empty();
  double stored = 0.0, plastic = 0.0, crushing = 0.0, opening = 0.0, stab = 0.0;
  std::visit(
      [&](const auto& block) {
#pragma omp parallel for schedule(static) reduction(+ : stored, plastic, crushing, opening, stab) if (n >= kParallelMinParticles)
        for (std::int64_t i = 0; i < n; ++i) {
          if (!counted(static_cast<std::size_t>(i))) continue;
          const auto& st = block.state[static_cast<std::size_t>(i)];
          stored += block.law.stored_energy(st) * p_.volume[i];
          const DissipationParts parts = block.law.dissipation(st);
          plastic += parts.plastic * p_.volume0[i];
          crushing += parts.crushing * p_.volume0[i];
          opening += parts.opening * p_.volume0[i];
          if (nsni) stab += stabilization_energy(block.law.moduli(st), i);
        }
      },
      material_);
  ranks_sum({&stored, &plastic, &crushing, &opening, &stab});
  st_.ledger.material_stored = stored;
  st_.ledger.material_dissipated = st_.ledger.internal - st_.ledger.stabilization - stored;
  st_.ledger.plastic = plastic;
  st_.ledger.crushing = crushing;
  st_.ledger.opening = opening;
  st_.ledger.stabilization_stored = stab;
}

double ExplicitSolver::stabilization_energy(const Moduli& mod, std::int64_t i) const {
  using RowMat = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>;
  const double v = p_.volume[i];
  const double moment = nsni_moment(v, p_.nsni_moment_scale);
  const std::vector<double>& force = p_.force_stress_grad();
  double e = 0.0;
  for (int d = 0; d < 3; ++d)
    e += half_compliance_product(RowMat(force.data() + 27 * i + 9 * d), RowMat(p_.stress_grad.data() + 27 * i + 9 * d),
                                 mod.bulk_Pa, mod.shear_Pa);
  return moment * e;
}

double ExplicitSolver::dissipated_density(std::size_t i) const {
  return std::visit(
      [&](const auto& block) {
        return (p_.work[i] - block.law.stored_energy(block.state[i]) * p_.volume[i]) / p_.volume0[i];
      },
      material_);
}

StepFailure ExplicitSolver::attempt(double h) {
  inverted_ = -1;
  if (st_.sphere)  // first half kick of the sphere, with the particles' (inside velocity_verlet_step)
    for (int d = 0; d < 3; ++d) st_.sphere->v[d] += 0.5 * h * st_.sphere->force[d] / st_.sphere->mass_kg;
  velocity_verlet_step(*this, h);
  if (st_.sphere) {  // second half kick, with the force of the new configuration
    for (int d = 0; d < 3; ++d) st_.sphere->v[d] += 0.5 * h * st_.sphere->force[d] / st_.sphere->mass_kg;
    book_contact_work(h);
  }
  st_.time_s += h;
  update_momentum_and_kinetic();

  failure_ = FailureReport{};
  std::int64_t particle = first_non_finite(p_, owned_flags());
  StepFailure kind = StepFailure::None;
  if (particle >= 0) {
    kind = StepFailure::NonFinite;
  } else if (st_.sphere && !(std::isfinite(st_.sphere->x[0] + st_.sphere->x[1] + st_.sphere->x[2] + st_.sphere->v[0] +
                                        st_.sphere->v[1] + st_.sphere->v[2]))) {
    kind = StepFailure::NonFinite;
  } else if (inverted_ >= 0) {
    kind = StepFailure::InvertedVolume;
    particle = inverted_;
  } else if (domain_is_guard() && (particle = first_outside(p_, domain_, owned_flags())) >= 0) {
    kind = StepFailure::OutOfDomain;
  } else if (options_.energy_error_limit > 0 && energy_error_ratio(st_.ledger) > options_.energy_error_limit) {
    kind = StepFailure::EnergyBalance;
    failure_.energy_error = energy_error_ratio(st_.ledger);
    particle = most_kinetic_particle(p_, owned_flags());  // where the instability shows first
  }
  if (share_) {  // every rank fails the step when one does (the first failure kind of any rank)
    const double kinds = static_cast<double>(kind == StepFailure::None ? 255 : static_cast<int>(kind));
    const double first = ranks_min(kinds);
    const StepFailure agreed = first == 255.0 ? StepFailure::None : static_cast<StepFailure>(static_cast<int>(first));
    if (agreed != kind) {  // so that no rank repeats the step while another gives it up
      kind = agreed;
      particle = -1;  // another rank's
    }
    if (kind == StepFailure::EnergyBalance) failure_.energy_error = energy_error_ratio(st_.ledger);
  }
  if (kind != StepFailure::None) {
    failure_.kind = kind;
    failure_.particle = particle;
    if (particle >= 0) {
      const std::size_t i = static_cast<std::size_t>(particle);
      if (share_) failure_.particle = share_->ids[i];  // a distributed run names the particle by its global id
      for (int d = 0; d < 3; ++d) {
        failure_.x[d] = p_.x[3 * i + d];
        failure_.v[d] = p_.v[3 * i + d];
      }
      failure_.volume_m3 = p_.volume[i];
      failure_.volume0_m3 = p_.volume0[i];
    } else if (st_.sphere) {
      failure_.x = st_.sphere->x;
      failure_.v = st_.sphere->v;
    }
  }
  return kind;
}

bool ExplicitSolver::step() {
  double h = dt();
  // A step of 0 (or NaN) would never advance time: a run with it fails here rather than loop forever.
  if (!(h > 0.0) || !std::isfinite(h)) {
    failure_ = FailureReport{};
    failure_.kind = StepFailure::StepCollapse;
    failure_.time_s = time();
    failure_.dt_s = h;
    failure_.step = counters_.steps + 1;
    return false;
  }
  save_state();
  const bool guard = options_.fixed_dt_s <= 0 && options_.dt_collapse_fraction > 0;
  for (int repeat = 0;; ++repeat) {
    StepFailure kind = attempt(h);
    // A collapsed stable step is redone first: the energy error of the too-long attempt is its symptom.
    const bool redo_allowed = kind == StepFailure::None || kind == StepFailure::EnergyBalance;
    if (redo_allowed && guard && st_.dt_s < options_.dt_collapse_fraction * h) {
      if (repeat < options_.max_step_repeats) {
        const double smaller = st_.dt_s;
        restore_state();
        ++counters_.repeats;
        h = smaller;
        continue;
      }
      kind = StepFailure::StepCollapse;
      failure_ = FailureReport{};
      failure_.kind = kind;
    }
    if (kind != StepFailure::None) {
      failure_.time_s = saved_.state.time_s;
      failure_.dt_s = h;
      failure_.step = counters_.steps + 1;
      restore_state();
      return false;
    }
    break;
  }
  ++counters_.steps;
  counters_.last_dt_s = h;
  return true;
}

namespace {
// Same-size copy, split over the threads for large arrays (memory bandwidth is per core here).
void copy_same_size(const std::vector<double>& from, std::vector<double>& to) {
  const std::int64_t n = static_cast<std::int64_t>(from.size());
  constexpr std::int64_t kBlock = 8192;
  const std::int64_t blocks = (n + kBlock - 1) / kBlock;
#pragma omp parallel for schedule(static) if (n >= 3 * kParallelMinParticles)
  for (std::int64_t b = 0; b < blocks; ++b) {
    const std::int64_t lo = b * kBlock, hi = std::min(n, lo + kBlock);
    std::copy(from.data() + lo, from.data() + hi, to.data() + lo);
  }
}

void check_size(const char* what, std::size_t got, std::size_t expected) {
  if (got != expected)
    throw std::invalid_argument(std::string("ExplicitSolver::resume: ") + what + ": " + std::to_string(got) +
                                " values, the solver has " + std::to_string(expected));
}

// The checkpoint's particle fields in the order of kEvolvingFields, found by name (a file may list them in
// another order), each checked to hold `particles` particles' values (as many a particle as p's).
std::vector<const std::vector<double>*> checkpoint_fields(const SolverCheckpoint& c, const Particles& p,
                                                          std::size_t particles) {
  std::vector<const std::vector<double>*> fields;
  for (const EvolvingField& f : kEvolvingFields) {
    const auto it = std::find_if(c.particle_fields.begin(), c.particle_fields.end(),
                                 [&](const auto& named) { return named.first == f.name; });
    if (it == c.particle_fields.end())
      throw std::invalid_argument(std::string("ExplicitSolver::resume: no particle field '") + f.name + "'");
    check_size(f.name, it->second.size(), (p.*f.field).size() / std::max<std::size_t>(p.n, 1) * particles);
    fields.push_back(&it->second);
  }
  return fields;
}
}  // namespace

void ExplicitSolver::save_state() {
  saved_.particle_fields.resize(std::size(kEvolvingFields));
  for (std::size_t k = 0; k < std::size(kEvolvingFields); ++k) {
    const std::vector<double>& field = p_.*kEvolvingFields[k].field;
    std::vector<double>& copy = saved_.particle_fields[k];
    if (copy.size() != field.size()) copy = field;  // sizes it (initialize())
    else copy_same_size(field, copy);
  }
  if (saved_.material) *saved_.material = material_; else saved_.material.emplace(material_);
  saved_.state = st_;  // same sizes after the first: the vectors' copies do not allocate
}

// The shape cache is not restored: every step rebuilds it before using it, and EndpointAverage, which
// reads it first, rebuilds it at the restored positions (shapes_at_x_).
void ExplicitSolver::restore_state() {
  shapes_at_x_ = false;
  for (std::size_t k = 0; k < std::size(kEvolvingFields); ++k)
    copy_same_size(saved_.particle_fields[k], p_.*kEvolvingFields[k].field);
  material_ = *saved_.material;
  st_ = saved_.state;
}

SolverCheckpoint ExplicitSolver::checkpoint() const {
  if (share_) throw std::logic_error("ExplicitSolver::checkpoint: for one process (a distributed run: its whole body's, adopt_run_state)");
  SolverCheckpoint c;
  for (const EvolvingField& f : kEvolvingFields) c.particle_fields.emplace_back(f.name, p_.*f.field);
  std::visit(
      [&](const auto& block) {
        using State = typename std::decay_t<decltype(block.state)>::value_type;
        // The states hold scalars and fixed-size Eigen matrices only: standard layout, nothing to free, no
        // pointers, so their bytes are their values (Eigen's copy constructor keeps them from being
        // "trivially copyable" in the standard's sense).
        static_assert(std::is_standard_layout_v<State> && std::is_trivially_destructible_v<State>,
                      "a checkpoint copies the material states as bytes");
        const auto* bytes = reinterpret_cast<const std::uint8_t*>(block.state.data());
        c.material_states.assign(bytes, bytes + block.state.size() * sizeof(State));
      },
      material_);
  c.state = st_;
  c.counters = counters_;
  return c;
}

void ExplicitSolver::resume(const SolverCheckpoint& c) {
  if (!initialized_) throw std::logic_error("ExplicitSolver::resume: call after initialize()");
  if (share_) throw std::logic_error("ExplicitSolver::resume: for one process (a distributed run's rank: resume_part)");
  const std::vector<const std::vector<double>*> fields = checkpoint_fields(c, p_, p_.n);
  check_size("particle fields", c.particle_fields.size(), std::size(kEvolvingFields));
  const std::size_t state_bytes = std::visit(
      [](const auto& block) { return block.state.size() * sizeof(typename std::decay_t<decltype(block.state)>::value_type); },
      material_);
  check_size("material state bytes", c.material_states.size(), state_bytes);
  check_size("f_ext_old", c.state.f_ext_old.size(), st_.f_ext_old.size());
  check_size("f_contact_old", c.state.f_contact_old.size(), st_.f_contact_old.size());
  if (c.state.sphere.has_value() != st_.sphere.has_value())
    throw std::invalid_argument("ExplicitSolver::resume: the checkpoint and the solver disagree on the sphere");
  // Everything checked: now the state is replaced.
  for (std::size_t k = 0; k < fields.size(); ++k) p_.*kEvolvingFields[k].field = *fields[k];
  std::visit([&](auto& block) { std::memcpy(static_cast<void*>(block.state.data()), c.material_states.data(), state_bytes); },
             material_);
  st_ = c.state;
  counters_ = c.counters;
  drop_shape_cache();
  save_state();
}

void ExplicitSolver::resume_part(const SolverCheckpoint& c) {
  if (!initialized_ || !share_) throw std::logic_error("ExplicitSolver::resume_part: for an initialized rank solver");
  std::size_t total = 0;  // the whole body's particles, from the checkpoint's positions
  for (const auto& [name, values] : c.particle_fields)
    if (name == "x") total = values.size() / 3;
  if (total == 0 || c.state.f_ext_old.size() != 3 * total || c.state.f_contact_old.size() != 3 * total)
    throw std::invalid_argument("ExplicitSolver::resume_part: the checkpoint holds no whole body");
  for (const std::uint32_t id : share_->ids)
    if (id >= total) throw std::invalid_argument("ExplicitSolver::resume_part: the checkpoint holds fewer particles than the run");
  const std::vector<const std::vector<double>*> fields = checkpoint_fields(c, p_, total);
  const std::size_t bytes = std::visit([](const auto& b) { return sizeof(b.state[0]); }, material_);
  check_size("material state bytes", c.material_states.size(), bytes * total);
  if (c.state.sphere.has_value() != st_.sphere.has_value())
    throw std::invalid_argument("ExplicitSolver::resume_part: the checkpoint and the solver disagree on the sphere");
  // Everything checked: now the state is replaced.
  for (std::size_t i = 0; i < p_.n; ++i) {
    const std::size_t g = share_->ids[i];
    for (std::size_t k = 0; k < fields.size(); ++k) {
      std::vector<double>& field = p_.*kEvolvingFields[k].field;
      const std::size_t w = field.size() / p_.n;
      std::copy(fields[k]->data() + w * g, fields[k]->data() + w * (g + 1), field.data() + w * i);
    }
    std::visit([&](auto& block) { std::memcpy(static_cast<void*>(&block.state[i]), c.material_states.data() + bytes * g, bytes); },
               material_);
  }
  take_run_state(c.state, c.counters);
  for (std::size_t i = 0; i < p_.n; ++i)
    for (std::size_t d = 0; d < 3; ++d) {
      st_.f_ext_old[3 * i + d] = c.state.f_ext_old[3 * share_->ids[i] + d];
      st_.f_contact_old[3 * i + d] = c.state.f_contact_old[3 * share_->ids[i] + d];
    }
  drop_shape_cache();
  save_state();
}

namespace {
template <class Block>
std::size_t state_bytes_per_particle(const Block&) {
  return sizeof(typename std::decay_t<decltype(std::declval<Block>().state)>::value_type);
}
std::size_t doubles_for(std::size_t bytes) { return (bytes + sizeof(double) - 1) / sizeof(double); }
}  // namespace

SolverCheckpoint ExplicitSolver::body_checkpoint(std::size_t total, const double* records, std::size_t stride) const {
  if (!share_ || p_.n == 0) throw std::logic_error("ExplicitSolver::body_checkpoint: for a rank solver that holds particles");
  SolverCheckpoint c;
  std::size_t at = 0;  // the field's place in a record (write_particle's order)
  for (const EvolvingField& f : kEvolvingFields) {
    const std::size_t w = (p_.*f.field).size() / p_.n;
    std::vector<double> values(w * total);
    for (std::size_t k = 0; k < total; ++k) std::copy(records + stride * k + at, records + stride * k + at + w, values.data() + w * k);
    c.particle_fields.emplace_back(f.name, std::move(values));
    at += w;
  }
  const std::size_t bytes = std::visit([](const auto& b) { return state_bytes_per_particle(b); }, material_);
  c.material_states.resize(bytes * total);
  for (std::size_t k = 0; k < total; ++k) std::memcpy(c.material_states.data() + bytes * k, records + stride * k + at, bytes);
  // The run's state, with the whole body's last forces: those the records carry (as read_particle takes them).
  c.state = st_;
  for (const auto& [name, values] : c.particle_fields) {
    if (name == "f_ext") c.state.f_ext_old = values;
    if (name == "f_contact") c.state.f_contact_old = values;
  }
  c.counters = counters_;
  return c;
}

std::size_t ExplicitSolver::particle_record_width() const {
  std::size_t width = 0;
  for (const EvolvingField& f : kEvolvingFields) width += (p_.*f.field).size() / std::max<std::size_t>(p_.n, 1);
  return width + doubles_for(std::visit([](const auto& b) { return state_bytes_per_particle(b); }, material_));
}

void ExplicitSolver::write_particle(std::size_t i, double* out) const {
  for (const EvolvingField& f : kEvolvingFields) {
    const std::vector<double>& field = p_.*f.field;
    const std::size_t w = field.size() / p_.n;
    out = std::copy(field.data() + w * i, field.data() + w * (i + 1), out);
  }
  std::visit(
      [&](const auto& block) {
        const std::size_t bytes = state_bytes_per_particle(block);
        if (bytes > 0) out[doubles_for(bytes) - 1] = 0.0;  // the last double may be partly padding
        std::memcpy(out, &block.state[i], bytes);
      },
      material_);
}

void ExplicitSolver::read_particle(std::size_t i, const double* in) {
  for (const EvolvingField& f : kEvolvingFields) {
    std::vector<double>& field = p_.*f.field;
    const std::size_t w = field.size() / p_.n;
    std::copy(in, in + w, field.data() + w * i);
    in += w;
  }
  std::visit([&](auto& block) { std::memcpy(static_cast<void*>(&block.state[i]), in, state_bytes_per_particle(block)); },
             material_);
  for (int d = 0; d < 3; ++d) {
    st_.f_ext_old[3 * i + d] = p_.f_ext[3 * i + d];
    st_.f_contact_old[3 * i + d] = p_.f_contact[3 * i + d];
  }
}

void ExplicitSolver::drop_shape_cache() {
  shapes_ = empty_shape_cache();
  shapes_at_x_ = false;
}

}  // namespace uhpc::macro
