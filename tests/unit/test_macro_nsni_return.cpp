// The NSNI stress gradient returned with the stress (macro/solver/nsni_gradient_return.hpp): the
// linearised radial return, and what the AFC law reports for it at a material point.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include "materials/afc.hpp"
#include "materials/afc_config.hpp"
#include "materials/j2_plasticity.hpp"
#include "materials/point_driver.hpp"
#include "solver/nsni_gradient_return.hpp"

namespace uhpc::macro {
namespace {

constexpr double MPa = 1e6;

Mat3 some_gradient() {
  Mat3 g;
  g << 3.0, 1.0, -2.0,  //
      1.0, -1.5, 0.5,   //
      -2.0, 0.5, 4.0;
  return g * MPa;
}

Mat3 some_stress() {
  Mat3 s;
  s << -50.0, 20.0, 0.0,  //
      20.0, -80.0, 5.0,   //
      0.0, 5.0, -30.0;
  return s * MPa;
}

double contract(const Mat3& a, const Mat3& b) { return a.cwiseProduct(b).sum(); }

TEST(NsniGradientReturn, ElasticStepLeavesTheGradientUntouched) {
  Mat3 g = some_gradient();
  return_stress_gradient(g, some_stress(), Moduli{1e10, 1e10, 1.0, 0.0, false});
  EXPECT_EQ(g, some_gradient());
}

TEST(NsniGradientReturn, YieldingRemovesTheComponentAlongTheDeviatorAndScalesTheRest) {
  const Mat3 sigma = some_stress();
  const Mat3 s = deviator(sigma);
  for (double beta : {0.7, 0.25, 0.0}) {
    Mat3 g = some_gradient();
    return_stress_gradient(g, sigma, Moduli{1e10, 1e10, beta, 0.0, false});
    // To first order the stress sigma + dx g stays on the strength surface: s : dev(g) = 0.
    EXPECT_NEAR(contract(s, deviator(g)), 0.0, 1e-9 * s.norm() * some_gradient().norm());
    // The pressure gradient is kept, the deviatoric part orthogonal to s is scaled by beta.
    EXPECT_NEAR(g.trace(), some_gradient().trace(), 1e-9 * MPa);
    const Mat3 d0 = deviator(some_gradient());
    const Mat3 orth = d0 - (contract(s, d0) / contract(s, s)) * s;
    EXPECT_LT((deviator(g) - beta * orth).norm(), 1e-9 * d0.norm()) << beta;
  }
}

TEST(NsniGradientReturn, APressureOnAFixedLimitHasNoGradient) {
  Mat3 g = some_gradient();
  return_stress_gradient(g, some_stress(), Moduli{1e10, 1e10, 1.0, 0.0, true});
  EXPECT_NEAR(g.trace(), 0.0, 1e-9 * MPa);
  EXPECT_LT((deviator(g) - deviator(some_gradient())).norm(), 1e-9 * MPa);
}

TEST(NsniGradientReturn, AfcReportsItsReturnFactorAndTheTensileCutoff) {
  const AfcParams p = load_afc_params(UHPC_DATA_DIR "/afc_uhpc.json", UHPC_DATA_DIR "/sdel_paper.json");
  const AfcMaterial law(p);
  PointDriver<AfcMaterial> pt(law, 0.003);
  Mat3 shear = Mat3::Zero();
  shear(0, 1) = shear(1, 0) = 0.5e-5;
  pt.strain_step(shear, 1e-5);  // elastic
  EXPECT_EQ(law.moduli(pt.state()).deviatoric_return, 1.0);
  EXPECT_FALSE(law.moduli(pt.state()).pressure_fixed);
  for (int i = 0; i < 600; ++i) pt.strain_step(shear, 1e-5);  // far past yield at P = 0
  const AfcMaterial::State& st = pt.state();
  ASSERT_GT(st.plastic_strain, 0.0);
  // The last step's trial deviator exceeded S by one elastic increment: S / q_trial = S / (S + 3G dg/2 ...).
  const double S = von_mises(st.effective_stress);  // the strength bounds the effective stress
  const double q_trial = S + 2.0 * p.shear_modulus_Pa * std::sqrt(1.5 * 2.0) * 0.5e-5;
  EXPECT_NEAR(law.moduli(st).deviatoric_return, S / q_trial, 1e-9);
  // Expansion past the tensile cutoff: the pressure is held at -Tmax (1 - d+) (the default coupling).
  PointDriver<AfcMaterial> open(law, 0.003);
  open.volumetric_step_to(-1e-3, 1e-6);
  EXPECT_TRUE(law.moduli(open.state()).pressure_fixed);
  EXPECT_NEAR(pressure_of(open.state().stress), -p.Tmax_Pa * (1.0 - open.state().d_plus), 1e-6 * p.Tmax_Pa);
  EXPECT_EQ(law.moduli(open.state()).tension_factor, 1.0);
  // With the split the cutoff is the undamaged -Tmax on the effective stress; d+ acts through the split.
  AfcParams split = p;
  split.options.tensile_degradation = TensileDegradation::Split;
  const AfcMaterial split_law(split);
  PointDriver<AfcMaterial> split_open(split_law, 0.003);
  split_open.volumetric_step_to(-1e-3, 1e-6);
  EXPECT_TRUE(split_law.moduli(split_open.state()).pressure_fixed);
  EXPECT_NEAR(pressure_of(split_open.state().effective_stress), -p.Tmax_Pa, 1e-6 * p.Tmax_Pa);
  EXPECT_EQ(split_law.moduli(split_open.state()).tension_factor, 1.0 - split_open.state().d_plus);
}

// The returned gradient is the derivative of the law's own update: for a state on the strength surface,
// the stress change caused by a perturbation of the strain increment, (s(de + eps delta) - s(de)) / eps,
// equals the elastic trial change 2G dev(delta) (+ K tr(delta) I) returned by return_stress_gradient.
Mat3 perturbation() {
  Mat3 delta;
  delta << 0.3, -0.2, 0.7,  //
      -0.2, -0.5, 0.1,      //
      0.7, 0.1, 0.4;
  return delta;
}

template <class Law>
void expect_return_is_the_derivative_of_the_update(const Law& law, typename Law::State at_yield, const Mat3& de,
                                                   const Mat3& delta, double dt, double K, double G) {
  const double eps = 1e-4 * de.norm();
  MaterialStep a, b;
  a.strain_increment = de;
  b.strain_increment = de + eps * delta;
  a.dt_s = b.dt_s = dt;
  a.spacing_m = b.spacing_m = 0.003;
  a.density_ratio = std::exp(-de.trace());
  b.density_ratio = std::exp(-(de + eps * delta).trace());
  typename Law::State sa = at_yield, sb = at_yield;
  law.update(sa, a);
  law.update(sb, b);
  ASSERT_LT(law.moduli(sa).deviatoric_return, 1.0) << "the step must yield";
  const Mat3 fd = (sb.stress - sa.stress) / eps;
  Mat3 g = K * delta.trace() * Mat3::Identity() + 2.0 * G * deviator(delta);
  return_stress_gradient(g, sa.stress, law.moduli(sa));
  EXPECT_LT((deviator(fd) - deviator(g)).norm(), 1e-5 * (2.0 * G * delta.norm()));
}

TEST(NsniGradientReturn, IsTheLinearisedReturnOfJ2WithHardening) {
  const J2Params p{7850.0, 160e9, 80e9, 400e6, 2e9};
  const J2Material law(p);
  PointDriver<J2Material> pt(law, 0.003);
  Mat3 shear = Mat3::Zero();
  shear(0, 1) = shear(1, 0) = 1e-4;
  for (int i = 0; i < 40; ++i) pt.strain_step(shear, 1e-6);  // plastic
  ASSERT_GT(pt.state().plastic_strain, 0.0);
  Mat3 de = shear;
  de(0, 0) = 2e-5;
  de(2, 2) = -1e-5;
  expect_return_is_the_derivative_of_the_update(law, pt.state(), de, perturbation(), 1e-6, p.bulk_modulus_Pa,
                                                p.shear_modulus_Pa);
  EXPECT_NEAR(law.moduli(pt.state()).along_deviator_return, 2e9 / (3 * 80e9 + 2e9), 1e-15);
}

TEST(NsniGradientReturn, IsTheLinearisedReturnOfAfcAtFixedPressureAndRate) {
  // Isochoric perturbations at a compressed state, d+ off and a rate below the reference: P, the branch
  // of the strength and F are the same on both sides, so S is fixed and the return is exact. (The
  // change of S with a pressure gradient is what the return neglects.)
  AfcParams p = load_afc_params(UHPC_DATA_DIR "/afc_uhpc.json", UHPC_DATA_DIR "/sdel_paper.json");
  p.options.tensile_damage = TensileDamage::Off;
  const AfcMaterial law(p);
  PointDriver<AfcMaterial> pt(law, 0.003);
  const double dt = 10.0;  // rate far below 1e-4 1/s: F = 1
  pt.volumetric_step_to(0.005, dt);
  Mat3 shear = Mat3::Zero();
  shear(0, 1) = shear(1, 0) = 0.5e-4;
  for (int i = 0; i < 200; ++i) pt.strain_step(shear, dt);
  ASSERT_GT(pt.state().plastic_strain, 0.0);
  ASSERT_GT(pressure_of(pt.state().stress), 0.0);
  Mat3 de = shear;
  de(0, 0) = 1e-6;
  de(1, 1) = -1e-6;
  const Mat3 delta = deviator(perturbation());
  expect_return_is_the_derivative_of_the_update(law, pt.state(), de, delta, dt, 0.0, p.shear_modulus_Pa);
}

// The AFC law's update of `state` (density ratio `density_ratio`) with the strain increment de and with
// de + eps delta, quasi-statically (dt 1 s).
std::pair<AfcMaterial::State, AfcMaterial::State> perturbed_updates(const AfcMaterial& law, const AfcMaterial::State& state,
                                                                    double density_ratio, const Mat3& de,
                                                                    const Mat3& delta, double eps) {
  MaterialStep a, b;
  a.strain_increment = de;
  b.strain_increment = de + eps * delta;
  a.dt_s = b.dt_s = 1.0;
  a.spacing_m = b.spacing_m = 0.003;
  a.density_ratio = density_ratio * std::exp(-de.trace());
  b.density_ratio = density_ratio * std::exp(-b.strain_increment.trace());
  AfcMaterial::State sa = state, sb = state;
  law.update(sa, a);
  law.update(sb, b);
  return {sa, sb};
}

// In crushing the gradient's pressure follows the hydrostat's tangent: the mean stress the law's update
// gives a perturbed volumetric increment, (sigma_m(de + eps delta) - sigma_m(de)) / eps, equals
// K tr(delta) with K = Moduli::bulk_Pa, while loading on the crushing curve (its slope, about a third of
// K_e) and while unloading below it (K_u).
void expect_bulk_is_the_derivative_of_the_pressure(const AfcMaterial& law, const AfcMaterial::State& state,
                                                   double density_ratio, double dmu) {
  const Mat3 de = -std::log((1.0 + dmu) / (1.0 + (density_ratio - 1.0))) / 3.0 * Mat3::Identity();
  const Mat3 delta = -1e-3 * Mat3::Identity();  // a little more compression
  const double eps = 1e-4 * de.norm();
  const auto [sa, sb] = perturbed_updates(law, state, density_ratio, de, delta, eps);
  const double fd = (sb.stress.trace() - sa.stress.trace()) / 3.0 / eps;
  const double K = law.moduli(sa).bulk_Pa;
  EXPECT_NEAR(fd, K * delta.trace(), 1e-4 * K * std::fabs(delta.trace()));
}

TEST(NsniGradientReturn, AfcBulkModulusIsTheHydrostatTangentInCrushing) {
  const AfcParams p = load_afc_params(UHPC_DATA_DIR "/afc_uhpc.json", UHPC_DATA_DIR "/sdel_paper.json");
  const AfcMaterial law(p);
  PointDriver<AfcMaterial> pt(law, 0.003);
  for (int i = 1; i <= 300; ++i) pt.volumetric_step_to(0.03 * i / 300.0, 1.0);
  ASSERT_GT(pt.state().mu_max, p.C7);
  // Loading on the curve: the crushing slope, well below the unloading modulus the gradient used before.
  expect_bulk_is_the_derivative_of_the_pressure(law, pt.state(), pt.density_ratio(), 0.0301);
  AfcMaterial::State loading = pt.state();
  law.update(loading, MaterialStep{-std::log(1.0301 / 1.03) / 3.0 * Mat3::Identity(), 1.0, 1.0301, 0.003});
  EXPECT_LT(law.moduli(loading).bulk_Pa, 0.5 * law.hydrostat().unloading_modulus(0.0301));
  // Unloading below mu_max: K_u.
  pt.volumetric_step_to(0.028, 1.0);
  expect_bulk_is_the_derivative_of_the_pressure(law, pt.state(), pt.density_ratio(), 0.0279);
}

// Eq. 21's split: the gradient the forces use is the first-order image of the effective gradient
// through the split, (split(sigma_e(de + eps delta)) - split(sigma_e(de))) / eps, at a state whose
// history strain is not exceeded (d+ fixed) and with tensile and compressive principal stresses.
TEST(NsniGradientReturn, TheSplitOfTheGradientIsTheDerivativeOfTheSplitStress) {
  AfcParams p = load_afc_params(UHPC_DATA_DIR "/afc_uhpc.json", UHPC_DATA_DIR "/sdel_paper.json");
  p.options.tensile_degradation = TensileDegradation::Split;
  const AfcMaterial law(p);
  PointDriver<AfcMaterial> pt(law, 0.003);
  Mat3 stretch = Mat3::Zero();
  stretch(0, 0) = 2e-6;
  stretch(1, 1) = -1e-6;
  stretch(0, 1) = stretch(1, 0) = 4e-7;
  for (int i = 0; i < 180; ++i) pt.strain_step(stretch, 1.0);
  for (int i = 0; i < 20; ++i) pt.strain_step(-stretch, 1.0);  // below the history maximum: d+ fixed
  const AfcMaterial::State at = pt.state();
  ASSERT_GT(at.d_plus, 0.2);
  ASSERT_LT(at.d_plus, 0.95);
  const Mat3 de = -0.5 * stretch;
  const Mat3 delta = perturbation();
  const double eps = 1e-4 * de.norm();
  const auto [sa, sb] = perturbed_updates(law, at, pt.density_ratio(), de, delta, eps);
  ASSERT_EQ(sa.d_plus, at.d_plus);
  ASSERT_EQ(sb.d_plus, at.d_plus);
  ASSERT_EQ(law.moduli(sa).deviatoric_return, 1.0);  // elastic: the effective gradient is C : delta
  const double K = p.C6_Pa / p.C7, G = p.shear_modulus_Pa;
  const Mat3 fd_effective = (sb.effective_stress - sa.effective_stress) / eps;
  const Mat3 fd_nominal = (sb.stress - sa.stress) / eps;
  const Mat3 g = K * delta.trace() * Mat3::Identity() + 2.0 * G * deviator(delta);
  EXPECT_LT((fd_effective - g).norm(), 1e-4 * g.norm());
  const Moduli mod = law.moduli(sa);
  ASSERT_EQ(mod.tension_factor, 1.0 - at.d_plus);
  const Mat3 nominal = StressGradientReturn(law.effective_stress(sa), mod).nominal(fd_effective);
  EXPECT_LT((nominal - fd_nominal).norm(), 1e-4 * fd_nominal.norm());
  EXPECT_GT((fd_nominal - fd_effective).norm(), 0.1 * fd_nominal.norm());  // the split does act
}

}  // namespace
}  // namespace uhpc::macro
