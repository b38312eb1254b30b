// A one-dimensional spall (plate impact in uniaxial strain) in the explicit solver, for the AFC law's
// tensile_rate option (docs/physics.md section 4.4): the spall strength with and without the fib Model
// Code 2010 tensile DIF, measured two ways, against the DIF at the measured strain rate and against what
// the law itself gives at a single point in the same stress state. docs/studies/2026-12-06-spall.md has
// the figures and what they mean.
//
// Set-up. One bar along x: a flyer [0, L_f] moving towards a target [L_f, 3 L_f] at rest (L_t = 2 L_f, the
// classic proportion), one body, so the interface is bonded; it only ever carries compression before the
// spall. The flyer's initial velocity is v0 (1 - x / L_f)^2: 0 at the interface, v0 at its free rear end.
// Why this shape and not a flyer at a uniform v0:
//   - a uniform flyer sends a rectangular pulse; its release and the tension reflected at the target's
//     rear meet as a jump, so the strain rate at the spall plane is set by the particle spacing (infinite
//     in theory) and the DIF would be a property of the mesh;
//   - a bonded flyer with a free rear end always sends a pulse symmetric about its peak (the right-going
//     half of its velocity field, then the left-going half reflected at its rear). With v falling towards
//     the interface the flyer is never in tension. Linear v (a triangular pulse) loads a whole band of
//     the target to the same tension at the same time (reflected rise and incident fall cancel in x), so
//     no plane is first and the band yields as a whole; the parabola makes the pulse's flanks convex, and
//     then, in linear acoustics, the tension is largest where the reflected peak is: the first plane to
//     reach a strength sigma_s = beta sigma0 is unique, at x_s = L_f (1 - sqrt(1 - beta)) / 2 from the rear
//     free surface, with the reflected peak on it (so the classic pullback formula applies), every plane
//     nearer the free surface stays below sigma_s, and each plane is loaded in tension at a constant rate,
//     at x_s edot = 2 v0 (1 - x_s / L_f) / L_f (sigma0 = rho c v0 / 2 the pulse's peak).
//   The discrete pulse is rounded at its peak over a few spacings, so the spall plane lies deeper than x_s
//   and the rate there is below the design rate (100 1/s): both are measured, not assumed.
// One dimension: uniaxial strain, as in a plate impact. The AFC Poisson ratio is 0.17, so a free narrow bar
// would be in uniaxial stress (and a different point of eq. 35); every lateral column of particles is held
// between two frictionless penalty walls (a single wall only pushes, and the lateral stress of uniaxial
// strain is tensile in the spall phase), so lateral displacements stay a few 1e-8 m (checked) and the
// cross-section (3 x 3 particles) is a slice of an infinite plate.
// h = 3 mm, the paper's centre spacing (the SDEL's lambda = h / l_mac); the shipped Table 6 constants and
// the paper's SDEL with the shipped options; only tensile_rate (and, in the second test,
// principal_stress_limit) is changed.
//
// Measured:
//   (a) the largest axial stress sigma_xx reached at the spall plane (the first layer whose damage reaches
//       0.99; layer means of the particles' stress);
//   (b) the rear free surface's pullback: sigma = rho0 c_L (u_max - u_min) / 2, the acoustic approximation
//       with c_L = sqrt((K_e + 4G/3) / rho0) = 4274 m/s, the longitudinal (uniaxial-strain) wave speed at
//       rest: the impedance of the elastic material between the spall plane and the free surface. Printed,
//       not asserted: without the DIF it is within 4 % of (a) at h = 3 mm but 10-22 % off at 1.5 mm (the
//       spall zone is a few layers wide and softens over a finite time, and the rounded discrete pulse puts
//       the first failing plane deeper than the reflected peak, the acoustic formula's assumptions); with
//       the DIF the material between the spall plane and the free surface itself yields (the DIF follows the
//       step's rate, and each point's tension peaks as its rate falls), so the pullback reads that material
//       (printed: how many of those layers yielded, and at what stress);
//   the strain rate at the spall plane when it fails: its layer's dv_x/dx at the step of its peak, and the
//       DIF the law held there (the same rate as the law sees it).
// Compared with: DIF(edot) Tmax (afc_tensile_dif at the measured rate), and the law's own spall strength in
// uniaxial strain at that rate (a PointDriver path at constant rate; the closed form is printed).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "bodies/generators.hpp"
#include "materials/afc.hpp"
#include "materials/afc_config.hpp"
#include "materials/afc_strength.hpp"
#include "materials/point_driver.hpp"
#include "solver/explicit_solver.hpp"

