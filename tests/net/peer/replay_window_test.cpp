#include "net/peer/replay_window.h"

#include <gtest/gtest.h>

namespace voxhap::net {
namespace {

using Verdict = ReplayWindow::Verdict;

TEST(ReplayWindow, EveryNumberIsNewOnceInAnyOrderWithinTheWindow) {
  ReplayWindow w;
  for (std::uint64_t s : {100u, 103u, 101u, 102u, 99u}) {
    ASSERT_EQ(w.check(s), Verdict::New) << s;
    w.accept(s);
    EXPECT_EQ(w.check(s), Verdict::Replayed) << s;
  }
  EXPECT_EQ(w.highest(), 103u);
  EXPECT_EQ(w.check(104), Verdict::New);
}

TEST(ReplayWindow, BelowTheWindowIsTooOldAndItsLowerEdgeIsStillKept) {
  ReplayWindow w;
  w.accept(5000);
  const std::uint64_t lowest = 5000 - ReplayWindow::kSize + 1;
  EXPECT_EQ(w.check(lowest), Verdict::New);
  EXPECT_EQ(w.check(lowest - 1), Verdict::TooOld);
  w.accept(lowest);
  EXPECT_EQ(w.check(lowest), Verdict::Replayed);
}

TEST(ReplayWindow, CheckAloneMovesNothing) {
  ReplayWindow w;
  w.accept(10);
  EXPECT_EQ(w.check(5000), Verdict::New);
  EXPECT_EQ(w.check(11), Verdict::New);  // the window did not slide to 5000
  EXPECT_EQ(w.highest(), 10u);
}

TEST(ReplayWindow, SlidingForgetsTheBitsOfNumbersThatLeftTheWindow) {
  ReplayWindow w;
  // numbers whose bits share slots with numbers a window later must read as new there
  for (std::uint64_t s = 0; s < ReplayWindow::kSize; s += 2) w.accept(s);
  w.accept(ReplayWindow::kSize + 1);  // slides by 3: the slots of kSize and kSize - 1 + 1 are reused
  EXPECT_EQ(w.check(ReplayWindow::kSize), Verdict::New);
  EXPECT_EQ(w.check(ReplayWindow::kSize - 2), Verdict::Replayed);
  EXPECT_EQ(w.check(ReplayWindow::kSize - 1), Verdict::New);
  EXPECT_EQ(w.check(0), Verdict::TooOld);
  EXPECT_EQ(w.check(2), Verdict::Replayed);
  // a jump of more than a window clears everything
  w.accept(10 * ReplayWindow::kSize);
  EXPECT_EQ(w.check(10 * ReplayWindow::kSize - 2), Verdict::New);
  EXPECT_EQ(w.check(10 * ReplayWindow::kSize), Verdict::Replayed);
}

TEST(ReplayWindow, AgreesWithASetOfEverythingTakenOverALongShuffledRun) {
  // sequence numbers 0..N-1 delivered up to 1500 late, some twice or more: the
  // window must take each exactly once, and refuse only numbers a window below the highest
  ReplayWindow w;
  std::vector<bool> taken(20000, false);
  std::uint64_t rng = 12345;
  auto next = [&rng] { return rng = rng * 6364136223846793005ull + 1442695040888963407ull; };
  std::uint64_t highest = 0;
  for (std::uint64_t i = 0; i < taken.size() * 2; ++i) {
    const std::uint64_t base = i / 2;
    const std::uint64_t s = base >= 1500 ? base - (next() >> 33) % 1500 : base;
    const Verdict v = w.check(s);
    if (taken[s]) {
      EXPECT_NE(v, Verdict::New) << s;
    } else if (highest >= s + ReplayWindow::kSize) {
      EXPECT_EQ(v, Verdict::TooOld) << s;
    } else {
      ASSERT_EQ(v, Verdict::New) << s;
      w.accept(s);
      taken[s] = true;
      highest = std::max(highest, s);
    }
  }
}

}  // namespace
}  // namespace voxhap::net
