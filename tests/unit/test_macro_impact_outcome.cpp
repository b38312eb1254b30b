// The outcome of a shot (macro/app/run_outputs.hpp, ImpactTracker::decide) on states set by hand: a
// 10 kg target 31.75 mm thick struck at 400 m/s by the 9.071 g sphere, which has given 0.99 of its
// momentum to the target. Each rule fires where its conditions hold and not where one of them fails.
#include <cmath>

#include <gtest/gtest.h>

#include "run_outputs.hpp"

namespace uhpc::macro {
namespace {

constexpr double kM = 9.071e-3, kV0 = 400.0, kTarget = 10.0, kT = 0.03175, kR = 0.00635;

struct Shot {
  RigidSphere sphere;
  EnergyLedger ledger;
  ImpactTracker tracker;
};

// The sphere at depth z (its centre), axial velocity v; the target has the rest of the initial momentum.
Shot shot(double z, double v) {
  Shot s;
  s.sphere.mass_kg = kM;
  s.sphere.radius_m = kR;
  s.sphere.x = {0.0, 0.0, z};
  s.sphere.v = {0.0, 0.0, v};
  s.ledger.kinetic_initial = 0.5 * kM * kV0 * kV0;
  s.ledger.kinetic_sphere = 0.5 * kM * v * v;
  s.ledger.momentum_sphere = {0.0, 0.0, kM * v};
  s.ledger.momentum = {0.0, 0.0, kM * kV0};  // conserved: the target holds kM (kV0 - v)
  s.tracker.thickness_m = kT;
  s.tracker.impact_velocity_m_s = kV0;
  s.tracker.target_mass_kg = kTarget;
  return s;
}

ImpactTracker decided(Shot s, std::int64_t in_contact, double worst_energy_error) {
  s.tracker.decide(s.sphere, s.ledger, in_contact, 1e-4, worst_energy_error);
  return s.tracker;
}

TEST(MacroImpactOutcome, AtRestRelativeToTheTargetIsEmbedded) {
  // The target's centre of mass moves at kM (kV0 - v) / kTarget = 0.36 m/s.
  const ImpactTracker slow = decided(shot(0.005, 0.3), 5, 0.0);
  EXPECT_EQ(slow.outcome, ImpactOutcome::Embedded);
  EXPECT_EQ(slow.embedded_by, EmbeddedBy::AtRest);
  EXPECT_EQ(slow.residual_velocity_m_s, 0.3);
  // Its centre not yet past the entry face: followed on (it may still rebound).
  EXPECT_FALSE(decided(shot(-0.001, 0.3), 5, 0.0).decided());
}

TEST(MacroImpactOutcome, BelowTheRunsEnergyResolutionIsEmbeddedAboveItIsNot) {
  // 7.5 m/s: kinetic energy (7.5 / 400)^2 = 3.5e-4 of the impact energy, faster than the target's 0.36.
  const Shot carried = shot(0.005, 7.5);
  const double share = std::pow(7.5 / kV0, 2);
  const ImpactTracker within = decided(carried, 3, 1.01 * share);
  EXPECT_EQ(within.outcome, ImpactOutcome::Embedded);
  EXPECT_EQ(within.embedded_by, EmbeddedBy::WithinEnergyResolution);
  EXPECT_EQ(within.residual_velocity_m_s, 7.5);
  EXPECT_FALSE(decided(carried, 3, 0.99 * share).decided());  // the run resolves it: still moving
  EXPECT_FALSE(decided(shot(-0.001, 7.5), 3, 1.01 * share).decided());  // not past the entry face
}

TEST(MacroImpactOutcome, PerforatedAndReboundedNeedTheSphereFree) {
  const ImpactTracker out = decided(shot(kT + 0.001, 50.0), 0, 0.0);
  EXPECT_EQ(out.outcome, ImpactOutcome::Perforated);
  EXPECT_EQ(out.embedded_by, EmbeddedBy::None);
  EXPECT_FALSE(decided(shot(kT + 0.001, 50.0), 2, 0.0).decided());  // still pushing particles
  EXPECT_EQ(decided(shot(-kR - 0.001, -10.0), 0, 0.0).outcome, ImpactOutcome::Rebounded);
  EXPECT_FALSE(decided(shot(-kR - 0.001, -10.0), 1, 0.0).decided());
}

}  // namespace
}  // namespace uhpc::macro
