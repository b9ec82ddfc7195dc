#include "haptics/coherence/point_queues.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include <gtest/gtest.h>

namespace voxhap {
namespace {

TEST(PointQueues, EveryPointIsInExactlyTheQueueItWasPutIn) {
  PointQueues queues(1000, 5);
  for (std::uint32_t p = 0; p < 1000; ++p) queues.insert(p, static_cast<int>(p % 5));
  for (int q = 0; q < 5; ++q) EXPECT_EQ(queues.count(q), 200u);
  queues.move(7, 2, 0);
  EXPECT_EQ(queues.queueOf(7), 0);
  EXPECT_EQ(queues.count(0), 201u);
  EXPECT_EQ(queues.count(2), 199u);
  queues.remove(7, 0);
  EXPECT_EQ(queues.queueOf(7), -1);
}

TEST(PointQueues, AssignAllPutsEveryPointInOneQueue) {
  for (const std::uint32_t n : {1u, 31u, 32u, 33u, 1024u, 1025u, 70000u}) {
    PointQueues queues(n, 3);
    queues.insert(0, 1);
    queues.assignAll(2);
    EXPECT_EQ(queues.count(2), n);
    EXPECT_EQ(queues.count(1), 0u);
    std::vector<std::uint32_t> out(n + 1);
    ASSERT_EQ(queues.takeAll(2, out), n);
    for (std::uint32_t p = 0; p < n; ++p) ASSERT_EQ(out[p], p);
    queues.remove(n - 1, 2);  // the last word and summary bits are consistent
    EXPECT_EQ(queues.takeAll(2, out), n - 1);
  }
}

TEST(PointQueues, TakeAllListsASparseQueueInIndexOrder) {
  // a few points spread over a large pointshell: the summary bits skip the empty words
  PointQueues queues(1 << 20, 2);
  const std::uint32_t points[] = {3, 31, 32, 1000, 65535, 65536, (1 << 20) - 1};
  for (std::uint32_t p : points) queues.insert(p, 1);
  std::vector<std::uint32_t> out(16);
  ASSERT_EQ(queues.takeAll(1, out), 7u);
  EXPECT_TRUE(std::equal(std::begin(points), std::end(points), out.begin()));
  EXPECT_EQ(queues.takeAll(0, out), 0u);
}

TEST(PointQueues, ARoundOfSweepsVisitsEveryPointOnce) {
  std::mt19937 random(7);
  PointQueues queues(5000, 3);
  std::set<std::uint32_t> members;
  for (std::uint32_t p = 0; p < 5000; ++p) {
    const int q = static_cast<int>(random() % 3);
    queues.insert(p, q);
    if (q == 1) members.insert(p);
  }
  std::vector<std::uint32_t> out(5000);
  std::vector<std::uint32_t> seen;
  std::uint32_t covered = 0;
  while (covered < queues.sweepBlockCount()) {
    const PointQueues::Sweep sweep =
        queues.takeSweep(1, std::min(7u, queues.sweepBlockCount() - covered), out);
    ASSERT_GT(sweep.coveredBlocks, 0u);
    covered += sweep.coveredBlocks;
    seen.insert(seen.end(), out.begin(), out.begin() + sweep.taken);
  }
  EXPECT_EQ(seen.size(), members.size());
  EXPECT_EQ(std::set<std::uint32_t>(seen.begin(), seen.end()), members);
}

TEST(PointQueues, ASweepNeverReturnsAPointTwice) {
  PointQueues queues(100, 1);
  for (std::uint32_t p : {5u, 50u, 99u}) queues.insert(p, 0);
  std::vector<std::uint32_t> out(10);
  EXPECT_EQ(queues.takeSweep(0, 1000, out).taken, 3u);
  std::sort(out.begin(), out.begin() + 3);
  EXPECT_EQ(out[0], 5u);
  EXPECT_EQ(out[1], 50u);
  EXPECT_EQ(out[2], 99u);
}

TEST(PointQueues, ASweepCoversItsBlocksWhateverJoinsTheQueue) {
  // points join ahead of the cursor all the time; a sweep by blocks still reaches a point
  // that joined before the cursor has moved a full round
  std::mt19937 random(3);
  constexpr std::uint32_t kPoints = 4096;
  PointQueues queues(kPoints, 2);
  queues.assignAll(0);
  std::vector<std::uint32_t> out(kPoints);
  std::vector<std::int64_t> waitedBlocks(kPoints, -1);  // since joining queue 1; −1: not in it
  for (int frame = 0; frame < 2000; ++frame) {
    for (int k = 0; k < 40; ++k) {  // join
      const auto p = static_cast<std::uint32_t>(random() % kPoints);
      if (queues.queueOf(p) == 0) {
        queues.move(p, 0, 1);
        waitedBlocks[p] = 0;
      }
    }
    const PointQueues::Sweep sweep = queues.takeSweep(1, 10, out);
    EXPECT_EQ(sweep.coveredBlocks, 10u);
    for (std::uint32_t i = 0; i < sweep.taken; ++i) {
      queues.move(out[i], 1, 0);
      waitedBlocks[out[i]] = -1;
    }
    for (std::int64_t& w : waitedBlocks) {
      if (w >= 0) {
        w += sweep.coveredBlocks;
        ASSERT_LT(w, queues.sweepBlockCount()) << "a point waited a full round";
      }
    }
  }
}

TEST(PointQueues, ASweepTakesACrowdedRunOfIndicesEvenlyRoundItsRound) {
  // the ball's mating face: 20,000 points of one queue in one run of a 96,032-point shell.
  // In index order a sweep of a twentieth of the round a frame would take nothing in most
  // frames and 4,800 in the rest.
  constexpr std::uint32_t kPoints = 96'032;
  PointQueues queues(kPoints, 2);
  for (std::uint32_t p = 40'000; p < 60'000; ++p) queues.insert(p, 1);
  std::vector<std::uint32_t> out(kPoints);
  const double perFrame = queues.sweepBlockCount() / 20.0;
  std::uint32_t least = kPoints, most = 0, covered = 0;
  for (int frame = 1; frame <= 20; ++frame) {
    const auto blocks = static_cast<std::uint32_t>(std::lround(frame * perFrame)) - covered;
    const PointQueues::Sweep sweep = queues.takeSweep(1, blocks, out);
    covered += sweep.coveredBlocks;
    least = std::min(least, sweep.taken);
    most = std::max(most, sweep.taken);
  }
  // 1,000 a frame on average
  EXPECT_GE(least, 800u);
  EXPECT_LE(most, 1200u);
}

TEST(PointQueues, PointsAheadCountsWhatTheNextSweepsTake) {
  std::mt19937 random(11);
  PointQueues queues(20'000, 3);
  for (std::uint32_t p = 0; p < 20'000; ++p)
    queues.insert(p, p > 5'000 && p < 9'000 ? 1 : static_cast<int>(random() % 3));
  std::vector<std::uint32_t> out(20'000);
  queues.takeSweep(1, 37, out);  // the cursor somewhere in the round
  const std::uint32_t marks[] = {0, 3, 3, 50, 120, queues.sweepBlockCount(), queues.sweepBlockCount() + 9};
  std::uint32_t ahead[std::size(marks)];
  queues.pointsAhead(1, marks, ahead);
  std::uint32_t taken = 0, covered = 0;
  for (std::size_t k = 0; k < std::size(marks); ++k) {
    const std::uint32_t blocks = std::min(marks[k], queues.sweepBlockCount()) - covered;
    const PointQueues::Sweep sweep = queues.takeSweep(1, blocks, out);
    taken += sweep.taken;
    covered += blocks;
    EXPECT_EQ(ahead[k], taken) << "mark " << marks[k];
  }
  EXPECT_EQ(ahead[std::size(marks) - 1], queues.count(1));
}

}  // namespace
}  // namespace voxhap
