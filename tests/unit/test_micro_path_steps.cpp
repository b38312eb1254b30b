// The path-following step sizes (micro/analysis/path_steps.hpp): each control halves its own increment
// on failure and gives up below its minimum, grows after easy steps up to its maximum, and a new
// control phase resets the opening holds only.
#include <gtest/gtest.h>

#include "path_steps.hpp"

namespace uhpc::micro {
namespace {

PathSteps shipped() { return PathSteps({0.02, 1e-6, 0.05}, {2e-6, 1e-11, 2e-5}, 1.5); }

TEST(microPathSteps, ACutHalvesTheIncrementAndFailsBelowTheMinimum) {
  PathSteps s = shipped();
  int cuts = 0;
  while (s.cut(Hold::Opening)) ++cuts;
  // 0.02 / 2^k >= 1e-6 for k <= 14 (0.02 / 2^14 = 1.22e-6); the 15th cut falls below.
  EXPECT_EQ(cuts, 14);
  EXPECT_LT(s.size(Hold::Opening), 1e-6);
  EXPECT_DOUBLE_EQ(s.size(Hold::Zone), 0.02);  // the other controls keep theirs
  EXPECT_DOUBLE_EQ(s.size(Hold::Lambda), 2e-6);
}

TEST(microPathSteps, EasyStepsGrowTheIncrementUpToTheMaximum) {
  PathSteps s = shipped();
  s.grow(Hold::Lambda);
  EXPECT_DOUBLE_EQ(s.size(Hold::Lambda), 3e-6);
  for (int k = 0; k < 20; ++k) s.grow(Hold::Lambda);
  EXPECT_DOUBLE_EQ(s.size(Hold::Lambda), 2e-5);
  s.grow(Hold::Zone);
  EXPECT_DOUBLE_EQ(s.size(Hold::Zone), 0.03);
}

TEST(microPathSteps, ANewPhaseResetsTheOpeningHoldsOnly) {
  PathSteps s = shipped();
  s.cut(Hold::Opening);
  s.grow(Hold::Zone);
  s.cut(Hold::Lambda);
  s.reset_openings();
  EXPECT_DOUBLE_EQ(s.size(Hold::Opening), 0.02);
  EXPECT_DOUBLE_EQ(s.size(Hold::Zone), 0.02);
  EXPECT_DOUBLE_EQ(s.size(Hold::Lambda), 1e-6);
}

}  // namespace
}  // namespace uhpc::micro
