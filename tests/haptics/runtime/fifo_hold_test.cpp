#include "haptics/runtime/fifo_hold.h"

#include <gtest/gtest.h>

namespace voxhap {
namespace {

using Change = FifoHold::Change;

/// `frames` frames alike; the change the last one brought.
Change run(FifoHold& hold, std::uint32_t frames, bool beganLate, bool quick) {
  Change last = Change::None;
  for (std::uint32_t i = 0; i < frames; ++i) {
    last = hold.afterFrame(beganLate, quick);
    if (i + 1 < frames) {
      EXPECT_EQ(last, Change::None) << "frame " << i;
    }
  }
  return last;
}

TEST(FifoHold, ItIsGivenUpAfterFiftyLateFramesInARowAndNotBefore) {
  FifoHold hold;
  EXPECT_TRUE(hold.held());
  EXPECT_EQ(run(hold, FifoHold::kLateFramesToGiveUp - 1, true, false), Change::None);
  EXPECT_EQ(hold.afterFrame(false, false), Change::None);  // one on time: the count starts again
  EXPECT_EQ(run(hold, FifoHold::kLateFramesToGiveUp - 1, true, false), Change::None);
  EXPECT_TRUE(hold.held());
  EXPECT_EQ(hold.givenUp(), 0u);
  EXPECT_EQ(hold.afterFrame(true, false), Change::GiveUp);
  EXPECT_FALSE(hold.held());
  EXPECT_EQ(hold.givenUp(), 1u);
}

TEST(FifoHold, ItIsTakenAgainAfterASecondOfQuickFramesInARow) {
  FifoHold hold;
  ASSERT_EQ(run(hold, FifoHold::kLateFramesToGiveUp, true, false), Change::GiveUp);
  // late or not does not matter without the priority; a slow frame starts the count again
  EXPECT_EQ(run(hold, FifoHold::kQuickFramesToTakeAgain - 1, true, true), Change::None);
  EXPECT_EQ(hold.afterFrame(false, false), Change::None);
  EXPECT_FALSE(hold.held());
  EXPECT_EQ(run(hold, FifoHold::kQuickFramesToTakeAgain, false, true), Change::TakeAgain);
  EXPECT_TRUE(hold.held());
  // and given up again as before
  EXPECT_EQ(run(hold, FifoHold::kLateFramesToGiveUp, true, true), Change::GiveUp);
  EXPECT_EQ(hold.givenUp(), 2u);
}

TEST(FifoHold, ARefusalToTakeItAgainLeavesTheThreadWithoutItUntilTheNextSecond) {
  FifoHold hold;
  ASSERT_EQ(run(hold, FifoHold::kLateFramesToGiveUp, true, false), Change::GiveUp);
  ASSERT_EQ(run(hold, FifoHold::kQuickFramesToTakeAgain, false, true), Change::TakeAgain);
  hold.refused();
  EXPECT_FALSE(hold.held());
  EXPECT_EQ(run(hold, FifoHold::kQuickFramesToTakeAgain, false, true), Change::TakeAgain);
  EXPECT_EQ(hold.givenUp(), 1u);  // a refusal is not a giving up
}

}  // namespace
}  // namespace voxhap
