#include "haptics/coherence/max_travel.h"

#include <gtest/gtest.h>

namespace voxhap {
namespace {

TEST(MaxTravel, FollowsEquationTwoAndItsBound) {
  constexpr double s = 0.001;
  // 100 mandatory, 1000 capacity: 900 tests for Σ n_i / i = 600/1 + 600/2 = 900 → s
  const std::uint32_t counts[] = {100, 600, 600};
  EXPECT_DOUBLE_EQ(maxTravel(1000, counts, s, 10 * s).maxTravelM, s);
  EXPECT_DOUBLE_EQ(maxTravel(1000, counts, s, 0.5 * s).maxTravelM, 0.5 * s);
  const TravelBudget stuck = maxTravel(100, counts, s, 0.5 * s);
  EXPECT_EQ(stuck.maxTravelM, 0.0);
  EXPECT_TRUE(stuck.deadlineMissed);
  const std::uint32_t nothingNear[] = {0, 0, 0};
  EXPECT_DOUBLE_EQ(maxTravel(1000, nothingNear, s, 0.5 * s).maxTravelM, 0.5 * s);
}

TEST(MaxTravel, QuotasTestEveryQueueOftenEnoughAndFitTheCapacity) {
  constexpr double s = 0.001;
  const std::uint32_t counts[] = {50, 300, 900, 2000, 10000};
  const double capacity = 2000;
  const TravelBudget budget = maxTravel(capacity, counts, s, 0.5 * s);
  ASSERT_FALSE(budget.deadlineMissed);
  std::uint32_t tests = counts[0];
  for (int i = 1; i < 5; ++i) {
    const std::uint32_t m = queueQuota(counts[i], i, budget.maxTravelM, s);
    // a point of queue i is due again after n_i / m_i frames, in which it moves at most
    // that many MaxTravels: never as far as its i voxels
    EXPECT_LE(static_cast<double>(counts[i]) / m * budget.maxTravelM, i * s * (1 + 1e-12));
    tests += m;
  }
  EXPECT_LE(tests, capacity + 4);  // each quota rounds up by less than one
}

TEST(MaxTravel, QueuesByValueAroundTheForceLayer) {
  // 4-bit fields: values 1 … 10, far 0; force layer 4
  EXPECT_EQ(queueCountFor(4, 10), 8);
  EXPECT_EQ(queueForValue(1, 4, 10), 0);
  EXPECT_EQ(queueForValue(4, 4, 10), 0);
  EXPECT_EQ(queueForValue(5, 4, 10), 1);
  EXPECT_EQ(queueForValue(10, 4, 10), 6);
  EXPECT_EQ(queueForValue(0, 4, 10), 7);
}

}  // namespace
}  // namespace voxhap
