#include "haptics/runtime/frame_clock.h"

#include <vector>

#include <gtest/gtest.h>

#include "support/allocation_counter.h"

namespace voxhap {
namespace {

constexpr std::int64_t kPeriodNs = 1'000'000;
constexpr std::int64_t kSpinNs = 100'000;

/// Time that passes only when asked: each reading of the clock takes kReadNs, a sleep
/// wakes exactly at its deadline (or, when told, once early as after a signal), and a
/// test moves it on to stand for a frame's work or a stall.
class FakeTime final : public TimeSource {
public:
  static constexpr std::int64_t kReadNs = 1'000;

  std::int64_t nowNs() noexcept override {
    const std::int64_t t = nowNs_;
    nowNs_ += kReadNs;
    ++reads;
    return t;
  }
  void sleepUntilNs(std::int64_t deadlineNs) noexcept override {
    sleeps.push_back(deadlineNs);
    if (wakeEarlyOnce) {
      wakeEarlyOnce = false;
      nowNs_ += (deadlineNs - nowNs_) / 2;
      return;
    }
    nowNs_ = std::max(nowNs_, deadlineNs);
  }
  void advance(std::int64_t ns) { nowNs_ += ns; }

  std::vector<std::int64_t> sleeps;  ///< every deadline a sleep was asked for
  int reads = 0;
  bool wakeEarlyOnce = false;

private:
  std::int64_t nowNs_ = 5'000'000'000;
};

TEST(AdvanceDeadline, KeepsTheGridUpToOneWholePeriodLate) {
  const std::int64_t d = 7'000'000;
  for (const std::int64_t late : {std::int64_t{0}, std::int64_t{1}, kPeriodNs / 2, kPeriodNs}) {
    const DeadlineAdvance next = advanceDeadline(d, d + late, kPeriodNs);
    EXPECT_EQ(next.nextDeadlineNs, d + kPeriodNs) << late << " ns late";
    EXPECT_EQ(next.skippedPeriods, 0u) << late << " ns late";
  }
}

TEST(AdvanceDeadline, AfterAStallResyncsToNowAndCountsTheWholePeriodsMissed) {
  const std::int64_t d = 7'000'000;
  const struct {
    std::int64_t lateNs;
    std::uint64_t skipped;
  } cases[] = {{kPeriodNs + 1, 1},
               {kPeriodNs * 3 / 2, 1},
               {2 * kPeriodNs, 2},
               {3 * kPeriodNs + 200'000, 3},
               {1000 * kPeriodNs, 1000}};
  for (const auto& c : cases) {
    const DeadlineAdvance next = advanceDeadline(d, d + c.lateNs, kPeriodNs);
    EXPECT_EQ(next.nextDeadlineNs, d + c.lateNs + kPeriodNs) << c.lateNs << " ns late";
    EXPECT_EQ(next.skippedPeriods, c.skipped) << c.lateNs << " ns late";
  }
}

TEST(FrameClock, SleepsToShortlyBeforeEachDeadlineThenSpinsToIt) {
  FakeTime time;
  FrameClock clock(kPeriodNs, kSpinNs, time);
  const FrameTick first = clock.waitForFrame();
  EXPECT_TRUE(time.sleeps.empty()) << "the first frame waited";
  EXPECT_EQ(first.sincePreviousNs, 0);
  EXPECT_EQ(first.deadlineNs, first.beganNs);
  for (int frame = 1; frame <= 5; ++frame) {
    time.advance(300'000);  // the frame's work
    const int readsBefore = time.reads;
    const FrameTick tick = clock.waitForFrame();
    const std::int64_t deadline = first.deadlineNs + frame * kPeriodNs;
    EXPECT_EQ(tick.deadlineNs, deadline);
    ASSERT_EQ(time.sleeps.size(), static_cast<std::size_t>(frame));
    EXPECT_EQ(time.sleeps.back(), deadline - kSpinNs);
    EXPECT_GE(tick.beganNs, deadline);
    EXPECT_LT(tick.beganNs, deadline + FakeTime::kReadNs);
    EXPECT_GT(time.reads - readsBefore, kSpinNs / FakeTime::kReadNs / 2) << "it did not spin";
    EXPECT_EQ(tick.skippedPeriods, 0u);
  }
  EXPECT_EQ(clock.skippedPeriods(), 0u);
}

TEST(FrameClock, AfterAStallTheNextFrameBeginsAtOnceAndTheOneAfterAPeriodLater) {
  FakeTime time;
  FrameClock clock(kPeriodNs, kSpinNs, time);
  clock.waitForFrame();
  const FrameTick before = clock.waitForFrame();
  time.advance(3 * kPeriodNs + 500'000);  // a frame that took 3.5 periods
  const std::size_t sleepsBefore = time.sleeps.size();
  const FrameTick late = clock.waitForFrame();
  EXPECT_EQ(time.sleeps.size(), sleepsBefore) << "a late frame slept";
  EXPECT_EQ(late.deadlineNs, before.deadlineNs + kPeriodNs);
  // 2.5 periods past its deadline: the frames due one and two periods later never run
  EXPECT_EQ(late.skippedPeriods, 2u);
  EXPECT_EQ(clock.skippedPeriods(), 2u);
  EXPECT_EQ(clock.nextDeadlineNs(), late.beganNs + kPeriodNs);
  // no catching up: the frames after it are a period apart, on the new grid
  for (int frame = 1; frame <= 3; ++frame) {
    const FrameTick tick = clock.waitForFrame();
    EXPECT_EQ(tick.deadlineNs, late.beganNs + frame * kPeriodNs);
    EXPECT_GE(tick.sincePreviousNs, kPeriodNs - FakeTime::kReadNs);
    EXPECT_EQ(tick.skippedPeriods, 0u);
  }
  EXPECT_EQ(clock.skippedPeriods(), 2u);
}

TEST(FrameClock, AFrameLateByLessThanAPeriodKeepsTheGrid) {
  FakeTime time;
  FrameClock clock(kPeriodNs, kSpinNs, time);
  const FrameTick first = clock.waitForFrame();
  time.advance(1'700'000);  // late for the next deadline by 0.7 periods
  const FrameTick late = clock.waitForFrame();
  EXPECT_EQ(late.deadlineNs, first.deadlineNs + kPeriodNs);
  EXPECT_EQ(late.skippedPeriods, 0u);
  const FrameTick next = clock.waitForFrame();
  EXPECT_EQ(next.deadlineNs, first.deadlineNs + 2 * kPeriodNs);
  EXPECT_LT(next.sincePreviousNs, kPeriodNs) << "the grid moved";
}

TEST(FrameClock, ASleepCutShortBySignalSleepsAgainToTheSameTime) {
  FakeTime time;
  FrameClock clock(kPeriodNs, kSpinNs, time);
  const FrameTick first = clock.waitForFrame();
  time.wakeEarlyOnce = true;
  const FrameTick tick = clock.waitForFrame();
  ASSERT_EQ(time.sleeps.size(), 2u);
  EXPECT_EQ(time.sleeps[0], first.deadlineNs + kPeriodNs - kSpinNs);
  EXPECT_EQ(time.sleeps[1], time.sleeps[0]);
  EXPECT_GE(tick.beganNs, tick.deadlineNs);
}

TEST(FrameClock, WaitingAllocatesNothing) {
  FakeTime time;
  time.sleeps.reserve(100);
  FrameClock clock(kPeriodNs, kSpinNs, time);
  const test::AllocationCounter allocations;
  for (int i = 0; i < 50; ++i) clock.waitForFrame();
  EXPECT_EQ(allocations.count(), 0u);
}

TEST(FrameClock, OnTheMonotonicClockNoFrameBeginsBeforeItsDeadline) {
  FrameClock clock(kPeriodNs);
  std::int64_t previous = 0;
  for (int i = 0; i < 3; ++i) {
    const FrameTick tick = clock.waitForFrame();
    EXPECT_GE(tick.beganNs, tick.deadlineNs);
    EXPECT_GT(tick.deadlineNs, previous);
    previous = tick.deadlineNs;
  }
}

}  // namespace
}  // namespace voxhap
