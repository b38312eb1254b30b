// The energy a crack dissipates per unit area in the 3D solver, against the particle spacing
// (docs/studies/2026-12-06-crack-band.md): a square bar of the shipped AFC material pulled apart, with the
// paper's SDEL (sdel_regularization lambda, the default) and with the crack band option.
//
// The bar: 90 mm long (a whole number of layers at every spacing: 60 / 40 / 30 / 20 / 15), 4 x 4
// particles across (side 4 h), the shipped solver settings (support 2.5 h, NSNI, endpoint-average
// strain, lazy rows 3e-4, bulk viscosity, stress-free points undamped). Loading: every particle starts in
// the uniform uniaxial-stress motion of the elastic bar, v = (edot (x - L/2), -nu edot (y - y_c),
// -nu edot (z - z_c)), and the three end layers at each end (more than the support, 2.5 h, so that no free
// particle's support is cut by an end face) are held in it. A uniform stress has no divergence, so until
// the material leaves the elastic range this motion is the exact solution, with no wave: quasi-static
// whatever the rate. Checked: the kinetic energy of the departure from the imposed motion stays below
// 1e-2 of the stored energy up to the peak. edot = 0.5 1/s brings the bar to its peak after about 25
// transits of the dilatational wave (L / c = 21 us).
//
// Where the crack goes: the middle layer is seeded weaker. Its peak in uniaxial tension is put 5 % below
// the bar's by an initial tensile damage d0 (found on the seeded point itself); with the crack band the
// layer also starts with the tensile work that d0 stands for on the reference curve (a layer that has
// already dissipated that much), so the law's own path goes on from it. 5 % because the rest of the
// bar goes on loading while the middle layer's unloading wave travels out: edot (L / 2) / c = 5e-6 of
// strain, 2 % of the peak strain. Without a seed the bar cracks in several places near the held ends.
// Checked: when the seeded layer fails no layer but it and the two beside it has failed.
//
// Past the peak the bar snaps back: 90 mm is far longer than the material's characteristic length
// (E G / f_t^2 = 2-5 mm), so the elastic energy of the two halves (120-220 J/m^2 at the peak) is
// released faster than the band can take it, whatever the loading rate, and ends as their vibration (the
// kinetic energy is printed). No test that pulls a 90 mm bar of this material can be quasi-static past
// its peak. G is the material's dissipation (EnergyLedger::material_dissipated) per unit cross-section,
// when the seeded layer has failed (d+ >= 1 - 1e-6 at all its particles: the halves are apart) and one
// transit L / c later (the layers beside it, which the RK support of 2.5 h strains with it, have then
// failed too); per layer around the seeded one, with the ledger's viscous and stabilization parts.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "afc_point_tests.hpp"
#include "bodies/generators.hpp"
#include "materials/afc_strength.hpp"
#include "solver/explicit_solver.hpp"

