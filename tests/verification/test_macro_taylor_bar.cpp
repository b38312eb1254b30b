// Taylor bar impact (solver core, J2 plasticity, rigid planar wall, disc_body as a bar): the copper
// cylinder that verifies explicit codes under large plastic flow. L0 = 32.4 mm, R0 = 3.2 mm, 227 m/s
// onto a rigid frictionless wall; rho 8930 kg/m3, E 117 GPa, nu 0.35, yield 400 MPa, tangent modulus
// E_t = 100 MPa (J2Params takes the plastic modulus: H = E E_t / (E - E_t)); 80 us, the bar at rest.
// Reference (FE, the benchmark usually attributed to Kamoulakos 1990): final length 21.42 - 21.48 mm,
// footprint radius 7.11 - 7.22 mm, plastic strain about 3 at the impact face (geometry: ANSYS MAPDL
// Technology Showcase example 17; results with these constants: the Taylor benchmark of Carina.jl,
// benchmark/tet15-p1/taylor/README.md, quoting Simo 1992, Zienkiewicz et al. 1998, Foulk et al. 2021).
// Used: 21.45 mm and 7.1 mm.
// Measures at 80 us: length = highest particle z + half an axial layer (the wall holds the face's
// centres h/2 off its plane); footprint = largest radius of the first layer's particles + h/2 (reads low
// by up to h/2 where the mushroom's edge is stretched 2x); largest plastic strain; worst energy balance.
// Support 3.0 h, not the default 2.0 h: the support is fixed in time and the mushroom stretches the
// material 2.2x radially. At 2.0 h the axis particles next to the wall go unstable at 7 - 12 us
// (also at CFL 0.2 and h = 0.5 mm); at 2.5 h the mushroom's edge does at 26 - 37 us at most spacings.
// At 3.0 h every spacing from 1.07 to 0.4 mm runs, and length and footprint converge toward the
// reference (macro/README.md, verification): at the test's h = 0.8 mm the length is within 3 % but the
// footprint is -7.6 % (inside 7 % from h = 0.6 mm), so the footprint is asserted by physics and
// convergence. By hand: UHPC_TAYLOR_SPACING_MM=0.5 build/tests/verification_test_macro_taylor_bar
// --gtest_also_run_disabled_tests --gtest_filter='*FinerSpacing*'.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include <gtest/gtest.h>

#include "bodies/generators.hpp"
#include "solver/explicit_solver.hpp"

