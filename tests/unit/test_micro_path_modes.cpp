// The path's two modes as state machines (micro/analysis/path_modes.hpp): each transition of the
// reload after a growth unload and of the process-zone control, with the numbers it carries.
#include <gtest/gtest.h>

#include "path_modes.hpp"

namespace uhpc::micro {
namespace {

using Phase = ReloadPath::Phase;

TEST(MicroPathModes, TheReloadGoesLinearStepThenSecantThenLoading) {
  ReloadPath r;
  EXPECT_EQ(r.phase(), Phase::Loading);
  EXPECT_EQ(r.separation_scale(2e-4), 1.0);
  r.unloaded(4e-4, 0.003, 0.5);  // unloaded at e_u = 4e-4 of a 3 mm cell, 0.5 J/m dissipated
  EXPECT_EQ(r.phase(), Phase::LinearStep);
  EXPECT_EQ(r.unloads(), 1u);
  EXPECT_DOUBLE_EQ(r.target_lambda(), 4e-4 * 0.003);
  EXPECT_DOUBLE_EQ(r.separation_scale(2e-4), 0.5);  // on the secant: half the unloading strain, half the stress
  r.linear_step_taken();
  EXPECT_EQ(r.phase(), Phase::OnSecant);
  EXPECT_EQ(r.target_lambda(), 0.0);
  r.dissipated(0.5 + 1e-12, 1e-9);  // within round-off: still on the secant
  EXPECT_EQ(r.phase(), Phase::OnSecant);
  r.dissipated(0.5 + 1e-6, 1e-9);
  EXPECT_EQ(r.phase(), Phase::Loading);
  EXPECT_EQ(r.separation_scale(2e-4), 1.0);
}

TEST(MicroPathModes, AReloadStepIsHalvedUntilBelowASixtyFourthThenOrdinarySteps) {
  ReloadPath r;
  r.unloaded(4e-4, 0.003, 0.0);
  const double full = 4e-4 * 0.003;
  for (int k = 1; k <= 6; ++k) {  // 1/2 ... 1/64: still a linear step
    r.halve();
    ASSERT_EQ(r.phase(), Phase::LinearStep) << k;
    EXPECT_DOUBLE_EQ(r.target_lambda(), full / (1 << k));
  }
  r.halve();  // 1/128
  EXPECT_EQ(r.phase(), Phase::OnSecant);
  EXPECT_EQ(r.target_lambda(), 0.0);
  // A state accepted while the linear step is still pending (a jump right after the unload) that has
  // dissipated again ends the reload: the cell is on its envelope.
  ReloadPath s;
  s.unloaded(4e-4, 0.003, 0.0);
  s.dissipated(1.0, 1e-9);
  EXPECT_EQ(s.phase(), Phase::Loading);
  EXPECT_EQ(s.target_lambda(), 0.0);
  EXPECT_EQ(s.separation_scale(2e-4), 1.0);
  s.unloaded(3e-4, 0.003, 0.0);  // a second unload counts
  EXPECT_EQ(s.unloads(), 2u);
}

TEST(MicroPathModes, AnUnloadAtNoTensionHasNoLinearStep) {
  // Unloaded from a state at e_u <= 0 (a re-equilibration that had landed in compression): there is no
  // linear step to e_u, only the secant, whose separation test stays the unload's.
  for (const double e_u : {0.0, -2.3e-4}) {
    ReloadPath r;
    r.unloaded(e_u, 0.003, 0.2);
    EXPECT_EQ(r.phase(), Phase::OnSecant) << e_u;
    EXPECT_EQ(r.target_lambda(), 0.0) << e_u;
    EXPECT_EQ(r.unloads(), 1u);
  }
}

TEST(MicroPathModes, TheOpeningFoldsToTheProcessZoneAndBack) {
  OpeningMode m(false);
  EXPECT_EQ(m.mode(), OpeningMode::Mode::Global);
  m.folded("Newton did not converge");
  EXPECT_EQ(m.mode(), OpeningMode::Mode::ProcessZone);
  EXPECT_EQ(m.fold_reason(), "Newton did not converge");
  m.back_to_global();
  EXPECT_EQ(m.mode(), OpeningMode::Mode::Global);
  // The verification hook: the process zone at every step, for good.
  OpeningMode always(true);
  EXPECT_EQ(always.mode(), OpeningMode::Mode::ProcessZone);
  always.back_to_global();
  EXPECT_EQ(always.mode(), OpeningMode::Mode::ProcessZone);
}

}  // namespace
}  // namespace uhpc::micro
