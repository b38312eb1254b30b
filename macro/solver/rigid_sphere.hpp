#pragma once
// The projectile: a free rigid sphere (mass, radius, position, velocity) in contact with the particles,
// frictionless by default (docs/physics.md section 5), Coulomb friction as an option.
//
// Each particle I has a contact radius r_I = contact_radius_factor * h_I (default h_I / 2: the
// particle's half spacing, so the body's surface and not its particle centres meets the sphere, as for
// the planar walls); it touches the sphere when d_I = |x_I - x_s| < R + r_I (the offset surface; the
// leading surface below). Every pair force is equal and opposite and, on the offset surface, central
// (along the line of centres n_I = (x_I - x_s) / d_I), so the contact conserves linear momentum exactly
// (to round-off) and exerts no torque on the sphere, whose spin is not tracked.
//
// Normal contact, two models (SphereContactModel):
// - Kinematic (default): inelastic in the normal direction, as the paper's kernel contact through the
//   bodies' velocity fields is (a struck particle moves on with the sphere; it is not thrown ahead).
//   The forces are the smallest that keep every particle out of the sphere at the next configuration
//   (predictor-corrector contact, after Taylor and Flanagan's PRONTO). The forces of this evaluation
//   act over the second half kick of the step dt just taken and the first half kick of the next step
//   dt' (known here: the material's and the travel limit's stable step), so without contact forces the
//   particles and the sphere would reach, after the next drift,
//     x_I* = x_I + dt' v_I + k a_I,   x_s* = x_s + dt' v_s,   k = dt' (dt + dt') / 2
//   (v the mid-step velocities, a_I the internal and wall forces only), with the gaps
//   g_I* = |x_I* - x_s*| - (R + r_I). The normal forces F_I >= 0 (on I along n_I, on the sphere
//   -F_I n_I) change the gaps by k (F_I / m_I + n_I . S / M), S = sum_J F_J n_J, and are the solution
//   of the complementarity problem g_I >= 0, F_I >= 0, F_I g_I = 0: on the active set (the particles
//   that would penetrate) F_I = m_I (-g_I* / k - n_I . S / M), which makes S the solution of one 3x3
//   system (I + sum m_I n_I n_I^T / M) S = sum m_I n_I (-g_I* / k); particles
//   with F_I < 0 leave the set, particles the corrected sphere still meets join it, until it settles.
//   A particle then ends the step on the sphere's surface with the sphere's normal velocity
//   (restitution 0): never faster than the sphere allows. An overlap already there (left by a change
//   of the step, since the prediction assumes the next step equals this one) is held, not pushed out. The contact stores no energy; the work of
//   its forces (the ledger's contact account) is what the inelastic impacts dissipate. It sets no
//   stable step of its own beyond the travel limit below.
// - Penalty (option, the earlier model): f_I = k_I delta_I n_I, delta_I = R + r_I - d_I > 0, with
//   k_I = penalty_scale rho0 c0^2 h_I (a cube of the undeformed material of side h_I) FIXED per particle
//   at initialize(): the gradient of the potential sum 1/2 k_I delta_I^2, elastic (restitution 1 for a
//   free particle: it leaves at up to twice the sphere's speed). Stable step 2 sqrt(m_I / k_I) per
//   particle in contact and 2 sqrt(M / sum k_I) for the sphere.
// Friction (option, friction_coefficient mu > 0; 0 by default). On top of the normal force F_I, each
// pair gets a Coulomb force against the tangential part w_t of the relative velocity w = v_I - v_s (at
// the mid-step, where the forces are evaluated):
//     f_t = -min(mu F_I, m_I |w_t| / dt) w_t / |w_t|  on the particle,  -f_t on the sphere.
// The cap m_I |w_t| / dt is sticking: the force never does more than stop the relative sliding within
// one step. Its work, f_t . w dt <= 0, is dissipated and lands in the contact energy of the ledger. The
// torque on the sphere is not applied: zero by symmetry for a normal impact on the axis.
// Both models also limit the step so that the sphere cannot pass through a particle's contact radius
// between two steps: the time it takes to travel the smallest contact radius, min r_I / |v_s| (h_I / 4 for r_I = 0).
// The contact surface (ContactSurface). With the offset surface (default) a particle touches at
// d_I = R + r_I all around: the sphere sweeps, per unit of its travel, the particles whose centres lie
// within R + r_I of its line, a mass rho0 pi (R + r_I)^2, which converges to the sphere's own
// rho0 pi R^2 as h -> 0 for any factor, and equals it at every spacing for factor 0 (the particles'
// centres meet the sphere's surface; kinematic model only), whose front then enters each particle's
// volume by h_I / 2 before it touches. The leading surface (kinematic model only) has both: a particle
// touches the union of the sphere and the sphere advanced by r_I along the flight direction e at impact
// (SphereContactOptions::leading_direction), so the body's surface meets the sphere's front (R + r_I on
// the flight line) while the union's section across the flight line, and so the swept mass while the
// sphere flies along e, is the sphere's own pi R^2 at every spacing. Its gap is the distance to the
// nearer of the two spheres, min(|x_I - x_s|, |x_I - x_s - r_I e|) - R, and the force acts along that
// distance's gradient (from the advanced sphere's centre on the front cap): normal to the surface, so a
// particle that slides on it exchanges no work with the contact. Central forces on this surface would
// (a sliding particle's radius changes with its direction: a friction of +-r_I / R that gives energy
// back towards the pole; measured on the elastic block's rebound, 0.9 J given back of 5.1 J). The forces
// are equal and opposite, so momentum is conserved; the torque of the front cap's forces about the
// sphere's centre (their lines pass through the advanced centre, on the flight line) is dropped with the
// spin, as friction's is, and vanishes by symmetry for a normal impact on the axis. e is the flight
// direction at impact and not the current velocity: the face that struck keeps its reach when the
// sphere stops or rebounds (with the velocity the reach of the struck face would drop by r_I at the
// turn, and the target's surface would strike it again: tried, the elastic block's rebound then lost
// most of its energy). The active-set solve below is the offset surface's with these gaps and normals.
#include <cstdint>
#include <vector>

