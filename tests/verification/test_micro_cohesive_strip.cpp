// Known answers of the cohesive-crack analysis (micro/analysis/cell_analysis):
//  - a strip without pores with one straight crack path across it, normal to the load, pulled to
//    separation: the crack activates when the (uniform) stress reaches f_t, so the peak sigma_bar is
//    f_t; the energy dissipated at separation is G_f x crack length (per unit thickness); the damage
//    d = 1 - sigma_bar/(E0_bar e_bar) is 0 to round-off before the crack opens and tends to 1 at
//    separation; the external work equals bulk + cohesive + dissipated energy along the whole path;
//  - a cell with one pore and its two seeds (top and bottom of the pore): the seeds activate at the
//    hoop-stress concentration, the cracks grow normal to the load to the cell edges and the cell
//    separates.
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <Eigen/Core>
#include <gtest/gtest.h>

#include "cell_analysis.hpp"
#include "cell_generator.hpp"
#include "cell_mesh.hpp"
#include "enrichment.hpp"
#include "rk_galerkin_model.hpp"
#include "micro_paper_options.hpp"

namespace uhpc::micro {
namespace {

CellMaterial table2() {
  CellMaterial m;
  m.elastic = {4.4296e10, 0.2};
  m.tensile_strength_Pa = 22.7e6;
  m.fracture_energy_J_m2 = 35.0;
  return m;
}

// Tolerances of the straight strip's checks below. The damage never fell between states on any path
// (measured 0 exactly): only round-off is admitted. The variants' peak is the default path's to the bit
// (the crack activates at f_t on every path); their dissipation at separation is 0.26 % above the default
// path's (measured +2.63e-3 with the process zone at every step or growth at zero load, +2.5e-5 with VCI),
// because the default path declares separation at d = 0.99956, short of the last 0.26 % of G_f L in the
// softening law's tail, where the others go on to d = 0.99998: twice that is admitted.
constexpr double kDamageRoundOff = 1e-12;
constexpr double kSamePeak = 1e-12;
constexpr double kSameDissipation = 5e-3;

MeshOptions spacing(double h) {
  MeshOptions o;
  o.nominal_spacing_m = h;
  return o;
}

void print(const CellResponse& r) {
  if (std::getenv("UHPC_PRINT_STATES"))
    for (const CellState& s : r.states)
    std::printf("  e %.4e  s %.4f MPa  segs %zu open %zu  bulk %.3e coh %.3e diss %.3e W %.3e wmax %.3e it %d\n", s.strain,
                s.sigma_bar_Pa * 1e-6, s.crack_segments, s.open_segments, s.bulk_energy_J_m, s.cohesive_energy_J_m,
                s.dissipated_J_m, s.external_work_J_m, s.max_opening_m, s.newton_iterations);
  std::printf("status %s (%s), %zu states, E0_bar %.1f MPa, %zu nodes, %zu dofs, %zu enriched, %.2f s\n",
              to_string(r.status), r.diagnostic.c_str(), r.states.size(), r.E0_bar_Pa * 1e-6, r.nodes, r.dofs,
              r.enriched_nodes, r.wall_s);
}

// The ramped tip enrichment: with arbitrary enriched coefficients the displacement jumps across the
// active crack (by the jump operator of the cohesive points), the jump falls to zero at the open tip
// and the field is continuous beyond it.
TEST(microCohesiveStrip, RampedEnrichmentClosesAtTheTip) {
  const double L = 1e-3;
  CellGeometry g;
  g.side_m = L;
  const CellDiscretization mesh = mesh_cell(g, spacing(100e-6));
  const RkGalerkinModel base = build_rk_galerkin_model(mesh, RkGalerkinOptions{});
  Crack c;
  c.root = CrackEnd::Edge;
  const double xc = 0.5 * L + 3.1e-6;
  for (int k = 0; k <= 6; ++k) c.points.push_back({xc, 0.1e-3 * k});  // planned to y = 0.6 mm
  c.active = 4;                                                        // tip at y = 0.4 mm: open
  const std::vector<Crack> cracks{c};
  const EnrichedModel em = build_enriched_model(base, mesh, cracks, {{0.0, 0.5 * L}}, EnrichmentOptions{});
  ASSERT_GT(em.enriched_node.size(), 0u);
  Eigen::VectorXd d = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(em.dof_count()));
  for (std::size_t k = 0; k < em.enriched_node.size(); ++k) {
    const auto i = static_cast<Eigen::Index>(2 * (em.standard_nodes + k));
    d[i] = 1e-6 * std::sin(1.0 + 0.7 * k);
    d[i + 1] = 1e-6 * std::cos(0.3 * k);
  }
  const double eps = 1e-9;
  auto jump_at = [&](double y) {
    const std::vector<double> pts{xc - eps, y, xc + eps, y};
    const GeneralTable t = enriched_table_at(base, em, cracks, pts);
    double u[2][2] = {{0.0, 0.0}, {0.0, 0.0}};
    for (std::size_t p = 0; p < 2; ++p)
      for (std::int64_t e = t.support.begin(p); e < t.support.end(p); ++e)
        for (int k = 0; k < 2; ++k) u[p][k] += t.psi[e] * d[2 * t.support.indices[e] + k];
    return std::hypot(u[0][0] - u[1][0], u[0][1] - u[1][1]);  // left (H = 1) minus right
  };
  double scale = 0.0;
  for (const CohesivePoint& q : em.cohesive) {
    double j[2] = {0.0, 0.0};
    for (std::int64_t e = q.begin; e < q.end; ++e)
      for (int k = 0; k < 2; ++k) j[k] += em.jump_coefficient[e] * d[2 * em.jump_node[e] + k];
    const double measured = jump_at(q.x[1]);
    EXPECT_NEAR(measured, std::hypot(j[0], j[1]), 1e-6 * 1e-6 + 1e-3 * measured) << "y = " << q.x[1];
    scale = std::max(scale, measured);
  }
  EXPECT_GT(scale, 1e-9);
  EXPECT_LT(jump_at(0.4e-3 - 1e-7), 2e-3 * scale);  // just behind the tip: almost closed
  EXPECT_LT(jump_at(0.4e-3 + 1e-6), 1e-9 * scale);  // beyond the tip: continuous
  EXPECT_LT(jump_at(0.55e-3), 1e-9 * scale);
  EXPECT_GT(jump_at(0.2e-3), 0.05 * scale);         // behind the last segment: open
}

double peak_stress(const CellResponse& r);

// Checks the straight strip's known answers under the options `o` and returns the response (for the
// variants' comparison with the default path).
CellResponse check_straight_strip(const CellAnalysisOptions& o) {
  const double L = 1e-3;
  CellGeometry g;
  g.side_m = L;
  const double xc = 0.5 * L + 1.3e-6;  // off the mesh's symmetry line, so no node sits on the crack
  g.seeds.push_back({-1, {xc, 0.0}, {xc, L}});  // a crack path from edge to edge, normal to x
  const CellDiscretization mesh = mesh_cell(g, spacing(100e-6));
  const CellMaterial m = table2();
  const CellResponse r = analyze_cell(g, mesh, m, o);
  print(r);
  EXPECT_EQ(r.status, CellStatus::Separated) << r.diagnostic;
  if (r.status != CellStatus::Separated) return r;

  double peak = 0.0;
  for (const CellState& s : r.states) peak = std::max(peak, s.sigma_bar_Pa);
  const CellState& last = r.states.back();
  const double Gl = m.fracture_energy_J_m2 * L;
  std::printf("peak sigma_bar %.4f MPa (f_t 22.7), dissipated %.5f J/m (G_f L %.5f), final d %.5f\n", peak * 1e-6,
              last.dissipated_J_m, Gl, state_damage(r, last));
  EXPECT_NEAR(peak / m.tensile_strength_Pa, 1.0, 0.02);
  EXPECT_NEAR(last.dissipated_J_m / Gl, 1.0, 0.02);
  EXPECT_GT(state_damage(r, last), 0.99);

  bool cracked = false;
  double worst = 0.0;
  for (std::size_t k = 1; k < r.states.size(); ++k) {
    const CellState& s = r.states[k];
    cracked = cracked || s.crack_segments > 0;
    if (!cracked) {
      EXPECT_NEAR(state_damage(r, s), 0.0, 1e-12) << "state " << k;
    }
    const double stored = s.bulk_energy_J_m + s.cohesive_energy_J_m + s.dissipated_J_m;
    worst = std::max(worst, std::abs(s.external_work_J_m - stored) / s.external_work_J_m);
    EXPECT_NEAR(stored / s.external_work_J_m, 1.0, 0.01) << "state " << k << " e_bar " << s.strain;
  }
  std::printf("worst energy balance error %.3e (relative to the external work), operator energy mismatch %.2e\n",
              worst, r.operator_energy_mismatch);
  EXPECT_LT(r.operator_energy_mismatch, 0.01);
  // A symmetric (Galerkin) cracked operator: its quadratic form is the stored energy to round-off
  // (2e-12 measured; VCI's Petrov-Galerkin operator: 6e-6).
  if (o.enrichment.cracked_correction == IntegrationCorrection::None) {
    EXPECT_LT(r.operator_energy_mismatch, 1e-9);
  }
  // Damage grows monotonically on the softening branch: from the crack's first segment to separation no
  // loaded state has less damage than the one before it (states at zero strain, where the fallback has
  // unloaded the strip, carry no secant damage and are skipped; an unloading state keeps its damage).
  EXPECT_TRUE(cracked);
  double previous = 0.0, worst_drop = 0.0;
  for (std::size_t k = 1; k < r.states.size(); ++k) {
    const CellState& s = r.states[k];
    if (s.crack_segments == 0 || !(s.strain > 0.0)) continue;
    const double d = state_damage(r, s);
    worst_drop = std::max(worst_drop, previous - d);
    EXPECT_GE(d, previous - kDamageRoundOff) << "state " << k << " e_bar " << s.strain;
    previous = std::max(previous, d);
  }
  std::printf("largest fall of the damage between states on the softening branch: %.2e\n", worst_drop);
  if (o.verification.unload_at_every_growth) {
    EXPECT_GT(r.growth_unloads, 5u);
  }
  return r;
}

// The variants below follow the same path by other means, so they must give the default path's answer,
// not only pass the same known-answer bands: the peak and the dissipation at separation against the
// default run's, within kSamePeak and kSameDissipation (relative).
void expect_same_answer(const CellResponse& variant, const CellResponse& reference) {
  ASSERT_EQ(variant.status, CellStatus::Separated);
  ASSERT_EQ(reference.status, CellStatus::Separated);
  const double peak_ratio = peak_stress(variant) / peak_stress(reference);
  const double dissipated_ratio = variant.states.back().dissipated_J_m / reference.states.back().dissipated_J_m;
  std::printf("against the default path: peak %+.2e, dissipated %+.2e (relative)\n", peak_ratio - 1.0,
              dissipated_ratio - 1.0);
  EXPECT_NEAR(peak_ratio, 1.0, kSamePeak);
  EXPECT_NEAR(dissipated_ratio, 1.0, kSameDissipation);
}

void expect_same_answer(const CellResponse& variant) {
  static const CellResponse reference = check_straight_strip(CellAnalysisOptions{});
  expect_same_answer(variant, reference);
}

// Every step on the process zone's opening (the test hook zone_at_every_step; the default uses it only
// where the global opening integral folds): the same peak, dissipation and energy balance.
TEST(microCohesiveStrip, ProcessZoneControlGivesTheSameAnswer) {
  CellAnalysisOptions o;
  o.verification.zone_at_every_step = true;
  expect_same_answer(check_straight_strip(o));
}

TEST(microCohesiveStrip, StraightCrackDissipatesGfAndPeaksAtFt) { check_straight_strip(CellAnalysisOptions{}); }

// The cracked model with VCI (quadrature.cracked_correction = vci, the default before: a
// Petrov-Galerkin operator once a segment is active): the same peak, dissipation and balance.
TEST(microCohesiveStrip, StraightCrackWithCrackedVciGivesTheSameAnswer) {
  CellAnalysisOptions o;
  o.enrichment.cracked_correction = IntegrationCorrection::Vci;
  expect_same_answer(check_straight_strip(o));
}

// Every growth event through the fallback (unload to zero, grow there, reload): the same peak,
// dissipation and energy balance, so the fallback that rescues porous cells is consistent.
TEST(microCohesiveStrip, GrowingAtZeroLoadGivesTheSameAnswer) {
  CellAnalysisOptions o;
  o.verification.unload_at_every_growth = true;
  expect_same_answer(check_straight_strip(o));
}

// A strip longer than 2 l_ch (l_ch = E G_f / f_t^2 = 3.0 mm): the elastic energy stored at the peak
// exceeds G_f x crack length, so the equilibrium path snaps back (the far-face displacement must
// decrease after the peak). The crack-opening control follows it to separation with the same
// dissipation and energy balance as the short strip.
constexpr double kLongStrip_m = 8e-3;

CellGeometry long_strip() {
  CellGeometry g;
  g.side_m = kLongStrip_m;
  const double xc = 0.5 * kLongStrip_m + 7.3e-6;  // off the node columns
  g.seeds.push_back({-1, {xc, 0.0}, {xc, kLongStrip_m}});
  return g;
}

CellResponse check_long_strip(const CellAnalysisOptions& o) {
  const double L = kLongStrip_m;
  const CellGeometry g = long_strip();
  const CellDiscretization mesh = mesh_cell(g, spacing(400e-6));
  const CellMaterial m = table2();
  const CellResponse r = analyze_cell(g, mesh, m, o);
  print(r);
  EXPECT_EQ(r.status, CellStatus::Separated) << r.diagnostic;
  if (r.status != CellStatus::Separated) return r;
  double peak = 0.0, e_peak = 0.0, e_min_after = 1.0, worst = 0.0;
  for (const CellState& s : r.states) {
    if (s.sigma_bar_Pa > peak) {
      peak = s.sigma_bar_Pa;
      e_peak = s.strain;
      e_min_after = s.strain;
    }
    e_min_after = std::min(e_min_after, s.strain);
    if (s.external_work_J_m > 0.0)
      worst = std::max(worst, std::abs(s.external_work_J_m - s.bulk_energy_J_m - s.cohesive_energy_J_m -
                                       s.dissipated_J_m) / s.external_work_J_m);
  }
  const CellState& last = r.states.back();
  std::printf("peak %.4f MPa at e %.4e, smallest e after the peak %.4e, dissipated %.5f J/m (G_f L %.5f), worst "
              "energy balance %.2e\n", peak * 1e-6, e_peak, e_min_after, last.dissipated_J_m,
              m.fracture_energy_J_m2 * L, worst);
  EXPECT_NEAR(peak / m.tensile_strength_Pa, 1.0, 0.02);
  EXPECT_LT(e_min_after, 0.8 * e_peak);  // snap-back: the imposed strain falls after the peak
  // ... but not below the end of the branch, e = sigma/E0_bar + w/L -> w_c/L at separation (linear
  // softening, w_c = 2 G_f/f_t). A growth step that held the total opening once took the path back to
  // the elastic line, 0.75 w_c/L (cell_analysis.cpp, grow()).
  const double w_c = 2.0 * m.fracture_energy_J_m2 / m.tensile_strength_Pa;
  EXPECT_GT(e_min_after, 0.98 * w_c / L);
  EXPECT_NEAR(last.dissipated_J_m / (m.fracture_energy_J_m2 * L), 1.0, 0.02);
  EXPECT_LT(worst, 0.01);
  return r;
}

TEST(microCohesiveStrip, LongStripSnapsBackAndSeparates) { check_long_strip(CellAnalysisOptions{}); }

// Every step on the process zone's opening: the snap-back followed alike, and the default path's peak
// and dissipation.
TEST(microCohesiveStrip, LongStripOnTheProcessZoneOpeningSnapsBackAlike) {
  CellAnalysisOptions o;
  o.verification.zone_at_every_step = true;
  expect_same_answer(check_long_strip(o), check_long_strip(CellAnalysisOptions{}));
}

// The same long strip under displacement control, which cannot follow the snap-back: at the peak
// the path has no continuation, and the jump a strain-controlled test takes there (JumpFallback::Relax)
// separates the strip at the peak strain (the bulk stores more than G_f L). Known answers: the
// cohesive dissipation is G_f L, and the jump releases the rest of the energy stored at the peak,
// 1/2 f_t^2 L^2 / E' - G_f L (0.0774 J/m against 0.280 J/m dissipated).
TEST(microCohesiveStrip, LongStripUnderDisplacementControlJumpsToSeparation) {
  const double L = kLongStrip_m;
  const CellGeometry g = long_strip();
  const CellDiscretization mesh = mesh_cell(g, spacing(400e-6));
  const CellMaterial m = table2();
  CellAnalysisOptions o;
  o.control = PathControl::Displacement;
  // The jump is verified on VCI's cracked operator: with the default plain Gauss (None) the growth at
  // this strip's peak does not re-equilibrate under displacement control; growth unloads follow and the
  // jump comes below the peak, releasing 10 % too little (micro/README.md); a known weakness of None
  // (enrichment.hpp), outside the crack-opening path the analyses use.
  o.enrichment.cracked_correction = IntegrationCorrection::Vci;
  o.min_strain_increment = 1e-8;  // the halvings before the jump are the slow part of this test
  const CellResponse r = analyze_cell(g, mesh, m, o);
  print(r);
  ASSERT_EQ(r.status, CellStatus::Separated) << r.diagnostic;
  double peak = 0.0, e_peak = 0.0;
  for (const CellState& s : r.states)
    if (s.sigma_bar_Pa > peak) {
      peak = s.sigma_bar_Pa;
      e_peak = s.strain;
    }
  const CellState& last = r.states.back();
  const double E = m.elastic.plane_modulus_Pa();
  const double released = 0.5 * m.tensile_strength_Pa * m.tensile_strength_Pa * L * L / E - m.fracture_energy_J_m2 * L;
  std::printf("peak %.4f MPa at e %.4e, separated at e %.4e after %zu jump(s); dissipated %.5f J/m (G_f L %.5f), "
              "released in the jump %.5f J/m (closed form %.5f)\n", peak * 1e-6, e_peak, last.strain, r.jumps,
              last.dissipated_J_m, m.fracture_energy_J_m2 * L, last.jump_dissipated_J_m, released);
  EXPECT_NEAR(peak / m.tensile_strength_Pa, 1.0, 0.02);
  EXPECT_EQ(r.jumps, 1u);
  EXPECT_NEAR(last.strain / e_peak, 1.0, 0.01);  // the jump happens at the peak strain
  EXPECT_NEAR(last.dissipated_J_m / (m.fracture_energy_J_m2 * L), 1.0, 0.02);
  EXPECT_NEAR(last.jump_dissipated_J_m / released, 1.0, 0.03);
  // Without the jump the displacement control stops at the peak.
  o.jump = JumpFallback::Fail;
  EXPECT_EQ(analyze_cell(g, mesh, m, o).status, CellStatus::Failed);
}

double peak_stress(const CellResponse& r) {
  double peak = 0.0;
  for (const CellState& s : r.states) peak = std::max(peak, s.sigma_bar_Pa);
  return peak;
}

CellResponse check_one_pore(const CellAnalysisOptions& o) {
  const double L = 1.2e-3, D = 0.3e-3;
  CellGeometry g;
  g.side_m = L;
  g.pores.push_back({{0.5 * L, 0.5 * L}, D});
  const double h = 50e-6;
  g.seeds.push_back({0, {0.5 * L, 0.5 * (L + D)}, {0.5 * L, 0.5 * (L + D) + h}});
  g.seeds.push_back({0, {0.5 * L, 0.5 * (L - D)}, {0.5 * L, 0.5 * (L - D) - h}});
  const CellDiscretization mesh = mesh_cell(g, spacing(h));
  const CellMaterial m = table2();
  std::vector<Crack> cracks;
  const CellResponse r = analyze_cell(g, mesh, m, o, {}, &cracks);
  print(r);
  EXPECT_EQ(r.status, CellStatus::Separated) << r.diagnostic;
  if (r.status != CellStatus::Separated) return r;
  const double peak = peak_stress(r);
  // Energy balance relative to the largest external work so far (an unload gives work back, so the
  // current work is no scale there), worst over the path and at the end.
  double worst = 0.0, work_max = 0.0, final_error = 0.0;
  for (const CellState& s : r.states) {
    work_max = std::max(work_max, s.external_work_J_m);
    if (work_max <= 0.0) continue;
    final_error = std::abs(s.external_work_J_m - s.bulk_energy_J_m - s.cohesive_energy_J_m - s.dissipated_J_m) / work_max;
    worst = std::max(worst, final_error);
  }
  std::printf("peak sigma_bar %.3f MPa, E0_bar %.0f MPa, energy balance worst %.2e, final %.2e, dissipated %.5f J/m, "
              "growth events passed by unloading %zu, operator energy mismatch %.2e\n",
              peak * 1e-6, r.E0_bar_Pa * 1e-6, worst, final_error, r.states.back().dissipated_J_m, r.growth_unloads,
              r.operator_energy_mismatch);
  // The discrete operator stays consistent with the stored energy (a spurious soft mode would part them).
  EXPECT_LT(r.operator_energy_mismatch, 0.01);
  // The pore concentrates the stress: the first crack starts below f_t x E0_bar/E'.
  EXPECT_LT(peak, m.tensile_strength_Pa);
  EXPECT_EQ(cracks.size(), 2u);
  if (cracks.size() != 2u) return r;
  for (const Crack& c : cracks) {
    std::printf("crack from seed %d: %zu active segments, tip (%.1f, %.1f) um, end %d\n", c.seed, c.active,
                c.tip().x * 1e6, c.tip().y * 1e6, static_cast<int>(c.tip_end));
    EXPECT_EQ(c.tip_end, CrackEnd::Edge);
    double drift = 0.0;
    for (std::size_t k = 0; k <= c.active; ++k) drift = std::max(drift, std::abs(c.points[k].x - 0.5 * L));
    EXPECT_LT(drift, 0.1 * 0.5 * (L - D));  // normal to the load: within 10 % of the ligament
  }
  // Two straight cracks across the ligaments: G_f x (L - D) dissipated, and the energies balance.
  EXPECT_NEAR(r.states.back().dissipated_J_m / (m.fracture_energy_J_m2 * (L - D)), 1.0, 0.02);
  EXPECT_LT(final_error, 0.01);
  if (!o.verification.unload_at_every_growth) {
    EXPECT_LT(worst, 0.01);
  } else {
    // Measured 1.3e-2 (plain path 5.6e-3): each unload books -1/2 F lambda, the operator's energy,
    // which exceeds the bulk energy reported by up to 0.7 % (VCI's asymmetry; the Nitsche terms hold
    // only 1e-6 of it), and the steps after a reload add their trapezoid error; a known cost of the
    // fallback, bounded here.
    EXPECT_LT(worst, 0.02);
    EXPECT_GT(r.growth_unloads, 5u);
  }
  return r;
}

TEST(microCohesiveStrip, SeedsOfOnePoreGrowNormalToTheLoadAndSeparate) { check_one_pore(CellAnalysisOptions{}); }

TEST(microCohesiveStrip, SeedsOfOnePoreGrowingAtZeroLoadGiveTheSameAnswer) {
  CellAnalysisOptions o;
  o.verification.unload_at_every_growth = true;
  const double peak = peak_stress(check_one_pore(o));
  EXPECT_NEAR(peak / peak_stress(check_one_pore(CellAnalysisOptions{})), 1.0, 0.01);
}

// Newton corrections by GMRES with an earlier factorization (newton.krylov_iterations, the default)
// against a factorization at every iteration: the same path to a fraction of the Newton tolerance,
// with fewer factorizations.
TEST(microCohesiveStrip, SeedsOfOnePoreWithKrylovCorrectionsGiveTheDirectAnswer) {
  CellAnalysisOptions direct;
  direct.krylov_iterations = 0;
  const CellResponse a = check_one_pore(CellAnalysisOptions{}), b = check_one_pore(direct);
  std::printf("factorizations %zu with %zu GMRES corrections (%zu products), %zu direct\n", a.factorizations,
              a.krylov_corrections, a.krylov_products, b.factorizations);
  EXPECT_EQ(b.krylov_corrections, 0u);
  EXPECT_GT(a.krylov_corrections, 0u);
  EXPECT_LT(a.factorizations, b.factorizations);
  ASSERT_EQ(a.states.size(), b.states.size());
  EXPECT_NEAR(peak_stress(a) / peak_stress(b), 1.0, 1e-6);
  EXPECT_NEAR(a.states.back().dissipated_J_m / b.states.back().dissipated_J_m, 1.0, 1e-6);
}

// A paper cell (Burr pores at 3.4 %, two seeds per pore, 50 um spacing) to separation: a measurement,
// not a check (minutes per cell), so disabled by default. UHPC_CELL_SIZE (m, default 0.003) and
// UHPC_CELL_SEED (default 1) choose the cell. Prints the peak, the strain at d = 0.5, steps and time.
TEST(microCohesiveStrip, DISABLED_PaperCellToSeparation) {
  const double side = std::getenv("UHPC_CELL_SIZE") ? std::atof(std::getenv("UHPC_CELL_SIZE")) : 0.003;
  const std::uint64_t seed = std::getenv("UHPC_CELL_SEED") ? std::strtoull(std::getenv("UHPC_CELL_SEED"), nullptr, 10) : 1;
  const GeneratedCell cell = generate_cell(paper_options(side), seed);
  const double h = std::getenv("UHPC_CELL_SPACING") ? std::atof(std::getenv("UHPC_CELL_SPACING")) : 50e-6;
  const CellDiscretization mesh = mesh_cell(cell.geometry, spacing(h));
  std::printf("cell %.1f mm seed %llu: %zu pores, %zu seeds, porosity %.4f, %zu nodes\n", side * 1e3,
              static_cast<unsigned long long>(seed), cell.geometry.pores.size(), cell.geometry.seeds.size(),
              cell.geometry.porosity(), mesh.node_count());
  std::vector<Crack> cracks;
  CellAnalysisOptions options;
  if (std::getenv("UHPC_MIXED_MODE")) options.mode = CohesiveMode::MixedMode;
  const CellResponse r = analyze_cell(cell.geometry, mesh, table2(), options,
                                      [](std::size_t i, const CellState& s) {
                                        if (std::getenv("UHPC_PRINT_STATES")) {
                                          std::printf("  %zu e %.4e s %.4f MPa segs %zu it %d\n", i, s.strain,
                                                      s.sigma_bar_Pa * 1e-6, s.crack_segments, s.newton_iterations);
                                          std::fflush(stdout);
                                        }
                                      },
                                      &cracks);
  print(r);
  double peak = 0.0, e_peak = 0.0, e_half = -1.0, worst = 0.0;
  for (const CellState& s : r.states) {
    if (s.sigma_bar_Pa > peak) {
      peak = s.sigma_bar_Pa;
      e_peak = s.strain;
    }
    if (e_half < 0.0 && s.strain > 0.0 && state_damage(r, s) >= 0.5) e_half = s.strain;
    if (s.external_work_J_m > 0.0)
      worst = std::max(worst, std::abs(s.external_work_J_m - s.bulk_energy_J_m - s.cohesive_energy_J_m -
                                       s.dissipated_J_m) / s.external_work_J_m);
  }
  std::size_t stopped = 0;
  for (const Crack& c : cracks) stopped += c.stopped() ? 1 : 0;
  std::printf("peak sigma_bar %.3f MPa at e %.4e; first e with d >= 0.5: %.4e; final d %.4f; worst energy balance "
              "%.2e; %zu cracks (%zu stopped); final dissipated %.4e J/m\n",
              peak * 1e-6, e_peak, e_half, state_damage(r, r.states.back()), worst, cracks.size(), stopped,
              r.states.back().dissipated_J_m);
  if (std::getenv("UHPC_PRINT_STATES")) {
    for (const Pore& p : cell.geometry.pores)
      std::printf("pore %.6e %.6e %.6e\n", p.center_m.x, p.center_m.y, p.radius_m());
    for (const Crack& c : cracks) {
      std::printf("crack %d active %zu end %d:", c.seed, c.active, static_cast<int>(c.tip_end));
      for (std::size_t k = 0; k <= c.active; ++k) std::printf(" %.6e %.6e", c.points[k].x, c.points[k].y);
      std::printf("\n");
    }
  }
  EXPECT_EQ(r.status, CellStatus::Separated) << r.diagnostic;
}

}  // namespace
}  // namespace uhpc::micro
