// Material laws of the 3D code at a single material point, against closed-form responses.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "materials/elastic.hpp"
#include "materials/j2_plasticity.hpp"

namespace m = uhpc::macro;

namespace {

constexpr double K = 160e9, G = 80e9, rho = 7850.0;

m::MaterialStep uniaxial_strain(double de) {
  m::MaterialStep step;
  step.strain_increment(0, 0) = de;
  step.dt_s = 1e-8;
  return step;
}

m::MaterialStep simple_shear(double dgamma) {
  m::MaterialStep step;
  step.strain_increment(0, 1) = step.strain_increment(1, 0) = 0.5 * dgamma;
  step.dt_s = 1e-8;
  return step;
}

TEST(ElasticMaterial, UniaxialStrainGivesConstrainedModulusAndLateralStress) {
  const m::ElasticMaterial mat({rho, K, G});
  m::ElasticMaterial::State s;
  for (int i = 0; i < 100; ++i) mat.update(s, uniaxial_strain(1e-5));
  const double e = 1e-3;
  EXPECT_NEAR(s.stress(0, 0), (K + 4.0 / 3.0 * G) * e, 1e-6 * K * e);
  EXPECT_NEAR(s.stress(1, 1), (K - 2.0 / 3.0 * G) * e, 1e-6 * K * e);
  EXPECT_NEAR(s.stress(2, 2), s.stress(1, 1), 1e-9 * K * e);
  EXPECT_EQ(s.stress(0, 1), 0.0);
}

TEST(ElasticMaterial, WaveSpeedFollowsTheCurrentDensity) {
  const m::ElasticMaterial mat({rho, K, G});
  const double c0 = std::sqrt((K + 4.0 / 3.0 * G) / rho);
  EXPECT_DOUBLE_EQ(mat.wave_speed({}, 1.0), c0);
  EXPECT_DOUBLE_EQ(mat.wave_speed({}, 1.21), c0 / 1.1);
  EXPECT_THROW(m::ElasticMaterial({rho, -1.0, G}), std::invalid_argument);
}

class J2 : public ::testing::Test {
 protected:
  const double sy = 400e6, H = 2e9;
  const m::J2Material mat{{rho, K, G, 400e6, 2e9}};
};

TEST_F(J2, SimpleShearFollowsTheClosedForm) {
  // tau = G gamma up to tau_y = sigma_y / sqrt(3), then d tau / d gamma = G H / (3G + H).
  m::J2Material::State s;
  const double dg = 1e-5, gamma_y = sy / std::sqrt(3.0) / G;
  double gamma = 0.0;
  for (int i = 0; i < 2000; ++i) {
    mat.update(s, simple_shear(dg));
    gamma += dg;
    const double tau = gamma <= gamma_y ? G * gamma : sy / std::sqrt(3.0) + G * H / (3 * G + H) * (gamma - gamma_y);
    ASSERT_NEAR(s.stress(0, 1), tau, 1e-9 * sy) << "gamma " << gamma;
  }
  EXPECT_NEAR(uhpc::macro::pressure_of(s.stress), 0.0, 1e-9 * sy);
}

TEST_F(J2, ReturnMappingLandsExactlyOnTheHardenedYieldSurface) {
  m::J2Material::State s;
  for (int i = 0; i < 50; ++i) mat.update(s, uniaxial_strain(1e-4));
  ASSERT_GT(s.plastic_strain, 0.0);
  EXPECT_NEAR(m::von_mises(s.stress), mat.yield_stress(s.plastic_strain), 1e-10 * sy);
}

TEST_F(J2, UniaxialStrainSplitsIntoElasticPressureAndYieldingDeviator) {
  // Pressure stays elastic (K eps); q = 2 G eps until sigma_y, then grows at 2 G H / (3G + H).
  m::J2Material::State s;
  const double de = 2e-5, e_y = sy / (2 * G);
  double e = 0.0;
  for (int i = 0; i < 500; ++i) {
    mat.update(s, uniaxial_strain(de));
    e += de;
    const double q = e <= e_y ? 2 * G * e : sy + 2 * G * H / (3 * G + H) * (e - e_y);
    ASSERT_NEAR(m::pressure_of(s.stress), -K * e, 1e-9 * K * e);
    ASSERT_NEAR(s.stress(0, 0) - s.stress(1, 1), q, 1e-9 * sy);
  }
}

TEST_F(J2, UnloadingIsElasticAndPlasticWorkIsTheAreaUnderTheYieldCurve) {
  m::J2Material::State s;
  for (int i = 0; i < 300; ++i) mat.update(s, simple_shear(1e-5));
  const double ep = s.plastic_strain, work = s.plastic_work;
  EXPECT_NEAR(work, sy * ep + 0.5 * H * ep * ep, 1e-9 * sy * ep);
  const double tau0 = s.stress(0, 1);
  mat.update(s, simple_shear(-1e-4));
  EXPECT_NEAR(s.stress(0, 1), tau0 - G * 1e-4, 1e-9 * sy);
  EXPECT_EQ(s.plastic_strain, ep);
  EXPECT_EQ(s.plastic_work, work);
}

TEST_F(J2, RejectsNonPhysicalParameters) {
  EXPECT_THROW(m::J2Material({rho, K, G, 0.0, H}), std::invalid_argument);
  EXPECT_THROW(m::J2Material({rho, K, G, sy, -1.0}), std::invalid_argument);
}

}  // namespace