#include "solver/conditions.hpp"
#include "solver/particles.hpp"
#include "solver/rank_share.hpp"

namespace uhpc::macro {

enum class SphereContactModel : std::uint8_t { Kinematic, Penalty };

// [choice] Where a particle touches the sphere (header). Offset (default): at R + r_I in every direction.
// Leading (kinematic model only): the sphere and the sphere advanced by r_I along the flight direction.
enum class ContactSurface : std::uint8_t { Offset, Leading };

struct SphereContactOptions {
  SphereContactModel model = SphereContactModel::Kinematic;
  double penalty_scale = 1.0;          // Penalty: k_I = penalty_scale * rho0 c0^2 h_I
  double contact_radius_factor = 0.5;  // r_I = contact_radius_factor * h_I (>= 0; > 0 for the penalty)
  double friction_coefficient = 0.0;   // Coulomb mu (0: frictionless)
  ContactSurface surface = ContactSurface::Offset;
  Vec3 leading_direction{0.0, 0.0, 1.0};  // Leading: the unit flight direction at impact
};

// The distance that sets the travel limit and the candidates' margin for a particle of spacing h: its
// contact radius factor x h, or h / 4 when that is 0.
double contact_reach(const SphereContactOptions& contact, double spacing);

// The gap of a particle of contact radius r_I at `rel` = x_I - x_s from a sphere of radius R (negative:
// overlapping) and the unit normal along which the contact pushes it (header: the offset and the
// leading surface). Allocation-free.
double contact_gap(const SphereContactOptions& contact, double R, double r_I, const double* rel, double* normal);

struct RigidSphere {
  double mass_kg = 0.0;
  double radius_m = 0.0;
  Vec3 x{};       // centre, m
  Vec3 v{};       // velocity, m/s
  Vec3 x_prev{};  // centre at the start of the step
  Vec3 force{};   // contact force on the sphere (minus the sum of the forces on the particles), N
  SphereContactOptions contact;

  // Throws std::invalid_argument unless mass, radius, penalty scale and contact radius factor are > 0,
  // the friction coefficient is >= 0 and the state is finite.
  void validate() const;
  double kinetic_energy() const { return 0.5 * mass_kg * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }
};

// What one contact evaluation found.
struct SphereContactSums {
  Vec3 force_on_sphere{};            // N
  double stored_energy = 0.0;        // sum 1/2 k_I delta_I^2 (penalty), J; 0 for the kinematic contact
  double critical_step = 0.0;        // s (infinity when nothing limits it)
  std::int64_t particles_in_contact = 0;  // pairs with a force
};

class SphereContact {
 public:
  // Fixes the penalty stiffness from the reference density and the reference state's wave speeds
  // (wave_speed, one a particle), and the smallest contact radius; sizes the scratch (no allocation in
  // the steps after).
  // share (a distributed run's rank, rank_share.hpp): the owned particles count; the kinematic
  // contact's active set is solved over every rank's candidates, and the penalty's sums are made over
  // every rank's pairs, gathered in the order of their ids, so that each rank finds the one-process
  // forces and the same force on the sphere.
  void initialize(const RigidSphere& sphere, const Particles& p, const double* wave_speed,
                  const RankShare* share = nullptr);
  // The contact force of every particle into f_contact (3n; zero where there is none), with the
  // particles' internal and external forces already in p.f_int and p.f_ext (the kinematic model
  // predicts the motion they cause). The forces act over the second half kick of the step dt that
  // produced this configuration (0 at the start: there is none) and the first half kick of the next
  // step dt_next, after which the particles drift by dt_next times their velocity.
  SphereContactSums compute(const RigidSphere& sphere, const Particles& p, double dt, double dt_next,
                            double* f_contact, const RankShare* share = nullptr);
  // The time the sphere takes to travel the smallest contact radius (a bound of the step).
  double travel_limit(const RigidSphere& sphere) const;

 private:
  SphereContactSums penalty(const RigidSphere& sphere, const Particles& p, double dt, double* f_contact,
                            const RankShare* share);
  SphereContactSums kinematic(const RigidSphere& sphere, const Particles& p, double dt, double dt_next,
                              double* f_contact, const RankShare* share);
  // The candidates of every rank in the order of their global ids (a distributed run).
  void gather_candidates(const RankShare& share);
  // Adds the Coulomb force of a pair of particle velocity v and mass m with normal force `normal_force`
  // along the unit normal n.
  static void add_friction(const RigidSphere& s, const double* v, double m, const double* n, double normal_force,
                           double dt, double* f);

  std::vector<double> k_;                // penalty stiffness per particle
  double min_travel_distance_ = 0.0;
  std::vector<unsigned char> flagged_;   // kinematic: would penetrate without contact forces
  std::vector<std::int32_t> candidates_;
  std::vector<double> gap_, normal_, force_;  // per candidate (normal: 3 each)
  std::vector<double> mass_, velocity_;       // per candidate (velocity: 3 each)
  std::vector<unsigned char> active_;
  // Distributed: per candidate, the particle's index here when it is owned here (-1 otherwise); and
  // the records the ranks exchange (the kinematic contact's candidates, the penalty's pairs).
  std::vector<std::int64_t> local_;
  std::vector<double> mine_, all_;
  std::vector<std::size_t> order_;
};

}  // namespace uhpc::macro