namespace uhpc::macro {
namespace {

using afc_test::Driver;
using afc_test::shipped;

constexpr double kLength = 0.09;      // m
constexpr double kStrainRate = 0.5;   // 1/s
constexpr double kSeedMargin = 0.05;  // the seeded layer's strength below the bar's peak
constexpr int kGripLayers = 3;        // held layers at each end
constexpr double kFailed = 1.0 - 1e-6;

// The law of a run: the regularization and, for the crack band, the band's width in spacings.
struct Law {
  SdelRegularization reg = SdelRegularization::Lambda;
  double width = 1.0;             // AfcOptions::crack_band_width_spacings
  bool reduce_strength = false;   // AfcOptions::crack_band_strength_reduction
};
std::string name(const Law& l) {
  if (l.reg == SdelRegularization::Lambda) return "lambda";
  return (l.width == 1.0 ? "crack_band" : "crack_band x" + std::to_string(static_cast<int>(l.width))) +
         (l.reduce_strength ? ", strength reduced" : "");
}

AfcParams material(const Law& l) {
  AfcParams p = shipped();
  p.options.sdel_regularization = l.reg;
  p.options.crack_band_width_spacings = l.width;
  p.options.crack_band_strength_reduction = l.reduce_strength;
  return p;
}

struct Elastic {
  double E, nu, c;
};
Elastic elastic(const AfcParams& p) {
  const double K = p.C6_Pa / p.C7, G = p.shear_modulus_Pa;
  return {9 * K * G / (3 * K + G), (3 * K - 2 * G) / (2 * (3 * K + G)), std::sqrt((K + 4 * G / 3) / p.density_kg_m3)};
}

// The seed of a layer: its initial d+ and (crack band) tensile work.
struct Seed {
  double d_plus = 0, tensile_work = 0;
};

// A material point on the uniaxial-stress path at the bar's strain rate (the same rate factor), from a
// seed: its peak, and its work per volume to full damage (or to the peak only).
struct PointPath {
  double peak_Pa = 0, work_J_m3 = 0;
};
PointPath point_path(const AfcMaterial& law, double h, const Seed& seed, bool to_peak_only) {
  Driver pt{law, h};
  pt.state().d_plus = seed.d_plus;
  pt.state().tensile_work = seed.tensile_work;
  const double de = 1e-7;
  PointPath r;
  double s_old = 0.0, e_old = 0.0;
  for (int i = 0; i < 200000 && pt.state().d_plus < kFailed; ++i) {
    pt.uniaxial_stress_step(de, de / kStrainRate);
    const double s = pt.state().stress(0, 0), e = pt.total_strain()(0, 0);
    r.work_J_m3 += 0.5 * (s + s_old) * (e - e_old);
    r.peak_Pa = std::max(r.peak_Pa, s);
    if (to_peak_only && s < 0.9 * r.peak_Pa) break;
    s_old = s;
    e_old = e;
  }
  return r;
}

// The seed that puts the layer's peak in uniaxial tension at the bar's rate at (1 - kSeedMargin) of the
// unseeded point's: d0 by bisection on the seeded point's own peak, and with the crack band the tensile
// work it stands for, the reference work x with D(x) = d0 (bisection), W_t = x l_ref / (n_b h).
Seed seed_with_damage(const AfcMaterial& law, double h, double d0) {
  const AfcParams& p = law.params();
  Seed s;
  s.d_plus = d0;
  if (p.options.sdel_regularization == SdelRegularization::CrackBand) {
    double lo = 0.0, hi = 1e6;
    for (int i = 0; i < 100; ++i) {
      const double mid = 0.5 * (lo + hi);
      (law.crack_band_damage(mid) < d0 ? lo : hi) = mid;
    }
    s.tensile_work = lo * p.options.crack_band_reference_size_m / law.band_width(h);
  }
  return s;
}
Seed seed_for(const AfcMaterial& law, double h) {
  const double target = (1 - kSeedMargin) * point_path(law, h, {}, true).peak_Pa;
  double lo = 0.0, hi = 0.9;
  for (int i = 0; i < 25; ++i) {
    const double mid = 0.5 * (lo + hi);
    (point_path(law, h, seed_with_damage(law, h, mid), true).peak_Pa > target ? lo : hi) = mid;
  }
  return seed_with_damage(law, h, hi);
}

struct BarResult {
  Law law;
  double h = 0;
  Seed seed;
  double seeded_peak_Pa = 0;          // the seeded point's peak at the bar's rate
  double point_peak_Pa = 0;           // the intact point's
  double g_point = 0, g_point_seeded = 0;  // h x the point's work: quasi-static; seeded at the bar's rate
  double g_separation = 0, g_band = 0;     // material dissipation / A at separation, one transit later
  double g_viscous = 0, g_stabilization = 0, kinetic = 0;  // at the end, / A
  std::vector<double> layers;         // per layer / A at the end, the seeded one +- 2
  std::vector<double> layer_damage;   // the smallest d+ of each of those layers
  double prepeak_kinetic = 0;         // largest departure kinetic energy / stored energy before the peak
  double peak_Pa = 0;                 // largest mean axial stress of the bar
  double time_to_peak = 0, transit = 0;
  bool separated = false;
  int other_failed_layers = 0;        // layers fully failed when the seeded one failed, not beside it
  double balance = 0;                 // the ledger's balance error over the energy put in
  long steps = 0;
  double wall_s = 0;
};

BarResult pull(double h, const Law& law_of_run) {
  const auto start = std::chrono::steady_clock::now();
  const AfcParams params = material(law_of_run);
  const AfcMaterial law(params);
  const Elastic el = elastic(params);
  BarResult r;
  r.law = law_of_run;
  r.h = h;
  r.transit = kLength / el.c;
  r.seed = seed_for(law, h);
  r.point_peak_Pa = point_path(law, h, {}, true).peak_Pa;
  const PointPath seeded = point_path(law, h, r.seed, false);
  r.seeded_peak_Pa = seeded.peak_Pa;
  r.g_point_seeded = h * seeded.work_J_m3;
  {
    Driver pt{law, h};  // quasi-static, no seed: the unit tests' G
    double s_old = 0.0, e_old = 0.0, work = 0.0;
    for (int i = 0; i < 200000 && pt.state().d_plus < kFailed; ++i) {
      pt.uniaxial_stress_step(1e-7, 1e-2);
      const double s = pt.state().stress(0, 0), e = pt.total_strain()(0, 0);
      work += 0.5 * (s + s_old) * (e - e_old);
      s_old = s;
      e_old = e;
    }
    r.g_point = h * work;
  }

  const double side = 4 * h, area = side * side;
  const ParticleBody body = box_body(kLength, side, side, h);
  const int layers = static_cast<int>(std::lround(kLength / h));
  const int seed_layer = layers / 2;
  std::vector<int> layer(body.size());
  for (std::size_t i = 0; i < body.size(); ++i) layer[i] = static_cast<int>(std::floor(body.position[3 * i] / h));
  MaterialSet set = make_material_set(law, body.size());
  for (std::size_t i = 0; i < body.size(); ++i)
    if (layer[i] == seed_layer) {
      AfcMaterial::State& s = std::get<MaterialBlock<AfcMaterial>>(set).state[i];
      s.d_plus = r.seed.d_plus;
      s.tensile_work = r.seed.tensile_work;
    }
  SolverOptions options;  // the shipped case's solver settings (macro/README.md)
  options.support_factor = 2.5;
  options.shape_reuse_tolerance = 3e-4;
  options.viscosity.damp_stress_free_points = false;
  ExplicitSolver solver(Particles::from_body(body, params.density_kg_m3, options.support_factor), std::move(set),
                        options);

  const auto motion = [&](const double* x) -> Vec3 {
    return {kStrainRate * (x[0] - 0.5 * kLength), -el.nu * kStrainRate * (x[1] - 0.5 * side),
            -el.nu * kStrainRate * (x[2] - 0.5 * side)};
  };
  Particles& p = solver.particles();
  for (std::size_t i = 0; i < p.n; ++i) {
    const Vec3 v = motion(&p.x[3 * i]);
    for (int d = 0; d < 3; ++d) p.v[3 * i + d] = v[d];
    if (layer[i] < kGripLayers || layer[i] >= layers - kGripLayers)
      solver.add_prescribed_velocity({{static_cast<std::int32_t>(i)}, v});
  }
  solver.initialize();

  const auto& states = std::get<MaterialBlock<AfcMaterial>>(solver.material()).state;
  const auto layer_failed = [&](int l) {
    for (std::size_t i = 0; i < p.n; ++i)
      if (layer[i] == l && states[i].d_plus < kFailed) return false;
    return true;
  };
  const std::vector<double> x0 = p.x;
  bool past_peak = false;
  double t_separation = 0.0;
  const double t_end = 2.0 * 4e-4 / kStrainRate;  // twice the time to a strain of 4e-4, past every peak here
  while (solver.time() < t_end) {
    if (!solver.step()) {
      ADD_FAILURE() << name(law_of_run) << ", h " << h << ": the step failed at t = " << solver.time();
      break;
    }
    double axial = 0.0;
    for (std::size_t i = 0; i < p.n; ++i) axial += states[i].stress(0, 0);
    axial /= static_cast<double>(p.n);
    if (axial > r.peak_Pa) {
      r.peak_Pa = axial;
      r.time_to_peak = solver.time();
    } else if (axial < 0.99 * r.peak_Pa) {
      past_peak = true;
    }
    if (!past_peak) {
      double departure = 0.0;
      for (std::size_t i = 0; i < p.n; ++i) {
        const Vec3 v = motion(&x0[3 * i]);  // each particle keeps its initial velocity in the exact solution
        for (int d = 0; d < 3; ++d) departure += 0.5 * p.mass[i] * std::pow(p.v[3 * i + d] - v[d], 2);
      }
      const double stored = solver.ledger().material_stored;
      if (stored > 0) r.prepeak_kinetic = std::max(r.prepeak_kinetic, departure / stored);
    }
    if (!r.separated && layer_failed(seed_layer)) {
      r.separated = true;
      t_separation = solver.time();
      r.g_separation = solver.ledger().material_dissipated / area;
      for (int l = 0; l < layers; ++l)
        if (std::abs(l - seed_layer) > 1 && layer_failed(l)) ++r.other_failed_layers;
    }
    if (r.separated && solver.time() >= t_separation + r.transit) break;
  }
  const EnergyLedger& e = solver.ledger();
  r.steps = solver.steps();
  r.g_band = e.material_dissipated / area;
  r.g_viscous = e.viscous / area;
  r.g_stabilization = e.stabilization_dissipated() / area;
  r.kinetic = e.kinetic / area;
  r.balance = e.balance_error() / (e.external + e.kinetic_initial);
  std::vector<double> per_layer(layers, 0.0), d_min(layers, 1.0);
  for (std::size_t i = 0; i < p.n; ++i) {
    per_layer[layer[i]] += solver.dissipated_density(i) * p.volume0[i] / area;
    d_min[layer[i]] = std::min(d_min[layer[i]], states[i].d_plus);
  }
  for (int l = seed_layer - 2; l <= seed_layer + 2; ++l) {
    r.layers.push_back(per_layer[l]);
    r.layer_damage.push_back(d_min[l]);
  }
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

void print(const BarResult& r) {
  std::printf("%-10s h %.2f mm: G bar %6.2f J/m^2 at separation, %6.2f one transit later | layers -2..+2: %.2f %.2f "
              "[%.2f] %.2f %.2f J/m^2, smallest d+ %.3f %.3f [%.3f] %.3f %.3f | point G %.2f (seeded, at the bar's "
              "rate %.2f) | viscous %.2f, stabilization %.2f, kinetic %.1f J/m^2 | peak %.2f MPa after %.0f transits, "
              "seeded layer's %.2f MPa (d+ %.3f), pre-peak departure KE %.1e of stored | balance %.1e | %ld steps, "
              "%.1f s\n",
              name(r.law).c_str(), 1e3 * r.h, r.g_separation, r.g_band, r.layers[0], r.layers[1], r.layers[2], r.layers[3],
              r.layers[4], r.layer_damage[0], r.layer_damage[1], r.layer_damage[2], r.layer_damage[3],
              r.layer_damage[4], r.g_point, r.g_point_seeded, r.g_viscous, r.g_stabilization, r.kinetic,
              1e-6 * r.peak_Pa, r.time_to_peak / r.transit, 1e-6 * r.seeded_peak_Pa, r.seed.d_plus, r.prepeak_kinetic,
              r.balance, r.steps, r.wall_s);
}

// What every run must show for its G to mean anything: the loading is quasi-static up to the peak, the
// crack forms at the seeded layer (it fails, and no layer but it and the two beside it, which the RK
// support strains with it, has failed by then), the bar peaks at the seeded layer's strength, and the
// ledger closes (sound runs stay below 2e-3 of the energy put in: SolverOptions::energy_error_limit).
void expect_sound(const BarResult& r) {
  EXPECT_LT(r.prepeak_kinetic, 1e-2) << name(r.law) << " " << r.h;
  EXPECT_TRUE(r.separated) << name(r.law) << " " << r.h;
  EXPECT_EQ(r.other_failed_layers, 0) << name(r.law) << " " << r.h;
  EXPECT_LT(std::fabs(r.balance), 2e-3) << name(r.law) << " " << r.h;
  // The bar peaks at the seeded layer's strength, below the intact material's.
  EXPECT_LT(r.peak_Pa, 0.98 * r.point_peak_Pa) << name(r.law) << " " << r.h;
  if (r.law.reg == SdelRegularization::CrackBand) {
    // What the crack band guarantees in the solver too: a layer does not fail before it has dissipated its
    // share of the reference's l_ref W_ref per unit area, h W = l_ref W_ref / n_b (d+ = 1 needs that tensile
    // work). The layers beside the seeded one, which fail with it, are checked (the seeded one started
    // with its seed's share).
    for (const int k : {1, 3}) {
      // They fail with it (d+ 0.9997 and more at 3.0 and 6.0 mm), and have dissipated their share.
      EXPECT_GE(r.layer_damage[k], 0.999) << name(r.law) << " " << r.h << " " << k;
      EXPECT_GT(r.layers[k], 0.995 * r.g_point) << name(r.law) << " " << r.h << " " << k;
    }
  }
}

double spread(const std::vector<BarResult>& rs, double BarResult::*g) {
  double lo = rs.front().*g, hi = lo;
  for (const BarResult& r : rs) {
    lo = std::min(lo, r.*g);
    hi = std::max(hi, r.*g);
  }
  return hi / lo - 1.0;
}

void study(const std::vector<double>& spacings, const std::vector<Law>& laws) {
  for (const Law& law : laws) {
    std::vector<BarResult> rs;
    for (const double h : spacings) {
      rs.push_back(pull(h, law));
      print(rs.back());
      expect_sound(rs.back());
    }
    std::printf("%s: spread of G over the spacings %.1f %% at separation, %.1f %% one transit later\n",
                name(law).c_str(), 100 * spread(rs, &BarResult::g_separation), 100 * spread(rs, &BarResult::g_band));
  }
}

const std::vector<Law> kBothLaws = {{SdelRegularization::Lambda}, {SdelRegularization::CrackBand}};

// ctest: two spacings, both laws (4 s on one thread).
TEST(MacroCrackBand, ABarPulledApartCracksInTheSeededLayerQuasiStatically) { study({0.003, 0.006}, kBothLaws); }

// The study (docs/studies/2026-12-06-crack-band.md), by hand, about a minute:
//   build/tests/verification_test_macro_crack_band --gtest_also_run_disabled_tests --gtest_filter=*Study
TEST(MacroCrackBand, DISABLED_Study) { study({0.0015, 0.00225, 0.003, 0.0045, 0.006}, kBothLaws); }

// The crack band three spacings wide (crack_band_width_spacings 3, the crack's width in the study above):
// the bar's G (one transit after separation) within 10 % across 1.5 / 2.25 / 3.0 mm, the spacings whose
// band 3 h the law holds to (up to about 8-9 mm, afc_params.hpp), and above the reference's G_ref by the
// seeded layer's extra only (measured 14.3-15.6 J/m^2 against G_ref 13.6: +5 to +15 %). Three layers fail,
// each dissipating its third of G_ref. Wider spacings (4.5, 6.0 mm: bands of 13.5 and 18 mm) snap back at
// a point and dissipate more, which the study below prints.
TEST(MacroCrackBand, ACrackBandThreeSpacingsWideGivesTheReferencesEnergyAtEverySpacing) {
  const Law law{SdelRegularization::CrackBand, 3.0};
  const double l_ref = AfcOptions{}.crack_band_reference_size_m;
  const AfcMaterial reference(material({SdelRegularization::Lambda}));
  const double g_ref = l_ref * point_path(reference, l_ref, {}, false).work_J_m3;
  std::vector<BarResult> rs;
  for (const double h : {0.0015, 0.00225, 0.003}) {
    rs.push_back(pull(h, law));
    print(rs.back());
    expect_sound(rs.back());
    EXPECT_GT(rs.back().g_band, g_ref) << rs.back().h;
    EXPECT_LT(rs.back().g_band, 1.2 * g_ref) << rs.back().h;
  }
  const double s = spread(rs, &BarResult::g_band);
  std::printf("%s: G_ref %.2f J/m^2 (at the bar's rate), spread of the bar's G over 1.5-3.0 mm %.1f %%\n",
              name(law).c_str(), g_ref, 100 * s);
  EXPECT_LE(s, 0.10);
}

// crack_band_strength_reduction past the band the law holds (bands of 13.5 and 18 mm at 4.5 and 6.0 mm):
// the crack's three layers dissipate G_ref and some more, as at 1.5-3.0 mm (measured 15.6 / 15.6 J/m^2;
// 15.6 / 14.3 / 14.9 there), and so does the bar at separation (15.6 / 15.5). One transit later the bar's
// total has 8-10 J/m^2 more (printed, not checked): the held end layers, whose strength is lowered too,
// yield under the grips' imposed motion; the layers between them and the crack dissipate nothing.
TEST(MacroCrackBand, AReducedStrengthHoldsTheThreeSpacingBandPastItsWidth) {
  const Law law{SdelRegularization::CrackBand, 3.0, true};
  const double l_ref = AfcOptions{}.crack_band_reference_size_m;
  const AfcMaterial reference(material({SdelRegularization::Lambda}));
  const double g_ref = l_ref * point_path(reference, l_ref, {}, false).work_J_m3;
  for (const double h : {0.0045, 0.006}) {
    const BarResult r = pull(h, law);
    print(r);
    expect_sound(r);
    const double crack = r.layers[1] + r.layers[2] + r.layers[3];
    EXPECT_GT(crack, g_ref) << h;
    EXPECT_LT(crack, 1.2 * g_ref) << h;
    EXPECT_GT(r.g_separation, g_ref) << h;
    EXPECT_LT(r.g_separation, 1.2 * g_ref) << h;
  }
}

// The three-spacing band at all five spacings (beside the study above), by hand:
//   build/tests/verification_test_macro_crack_band --gtest_also_run_disabled_tests --gtest_filter=*StudyWidth3
TEST(MacroCrackBand, DISABLED_StudyWidth3) {
  study({0.0015, 0.00225, 0.003, 0.0045, 0.006}, {{SdelRegularization::CrackBand, 3.0}});
}
TEST(MacroCrackBand, DISABLED_StudyWidth3Reduced) {
  study({0.0015, 0.00225, 0.003, 0.0045, 0.006}, {{SdelRegularization::CrackBand, 3.0, true}});
}

}  // namespace
}  // namespace uhpc::macro
