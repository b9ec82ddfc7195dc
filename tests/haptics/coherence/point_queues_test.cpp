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

TEST(PointQueues, RoundRobinVisitsEveryPointOnceBeforeAnyTwice) {
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
    const std::uint32_t n = queues.takeRoundRobin(1, 97, out);
    ASSERT_GT(n, 0u);
    seen.insert(seen.end(), out.begin(), out.begin() + n);
  }
  seen.resize(members.size());
  EXPECT_EQ(std::set<std::uint32_t>(seen.begin(), seen.end()), members);
  for (std::uint32_t p : seen) EXPECT_EQ(queues.queueOf(p), 1);
}

TEST(PointQueues, RoundRobinNeverReturnsAPointTwiceInOneCall) {
  PointQueues queues(100, 1);
  for (std::uint32_t p : {5u, 50u, 99u}) queues.insert(p, 0);
  std::vector<std::uint32_t> out(10);
  EXPECT_EQ(queues.takeRoundRobin(0, 10, out), 3u);
  std::sort(out.begin(), out.begin() + 3);
  EXPECT_EQ(out[0], 5u);
  EXPECT_EQ(out[1], 50u);
  EXPECT_EQ(out[2], 99u);
}

}  // namespace
}  // namespace voxhap
