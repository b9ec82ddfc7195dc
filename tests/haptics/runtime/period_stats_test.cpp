#include "haptics/runtime/period_stats.h"

#include <cmath>
#include <type_traits>

#include <gtest/gtest.h>

#include "support/allocation_counter.h"

namespace voxhap {
namespace {

constexpr std::int64_t kUs = 1'000;  // ns
constexpr std::int64_t kMs = 1'000'000;

/// 1000 durations: 1.5 µs, 2.5 µs, … 1000.5 µs, in a shuffled order.
PeriodStats thousandSteps() {
  PeriodStats stats(900 * kUs);
  for (std::int64_t i = 0; i < 1000; ++i) {
    const std::int64_t k = (i * 337) % 1000 + 1;  // 337 is prime to 1000: every k once
    stats.record(k * kUs + 500);
  }
  return stats;
}

TEST(PeriodStats, PercentilesAreTheNearestRankRoundedUpToItsBin) {
  const PeriodStats stats = thousandSteps();
  EXPECT_EQ(stats.count(), 1000u);
  EXPECT_EQ(stats.minNs(), 1 * kUs + 500);
  EXPECT_EQ(stats.maxNs(), 1000 * kUs + 500);
  EXPECT_DOUBLE_EQ(stats.meanNs(), 501 * kUs);
  // the 500th smallest is 500.5 µs, in the bin [500, 501) µs
  EXPECT_EQ(stats.percentileNs(0.5), 501 * kUs);
  EXPECT_EQ(stats.percentileNs(0.99), 991 * kUs);
  EXPECT_EQ(stats.percentileNs(0.999), 1000 * kUs);
  EXPECT_EQ(stats.percentileNs(0.0), 2 * kUs) << "the smallest sample's bin";
  EXPECT_EQ(stats.percentileNs(1.0), stats.maxNs()) << "a bin's edge above the maximum";
  // durations over 900 µs: 900.5 … 1000.5
  EXPECT_EQ(stats.overruns(), 101u);
  EXPECT_EQ(stats.overflow(), 0u);
}

TEST(PeriodStats, EqualDurationsGiveThemExactly) {
  PeriodStats stats(kMs);
  for (int i = 0; i < 10; ++i) stats.record(kMs + 250);
  EXPECT_EQ(stats.percentileNs(0.5), kMs + 250);
  EXPECT_EQ(stats.percentileNs(0.999), kMs + 250);
  EXPECT_EQ(stats.overruns(), 10u);
}

TEST(PeriodStats, StallsBeyondTheRangeCountInTheOverflowAndTheirPercentilesAreTheMaximum) {
  PeriodStats stats(1100 * kUs);
  for (int i = 0; i < 1000; ++i) stats.record(kMs);
  for (int i = 0; i < 3; ++i) stats.record(1500 * kUs);
  stats.record(7 * kMs);
  stats.record(12 * kMs);
  EXPECT_EQ(stats.count(), 1005u);
  EXPECT_EQ(stats.overruns(), 5u);
  EXPECT_EQ(stats.overflow(), 2u);
  EXPECT_EQ(stats.maxNs(), 12 * kMs);
  EXPECT_EQ(stats.percentileNs(0.99), kMs + kUs);    // rank 995 of 1005: a 1 ms period
  EXPECT_EQ(stats.percentileNs(0.998), 1501 * kUs);  // rank 1003
  EXPECT_EQ(stats.percentileNs(0.999), 12 * kMs);    // rank 1004, in the overflow
}

TEST(PeriodStats, SummaryAgreesWithTheSingleFigures) {
  const PeriodStats stats = thousandSteps();
  const PeriodSummary s = stats.summary();
  EXPECT_EQ(s.count, stats.count());
  EXPECT_EQ(s.overruns, stats.overruns());
  EXPECT_EQ(s.minNs, stats.minNs());
  EXPECT_EQ(s.p50Ns, stats.percentileNs(0.5));
  EXPECT_EQ(s.p99Ns, stats.percentileNs(0.99));
  EXPECT_EQ(s.p999Ns, stats.percentileNs(0.999));
  EXPECT_EQ(s.maxNs, stats.maxNs());
  EXPECT_EQ(s.meanNs, stats.meanNs());
  PeriodStats stalls(kMs);
  stalls.record(9 * kMs);
  EXPECT_EQ(stalls.summary().p50Ns, 9 * kMs);
  EXPECT_EQ(stalls.summary().p999Ns, 9 * kMs);
}

TEST(PeriodStats, EmptyStatsAreZeroAndANegativeDurationCountsAsZero) {
  PeriodStats stats(kMs);
  const PeriodSummary empty = stats.summary();
  EXPECT_EQ(empty.count, 0u);
  EXPECT_EQ(empty.minNs, 0);
  EXPECT_EQ(empty.p50Ns, 0);
  EXPECT_EQ(empty.maxNs, 0);
  EXPECT_EQ(empty.meanNs, 0.0);
  EXPECT_EQ(stats.percentileNs(0.5), 0);
  stats.record(-5 * kUs);
  EXPECT_EQ(stats.count(), 1u);
  EXPECT_EQ(stats.minNs(), 0);
  EXPECT_EQ(stats.maxNs(), 0);
  EXPECT_EQ(stats.percentileNs(0.5), 0);
}

TEST(PeriodStats, MergedHalvesEqualTheWholeAndACopyIsIndependent) {
  static_assert(std::is_trivially_copyable_v<PeriodStats>, "published by copying");
  PeriodStats low(900 * kUs);
  PeriodStats high(900 * kUs);
  for (std::int64_t k = 1; k <= 1000; ++k) (k % 2 ? low : high).record(k * kUs + 500);
  PeriodStats merged = low;
  merged.merge(high);
  const PeriodSummary a = merged.summary();
  const PeriodSummary b = thousandSteps().summary();
  EXPECT_EQ(a.count, b.count);
  EXPECT_EQ(a.overruns, b.overruns);
  EXPECT_EQ(a.minNs, b.minNs);
  EXPECT_EQ(a.p50Ns, b.p50Ns);
  EXPECT_EQ(a.p99Ns, b.p99Ns);
  EXPECT_EQ(a.p999Ns, b.p999Ns);
  EXPECT_EQ(a.maxNs, b.maxNs);
  EXPECT_EQ(a.meanNs, b.meanNs);
  EXPECT_EQ(low.count(), 500u) << "merging changed the copy it came from";
  PeriodStats empty(900 * kUs);
  empty.merge(low);
  EXPECT_EQ(empty.minNs(), low.minNs());
  merged.reset();
  EXPECT_EQ(merged.count(), 0u);
  EXPECT_EQ(merged.percentileNs(0.5), 0);
  EXPECT_EQ(merged.overrunNs(), 900 * kUs);
}

TEST(PeriodStats, RecordingAndSummingUpAllocateNothing) {
  PeriodStats stats(kMs);
  const test::AllocationCounter allocations;
  for (std::int64_t i = 0; i < 5000; ++i) stats.record(i * 997);
  const PeriodSummary s = stats.summary();
  EXPECT_EQ(allocations.count(), 0u);
  EXPECT_EQ(s.count, 5000u);
}

}  // namespace
}  // namespace voxhap