namespace uhpc::macro {
namespace {

constexpr double kL0 = 32.4e-3, kR0 = 3.2e-3, kV0 = 227.0, kEndTime = 80e-6;
constexpr double kRho = 8930.0, kE = 117e9, kNu = 0.35, kYield = 400e6, kTangent = 100e6;
constexpr double kHardening = kE * kTangent / (kE - kTangent);  // plastic modulus, 100.09 MPa
constexpr double kLengthRef = 21.45e-3, kFootprintRef = 7.1e-3;
constexpr double kSupportFactor = 3.0;  // see the header: 2.0 and 2.5 go unstable

struct TaylorResult {
  double h = 0, layer = 0;
  std::size_t particles = 0;
  std::int64_t steps = 0;
  double wall_s = 0;
  double length0 = 0, footprint0 = 0;  // the measures on the initial state
  double length = 0, footprint = 0, max_plastic_strain = 0;
  double worst_balance = 0, kinetic_left = 0, plastic_work = 0, axial_velocity = 0;
  bool completed = false;
};

// Length (max z + dz/2, the wall at z = 0) and footprint (largest radius in the first layer + h/2).
void measure(const Particles& p, const std::vector<std::size_t>& first_layer, double h, double layer, double& length,
             double& footprint) {
  double z_max = -1.0, r_max = 0.0;
  for (std::size_t i = 0; i < p.n; ++i) z_max = std::max(z_max, p.x[3 * i + 2]);
  for (std::size_t i : first_layer) r_max = std::max(r_max, std::hypot(p.x[3 * i], p.x[3 * i + 1]));
  length = z_max + 0.5 * layer;
  footprint = r_max + 0.5 * h;
}

TaylorResult taylor(double h) {
  const auto t_start = std::chrono::steady_clock::now();
  DiscSpec spec;
  spec.radius_m = kR0;
  spec.thickness_m = kL0;
  spec.h_axis_m = h;
  spec.h_rim_m = h;
  ParticleBody body = disc_body(spec);
  // The wall touches a particle at h_I/2 from its centre: lift the bar to 0.01 h from contact.
  double gap = 1.0;
  for (std::size_t i = 0; i < body.size(); ++i) gap = std::min(gap, body.position[3 * i + 2] - 0.5 * body.spacing[i]);
  for (std::size_t i = 0; i < body.size(); ++i) body.position[3 * i + 2] += 0.01 * h - gap;
  int n_axis = 0;
  double z_min = 1.0;
  for (std::size_t i = 0; i < body.size(); ++i) {
    if (body.position[3 * i] == 0.0 && body.position[3 * i + 1] == 0.0) ++n_axis;
    z_min = std::min(z_min, body.position[3 * i + 2]);
  }
  const double layer = kL0 / n_axis;
  std::vector<std::size_t> first_layer;
  for (std::size_t i = 0; i < body.size(); ++i)
    if (body.position[3 * i + 2] < z_min + 0.5 * layer) first_layer.push_back(i);

  J2Params jp;
  jp.density_kg_m3 = kRho;
  jp.bulk_modulus_Pa = kE / (3.0 * (1.0 - 2.0 * kNu));
  jp.shear_modulus_Pa = kE / (2.0 * (1.0 + kNu));
  jp.yield_stress_Pa = kYield;
  jp.hardening_modulus_Pa = kHardening;
  SolverOptions options;
  options.support_factor = kSupportFactor;
  ExplicitSolver solver(Particles::from_body(body, kRho, options.support_factor),
                        make_material_set(J2Material(jp), body.size()), options);
  set_initial_velocity(solver.particles(), Region{{-1, -1, -1}, {1, 1, 1}}, {0, 0, -kV0});
  Wall wall;
  wall.point = {0, 0, 0};
  wall.normal = {0, 0, 1};
  solver.add_wall(wall);
  solver.initialize();

  TaylorResult r;
  r.h = h;
  r.layer = layer;
  r.particles = body.size();
  measure(solver.particles(), first_layer, h, layer, r.length0, r.footprint0);
  double worst = 0.0;
  r.completed = true;
  while (solver.time() < kEndTime) {
    if (!solver.step()) {
      const FailureReport& f = solver.failure();
      ADD_FAILURE() << "h = " << h << ": step " << f.step << " failed at " << f.time_s << " s (" << to_string(f.kind)
                    << ", particle " << f.particle << ")";
      r.completed = false;
      break;
    }
    worst = std::max(worst, std::fabs(solver.ledger().balance_error()));
  }
  const Particles& p = solver.particles();
  measure(p, first_layer, h, layer, r.length, r.footprint);
  for (const auto& s : std::get<MaterialBlock<J2Material>>(solver.material()).state)
    r.max_plastic_strain = std::max(r.max_plastic_strain, s.plastic_strain);
  const EnergyLedger& e = solver.ledger();
  r.steps = solver.steps();
  r.worst_balance = worst / e.kinetic_initial;
  r.kinetic_left = e.kinetic / e.kinetic_initial;
  r.plastic_work = e.material_dissipated / e.kinetic_initial;
  double mass = 0.0;
  for (double m : p.mass) mass += m;
  r.axial_velocity = e.momentum[2] / mass;
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  return r;
}

void report(const TaylorResult& r) {
  std::printf(
      "Taylor bar, h = %.4f mm (axial layer %.4f mm): %zu particles, %lld steps, %.1f s wall%s\n"
      "  initial state: length %.4f mm, footprint %.4f mm\n"
      "  final length %.4f mm (%+.2f %% of %.2f), footprint %.4f mm (%+.2f %% of %.2f), max eps_p %.3f\n"
      "  worst energy balance error %.3e of the initial kinetic energy; kinetic left %.4f, plastic work %.4f; "
      "mean axial velocity %+.2f m/s\n",
      1e3 * r.h, 1e3 * r.layer, r.particles, static_cast<long long>(r.steps), r.wall_s,
      r.completed ? "" : " (FAILED before 80 us)", 1e3 * r.length0, 1e3 * r.footprint0, 1e3 * r.length,
      100.0 * (r.length / kLengthRef - 1.0), 1e3 * kLengthRef, 1e3 * r.footprint,
      100.0 * (r.footprint / kFootprintRef - 1.0), 1e3 * kFootprintRef, r.max_plastic_strain, r.worst_balance,
      r.kinetic_left, r.plastic_work, r.axial_velocity);
  std::fflush(stdout);
}

// One-dimensional Taylor estimate (Taylor 1948; Wilkins and Guinan 1973 with no elastic zone) of a
// rigid-perfectly-plastic bar of flow stress Y: L1 / L0 = exp(-rho U^2 / (2 Y)). Taylor's relation
// gives L1 / L0 >= that value for any length of the undeformed rear part, so with Y = the initial
// yield it bounds the length from below (no hardening: the shortest bar); with Y = the flow stress
// at the largest plastic strain of the converged solutions (about 3) it is the estimate for a bar
// flowing everywhere at the highest stress reached, the upper end of the bracket.
double taylor_length(double flow_stress) { return kL0 * std::exp(-kRho * kV0 * kV0 / (2.0 * flow_stress)); }

// What any sound run must satisfy, whatever the spacing.
void expect_physical(const TaylorResult& r) {
  ASSERT_TRUE(r.completed);
  // Energy: kinetic + internal (elastic + plastic) + viscous - wall work = initial kinetic.
  EXPECT_LT(r.worst_balance, 0.01);
  // At 80 us the bar has come to rest: the kinetic energy is gone, mostly into plastic work.
  EXPECT_LT(r.kinetic_left, 0.01);
  EXPECT_GT(r.plastic_work, 0.85);
  // Shorter than at the start, within the 1D Taylor bracket (18.23 - 23.32 mm).
  EXPECT_LT(r.length, kL0);
  EXPECT_GT(r.length, taylor_length(kYield));
  EXPECT_LT(r.length, taylor_length(kYield + 3.0 * kHardening));
  // A mushroom: the footprint is wider than the bar would be if it had shortened uniformly (volume
  // conserved), R0 sqrt(L0 / L).
  EXPECT_GT(r.footprint, kR0 * std::sqrt(kL0 / r.length));
  // The edge of the footprint has a hoop strain ln(R_f / R0); an isochoric flow with that hoop strain
  // has an equivalent plastic strain of at least as much.
  EXPECT_GT(r.max_plastic_strain, std::log(r.footprint / kR0));
}

// h = 0.8 mm (R0/4, 1840 particles) against the reference and physics; h = R0/3 (720 particles) for
// the convergence check. About 20 s on one busy core.
TEST(MacroTaylorBar, CopperBarAt227MetresPerSecond) {
  const TaylorResult coarse = taylor(kR0 / 3.0), fine = taylor(0.8e-3);
  report(coarse);
  report(fine);
  expect_physical(coarse);
  expect_physical(fine);
  // The measures are calibrated on the initial state.
  EXPECT_NEAR(fine.length0 / kL0, 1.0, 2e-3);
  EXPECT_NEAR(fine.footprint0 / kR0, 1.0, 1e-2);
  // Against the FE reference: the length within 3 %. The footprint (-7.6 %) misses the 7 % band at
  // this spacing (it is within it from h = 0.6 mm, header); what is asserted is that it converges.
  EXPECT_NEAR(fine.length / kLengthRef, 1.0, 0.03);
  EXPECT_LT(std::fabs(fine.length / kLengthRef - 1.0), 0.9 * std::fabs(coarse.length / kLengthRef - 1.0));
  EXPECT_LT(std::fabs(fine.footprint / kFootprintRef - 1.0),
            0.9 * std::fabs(coarse.footprint / kFootprintRef - 1.0));
  EXPECT_GT(fine.max_plastic_strain, coarse.max_plastic_strain);
}

// By hand (minutes): UHPC_TAYLOR_SPACING_MM (default 0.5) against the reference bands themselves.
TEST(MacroTaylorBar, DISABLED_FinerSpacing) {
  const char* env = std::getenv("UHPC_TAYLOR_SPACING_MM");
  const TaylorResult r = taylor(env ? 1e-3 * std::atof(env) : 0.5e-3);
  report(r);
  expect_physical(r);
  EXPECT_NEAR(r.length / kLengthRef, 1.0, 0.03);
  EXPECT_NEAR(r.footprint / kFootprintRef, 1.0, 0.07);
}

}  // namespace
}  // namespace uhpc::macro
