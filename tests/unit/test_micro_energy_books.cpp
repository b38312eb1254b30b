// The energy books of the crack analysis (micro/analysis/energy_books.hpp): the trapezoid work is exact
// on linear branches, secant unloading returns the elastic work, the admissibility test flags exactly
// the energy created beyond the tolerance, and trial states can be booked and undone.
#include <gtest/gtest.h>

#include "energy_books.hpp"

namespace uhpc::micro {
namespace {

TEST(microEnergyBooks, TheTrapezoidWorkOfALinearBranchIsExact) {
  EnergyBooks b(0.05);
  const double k = 3.0e10;  // N/m per m
  double work = 0.0;
  for (int i = 1; i <= 7; ++i) work = b.book_work(1e-6 * i, k * 1e-6 * i);
  EXPECT_NEAR(work, 0.5 * k * 49e-12, 1e-15 * k * 49e-12);
  EXPECT_DOUBLE_EQ(b.largest_work(), work);
}

TEST(microEnergyBooks, SecantUnloadingOfAnElasticStateReturnsItsWork) {
  EnergyBooks b(0.05);
  const double k = 2.0e10, lambda = 4e-6;
  b.book_work(0.5 * lambda, 0.5 * k * lambda);
  b.book_unload(lambda, k * lambda, 0.0);  // books the step to lambda, then unloads to zero
  EXPECT_NEAR(b.accepted_imbalance(), 0.0, 1e-12 * k * lambda * lambda);  // nothing dissipated, no net work
  // The reload starts at the origin: reloading to lambda books the elastic work again.
  EXPECT_NEAR(b.book_work(lambda, k * lambda), 0.5 * k * lambda * lambda, 1e-12 * k * lambda * lambda);
}

TEST(microEnergyBooks, OnlyEnergyCreatedBeyondTheToleranceOfTheLargestWorkIsExcess) {
  EnergyBooks b(0.05);
  b.book_work(1.0, 2.0);  // work 1
  b.accept(0.01);
  EXPECT_EQ(b.excess(0.01 + 0.049), 0.0);
  EXPECT_DOUBLE_EQ(b.excess(0.01 + 0.051), 0.051);
  EXPECT_EQ(b.excess(-1.0), 0.0);  // dissipating more than booked is not excess
}

TEST(microEnergyBooks, ATrialStateIsUndoneByRestoringTheWorkBooks) {
  EnergyBooks b(0.05);
  b.book_work(1.0, 1.0);
  const EnergyBooks::Work before = b.work_books();
  b.book_work(3.0, 5.0);
  b.note_operator_mismatch(0.5);
  b.restore(before);
  EXPECT_DOUBLE_EQ(b.largest_work(), 0.5);
  EXPECT_EQ(b.operator_mismatch(), 0.0);
  EXPECT_DOUBLE_EQ(b.book_work(2.0, 1.0), 1.5);  // continues from (1, 1)
}

TEST(microEnergyBooks, JumpsBookWhatTheyReleaseAndRoundOffAsNothing) {
  EnergyBooks b(0.05);
  b.book_jump(0.3);
  b.book_jump(-1e-18);
  EXPECT_DOUBLE_EQ(b.jump_dissipated(), 0.3);
  EXPECT_EQ(b.jumps(), 2u);
}

TEST(microEnergyBooks, TheOperatorMismatchIsRelativeToTheLargestWorkAndIgnoredBeforeAnyWork) {
  EnergyBooks b(0.05);
  b.note_operator_mismatch(1.0);
  EXPECT_EQ(b.operator_mismatch(), 0.0);
  b.book_work(2.0, 4.0);  // work 4
  b.note_operator_mismatch(1.0);
  b.note_operator_mismatch(0.5);
  EXPECT_DOUBLE_EQ(b.operator_mismatch(), 0.25);
}

}  // namespace
}  // namespace uhpc::micro