namespace uhpc::macro {
namespace {

constexpr double MPa = 1e6;
constexpr double kH = 0.003;          // particle spacing (the paper's centre spacing)
constexpr int kSide = 3;              // particles across the bar in y and in z
constexpr double kDesignRate = 100.0; // 1/s: UHPC's measured tensile DIF is 2-4 about here
constexpr double kFailed = 0.99;      // d+ of a failed layer

AfcParams shipped() { return load_afc_params(UHPC_DATA_DIR "/afc_uhpc.json", UHPC_DATA_DIR "/sdel_paper.json"); }

double bulk_modulus(const AfcParams& p) { return p.C6_Pa / p.C7; }  // K_e
double longitudinal_modulus(const AfcParams& p) { return bulk_modulus(p) + 4.0 / 3.0 * p.shear_modulus_Pa; }
double longitudinal_speed(const AfcParams& p) { return std::sqrt(longitudinal_modulus(p) / p.density_kg_m3); }

// The law's spall strength in uniaxial strain at a constant strain rate: the largest sigma_xx of a single
// point stretched along x at that rate (lateral strains zero), with d+ at that peak.
struct PointPeak {
  double stress, d_plus;
};
PointPeak uniaxial_strain_peak(const AfcParams& p, double rate) {
  PointDriver<AfcMaterial> pt(AfcMaterial(p), kH);
  const double de = 1e-7, dt = de / rate;
  PointPeak best{0.0, 0.0};
  for (int i = 0; i < 30000; ++i) {
    Mat3 d = Mat3::Zero();
    d(0, 0) = de;
    pt.strain_step(d, dt);
    if (pt.state().stress(0, 0) > best.stress) best = {pt.state().stress(0, 0), pt.state().d_plus};
  }
  return best;
}

// The same peak in closed form (for the explanation, not for the checks): on the elastic uniaxial-strain
// path P = -K e and q = 2 G e, so eq. 35, q = F a (T + P) / T with a = C1 - C2 and T = DIF Tmax (1 - d+),
// is met at e = F a / (2G + F a K / T), where sigma_xx = (K + 4G/3) e. F is AFC's deviatoric rate factor
// at the deviatoric rate 2/3 edot of uniaxial strain.
double eq35_uniaxial_strain_strength(const AfcParams& p, double rate, double d_plus) {
  const double K = bulk_modulus(p), G = p.shear_modulus_Pa;
  const double Fa = afc_rate_factor(2.0 / 3.0 * rate, p) * (p.C1_Pa - p.C2_Pa);
  const double T = afc_tensile_dif(rate, p) * p.Tmax_Pa * (1.0 - d_plus);
  return longitudinal_modulus(p) * Fa / (2.0 * G + Fa * K / T);
}

struct Spall {
  // the design
  double flyer_length = 0, v0 = 0, sigma0 = 0;
  // the spall plane: the first target layer whose mean d+ reaches kFailed (-1: none)
  int layer = -1;
  double depth = 0;          // its distance from the rear free surface
  double peak_axial = 0;     // (a)
  double rate = 0;           // its dv_x/dx at the step of its peak
  double law_dif = 0;        // the DIF the law held there at that step
  double max_tension = 0;    // its largest tensile pressure -P
  double pullback = 0, u_max = 0, u_min = 0;  // (b) and the free-surface velocities it is made of
  // the layers between the spall zone (every failed layer) and the free surface: how many yielded (plastic
  // strain > 1e-5, 4 % of the elastic strain at the static peak) and the lowest peak sigma_xx among those
  int path_layers = 0, path_yielded = 0;
  double path_weakest = 0;
  double lateral_strain = 0;  // largest |lateral displacement| / h of any particle over the run
};

// Runs the plate impact for a pulse of peak sigma0 = expected / beta.
Spall plate_impact(const AfcParams& p, double expected, double beta) {
  const double rho = p.density_kg_m3, c = longitudinal_speed(p);
  Spall r;
  r.sigma0 = expected / beta;
  const double xs = 0.5 * (1.0 - std::sqrt(1.0 - beta));  // x_s / L_f
  const double v0 = 2.0 * r.sigma0 / (rho * c);
  const int nf = static_cast<int>(std::lround(2.0 * (1.0 - xs) * v0 / kDesignRate / kH));
  r.flyer_length = nf * kH;
  r.v0 = kDesignRate * r.flyer_length / (2.0 * (1.0 - xs));  // the design rate exactly, on whole layers
  r.sigma0 = 0.5 * rho * c * r.v0;
  const int nl = 3 * nf;

  const ParticleBody body = box_body(nl * kH, kSide * kH, kSide * kH, kH);
  SolverOptions options;
  // The walls' penalty springs (25 rho c^2 h, angular frequency 5 c / h) are not in the solver's critical
  // step: CFL 0.1 keeps omega dt near 0.5 (the central difference needs < 2).
  options.cfl = 0.1;
  ExplicitSolver solver(Particles::from_body(body, rho, options.support_factor),
                        make_material_set(AfcMaterial(p), body.size()), options);
  Particles& P = solver.particles();
  const double lf = r.flyer_length, vr = r.v0;
  set_initial_velocity(P, [lf, vr](const double* x) -> Vec3 {
    const double s = x[0] < lf ? 1.0 - x[0] / lf : 0.0;
    return {vr * s * s, 0.0, 0.0};
  });
  std::vector<int> layer(P.n);
  std::vector<double> y0(P.n), z0(P.n);
  for (std::size_t i = 0; i < P.n; ++i) {
    layer[i] = static_cast<int>(std::floor(P.x[3 * i] / kH));
    y0[i] = P.x[3 * i + 1];
    z0[i] = P.x[3 * i + 2];
  }
  for (int d = 1; d <= 2; ++d)
    for (int k = 0; k < kSide; ++k) {
      Wall w;
      for (std::size_t i = 0; i < P.n; ++i)
        if (static_cast<int>(std::floor(P.x[3 * i + d] / kH)) == k) w.particles.push_back(static_cast<std::int32_t>(i));
      w.penalty_scale = 25.0;
      // Planes half a spacing either side of the column's centre: each particle just touches both at rest
      // (zero force) and is pushed back whichever way it moves.
      for (const double side : {-1.0, 1.0}) {
        w.point = {0, 0, 0};
        w.point[d] = (k + 0.5 + 0.5 * side) * kH;
        w.normal = {0, 0, 0};
        w.normal[d] = -side;  // the solid lies beyond the plane
        solver.add_wall(w);
      }
    }
  solver.initialize();
  const auto& law = std::get<MaterialBlock<AfcMaterial>>(solver.material());

  std::vector<double> sxx(nl), vx(nl), dp(nl), lxx(nl), tension(nl), dif(nl);
  std::vector<double> peak(nl, 0.0), rate_at_peak(nl, 0.0), dif_at_peak(nl, 0.0), max_tension(nl, 0.0);
  std::vector<double> fail_time(nl, -1.0);
  double u_max = 0.0, u_min = 0.0;
  bool past_peak = false, pulled_back = false;
  // The pulse reaches the rear at 2 L_f / c; the spall is expected about L_f / c later and its signal at the
  // free surface 2 x_s / c after that: 5 L_f / c is ample. The run stops once the pullback is recorded.
  const double t_end = 5.0 * lf / c;
  const double m = kSide * kSide;
  while (solver.time() < t_end && !pulled_back) {
    if (!solver.step()) {
      ADD_FAILURE() << "step failed at t = " << solver.time();
      break;
    }
    std::fill(sxx.begin(), sxx.end(), 0.0);
    std::fill(vx.begin(), vx.end(), 0.0);
    std::fill(dp.begin(), dp.end(), 0.0);
    std::fill(lxx.begin(), lxx.end(), 0.0);
    std::fill(tension.begin(), tension.end(), 0.0);
    std::fill(dif.begin(), dif.end(), 0.0);
    for (std::size_t i = 0; i < P.n; ++i) {
      const int k = layer[i];
      const double* s = P.stress.data() + 9 * i;
      sxx[k] += s[0] / m;
      tension[k] += (s[0] + s[4] + s[8]) / 3.0 / m;
      vx[k] += P.v[3 * i] / m;
      lxx[k] += P.vel_grad[9 * i] / m;
      dp[k] += law.state[i].d_plus / m;
      dif[k] += law.state[i].tensile_dif / m;
      r.lateral_strain = std::max({r.lateral_strain, std::fabs(P.x[3 * i + 1] - y0[i]) / kH,
                                   std::fabs(P.x[3 * i + 2] - z0[i]) / kH});
    }
    for (int k = nf; k < nl; ++k) {
      if (sxx[k] > peak[k]) {
        peak[k] = sxx[k];
        rate_at_peak[k] = lxx[k];
        dif_at_peak[k] = dif[k];
      }
      max_tension[k] = std::max(max_tension[k], tension[k]);
      if (fail_time[k] < 0.0 && dp[k] >= kFailed) fail_time[k] = solver.time();
    }
    // The rear free surface's velocity: its peak, then the first minimum after it that the velocity rises
    // from again (by 2 % of the peak: the spall signal, not the ripple of the discrete wave).
    const double u = vx[nl - 1];
    if (!past_peak) {
      if (u > u_max) u_max = u;
      else if (u_max > 0.25 * r.v0 && u < 0.98 * u_max) past_peak = true, u_min = u;
    } else {
      u_min = std::min(u_min, u);
      if (u > u_min + 0.02 * u_max) pulled_back = true;
    }
  }
  EXPECT_TRUE(pulled_back) << "no pullback of the free-surface velocity before " << t_end << " s";
  r.u_max = u_max;
  r.u_min = u_min;
  r.pullback = 0.5 * rho * c * (u_max - u_min);

  double first = HUGE_VAL;
  int shallowest_failed = -1;  // the failed layer nearest the free surface
  for (int k = nf; k < nl; ++k)
    if (fail_time[k] >= 0.0) {
      if (fail_time[k] < first) first = fail_time[k], r.layer = k;
      shallowest_failed = k;
    }
  if (r.layer < 0) return r;
  r.depth = (nl - r.layer - 0.5) * kH;
  r.peak_axial = peak[r.layer];
  r.rate = rate_at_peak[r.layer];
  r.law_dif = dif_at_peak[r.layer];
  r.max_tension = max_tension[r.layer];
  std::vector<double> plastic(nl, 0.0);
  for (std::size_t i = 0; i < P.n; ++i) plastic[layer[i]] = std::max(plastic[layer[i]], law.state[i].plastic_strain);
  r.path_weakest = HUGE_VAL;
  for (int k = shallowest_failed + 1; k < nl; ++k) {
    ++r.path_layers;
    if (plastic[k] > 1e-5) ++r.path_yielded, r.path_weakest = std::min(r.path_weakest, peak[k]);
  }
  return r;
}

struct Measured {
  Spall spall;
  double dif = 0, dif_tmax = 0, point = 0, point_d_plus = 0, closed_form = 0;
};

// One spall run designed for the law's own peak at the design rate, and its comparisons at the measured rate.
Measured measure(const char* label, const AfcParams& p, double beta) {
  Measured m;
  m.spall = plate_impact(p, uniaxial_strain_peak(p, kDesignRate).stress, beta);
  const Spall& s = m.spall;
  std::printf("%s: flyer %.0f mm at v0 %.2f m/s (pulse peak %.2f MPa), target %.0f mm, design rate %.0f 1/s\n", label,
              1e3 * s.flyer_length, s.v0, s.sigma0 / MPa, 2e3 * s.flyer_length, kDesignRate);
  if (s.layer < 0) {
    ADD_FAILURE() << label << ": no layer of the target failed (no spall)";
    return m;
  }
  m.dif = afc_tensile_dif(s.rate, p);
  m.dif_tmax = m.dif * p.Tmax_Pa;
  const PointPeak pp = uniaxial_strain_peak(p, s.rate);
  m.point = pp.stress;
  m.point_d_plus = pp.d_plus;
  m.closed_form = eq35_uniaxial_strain_strength(p, s.rate, pp.d_plus);
  std::printf("  spall plane %.1f mm from the rear free surface (design %.1f mm); strain rate there at its peak %.1f 1/s, "
              "DIF(rate) %.3f, DIF the law held %.3f\n",
              1e3 * s.depth, 1e3 * 0.5 * (1.0 - std::sqrt(1.0 - beta)) * s.flyer_length, s.rate, m.dif, s.law_dif);
  std::printf("  (a) peak sigma_xx at the spall plane %.2f MPa; (b) pullback rho c (u_max - u_min) / 2 = %.2f MPa "
              "(u_max %.3f, u_min %.3f m/s, c = %.0f m/s): (b)/(a) %.3f\n",
              s.peak_axial / MPa, s.pullback / MPa, s.u_max, s.u_min, longitudinal_speed(p), s.pullback / s.peak_axial);
  std::printf("  DIF(rate) Tmax = %.2f MPa: (a)/(DIF Tmax) %.3f, (b)/(DIF Tmax) %.3f\n", m.dif_tmax / MPa,
              s.peak_axial / m.dif_tmax, s.pullback / m.dif_tmax);
  std::printf("  the law in uniaxial strain at %.1f 1/s: peak %.2f MPa (d+ %.4f there; eq. 35 on the elastic path: "
              "%.2f MPa): (a)/law %.3f, (b)/law %.3f\n",
              s.rate, m.point / MPa, m.point_d_plus, m.closed_form / MPa, s.peak_axial / m.point, s.pullback / m.point);
  std::printf("  largest tensile pressure at the spall plane %.2f MPa = %.3f DIF Tmax; %d of the %d layers between the "
              "spall zone and the free surface yielded (weakest peak %.2f MPa); lateral strain <= %.1e\n",
              s.max_tension / MPa, s.max_tension / m.dif_tmax, s.path_yielded, s.path_layers,
              s.path_yielded ? s.path_weakest / MPa : 0.0, s.lateral_strain);
  // The set-up is one-dimensional: lateral displacements over h below 5 % of the pulse's axial strain
  // sigma0 / M (a lateral strain that size would change sigma_xx by (K - 2G/3) / M x 5 % = 1 %).
  EXPECT_LT(s.lateral_strain, 0.05 * s.sigma0 / longitudinal_modulus(p)) << label;
  // A spall inside the target, not a peeling of the free surface: deeper than two layers.
  EXPECT_GT(s.depth, 2.0 * kH) << label;
  // The rate the measurement sees is the rate the law sees (same layer, same step); without the option
  // both DIFs are 1 and there is nothing to compare.
  if (p.options.tensile_rate != TensileRate::Off) {
    EXPECT_NEAR(s.law_dif / m.dif, 1.0, 0.05) << label;
  }
  return m;
}

// The paper's model (shipped options: eq. 35 with the cutoff coupling, no principal-stress limit).
// (a) must be the law's own uniaxial-strain spall strength at the measured rate within 5 %: eq. 35's
// deviatoric limit, not the cutoff, ends the elastic path (q / -P = 2G / K = 1.67 there), so the spall
// strength is not Tmax (1.76 Tmax), nor DIF Tmax with the option (about 1.55 DIF Tmax). That misses the
// goal "spall strength = DIF Tmax" for a reason of the law, so it is printed, not asserted; what eq. 35
// guarantees is asserted: the law's own peak, and a gain from the DIF above 1 and below DIF.
TEST(MacroSpall, PaperModelSpallStrengthIsEq35sLimitInUniaxialStrain) {
  AfcParams p = shipped();
  ASSERT_EQ(p.options.tensile_rate, TensileRate::Off);  // the shipped default
  const Measured off = measure("paper's model, tensile_rate off", p, 0.75);
  p.options.tensile_rate = TensileRate::FibModelCode2010;
  const Measured on = measure("paper's model, tensile_rate fib_model_code_2010", p, 0.75);
  ASSERT_GE(off.spall.layer, 0);
  ASSERT_GE(on.spall.layer, 0);

  EXPECT_NEAR(off.spall.peak_axial / off.point, 1.0, 0.05);
  EXPECT_NEAR(on.spall.peak_axial / on.point, 1.0, 0.05);
  // The DIF raises the spall strength, by less than DIF (the deviatoric limit is not rate-scaled).
  const double gain = on.spall.peak_axial / off.spall.peak_axial;
  std::printf("spall strength on / off: %.3f (DIF at the rate with the option %.3f)\n", gain, on.dif);
  EXPECT_GT(gain, 1.0);
  EXPECT_LT(gain, on.dif);
}

// principal_stress_limit = tmax: sigma_1 <= DIF Tmax (1 - d+), which in uniaxial strain binds before eq. 35
// (it caps sigma_xx at Tmax where eq. 35 would allow 12 MPa). Then the spall strength is DIF Tmax (1 - d+)
// with d+ 0.002 when the cap is reached: (a) must be DIF(edot) Tmax within 5 %, with and without the option
// (DIF 1): the goal, met with this option. A pulse of twice the strength (beta 0.5): past the cap the
// plane softens only through d+, which needs a few times the elastic strain.
TEST(MacroSpall, PrincipalStressLimitTmaxSpallsAtDifTimesTmax) {
  AfcParams p = shipped();
  p.options.principal_stress_limit = PrincipalStressLimit::Tmax;
  const Measured off = measure("principal_stress_limit tmax, tensile_rate off", p, 0.5);
  p.options.tensile_rate = TensileRate::FibModelCode2010;
  const Measured on = measure("principal_stress_limit tmax, tensile_rate fib_model_code_2010", p, 0.5);
  ASSERT_GE(off.spall.layer, 0);
  ASSERT_GE(on.spall.layer, 0);

  EXPECT_NEAR(off.spall.peak_axial / off.dif_tmax, 1.0, 0.05);
  EXPECT_NEAR(on.spall.peak_axial / on.dif_tmax, 1.0, 0.05);
  std::printf("spall strength on / off: %.3f (DIF at the rate with the option %.3f)\n",
              on.spall.peak_axial / off.spall.peak_axial, on.dif);
}

}  // namespace
}  // namespace uhpc::macro
