#include "haptics/coherence/point_queues.h"

#include <algorithm>
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

TEST(PointQueues, SweepsVisitEveryPointOnceBeforeAnyTwice) {
  std::mt19937 random(7);
  PointQueues queues(5000, 3);
  std::set<std::uint32_t> members;
  for (std::uint32_t p = 0; p < 5000; ++p) {
    const int q = static_cast<int>(random() % 3);
    queues.insert(p, q);
    if (q == 1) members.insert(p);
  }
  std::vector<std::uint32_t> out(97);
  std::vector<std::uint32_t> seen;
  while (seen.size() < members.size()) {
    const std::uint32_t n = queues.takeSweep(1, 97, 0, out).taken;
    ASSERT_GT(n, 0u);
    seen.insert(seen.end(), out.begin(), out.begin() + n);
  }
  seen.resize(members.size());
  EXPECT_EQ(std::set<std::uint32_t>(seen.begin(), seen.end()), members);
  for (std::uint32_t p : seen) EXPECT_EQ(queues.queueOf(p), 1);
}

TEST(PointQueues, ASweepNeverReturnsAPointTwice) {
  PointQueues queues(100, 1);
  for (std::uint32_t p : {5u, 50u, 99u}) queues.insert(p, 0);
  std::vector<std::uint32_t> out(10);
  EXPECT_EQ(queues.takeSweep(0, 10, 0, out).taken, 3u);
  std::sort(out.begin(), out.begin() + 3);
  EXPECT_EQ(out[0], 5u);
  EXPECT_EQ(out[1], 50u);
  EXPECT_EQ(out[2], 99u);
}

TEST(PointQueues, ASweepCoversItsIndicesWhateverJoinsTheQueue) {
  // points join ahead of the cursor all the time; a sweep by indices still reaches a point
  // that joined before the cursor has moved a full circle
  std::mt19937 random(3);
  constexpr std::uint32_t kPoints = 4096;
  PointQueues queues(kPoints, 2);
  queues.assignAll(0);
  std::vector<std::uint32_t> out(kPoints);
  std::vector<std::int64_t> waitedIndices(kPoints, -1);  // since joining queue 1; −1: not in it
  for (int frame = 0; frame < 2000; ++frame) {
    for (int k = 0; k < 40; ++k) {  // join
      const auto p = static_cast<std::uint32_t>(random() % kPoints);
      if (queues.queueOf(p) == 0) {
        queues.move(p, 0, 1);
        waitedIndices[p] = 0;
      }
    }
    const PointQueues::Sweep sweep = queues.takeSweep(1, 1, 300, out);
    EXPECT_GE(sweep.coveredIndices, 300u);
    for (std::uint32_t i = 0; i < sweep.taken; ++i) {
      queues.move(out[i], 1, 0);
      waitedIndices[out[i]] = -1;
    }
    for (std::int64_t& w : waitedIndices) {
      if (w >= 0) {
        w += static_cast<std::int64_t>(sweep.coveredIndices);
        ASSERT_LT(w, kPoints) << "a point waited a full circle";
      }
    }
  }
}

}  // namespace
}  // namespace voxhap
