#include "haptics/coherence/max_travel.h"

#include <gtest/gtest.h>

namespace voxhap {
namespace {

/// Tests growing in proportion to the travel, `atFullTravel` at scale 1: Eq. 2 as the
/// paper writes it.
TestsByTravel proportional(double atFullTravel) {
  TestsByTravel tests{};
  for (std::size_t k = 0; k < tests.size(); ++k)
    tests[k] = atFullTravel * static_cast<double>(k) / kTravelSteps;
  return tests;
}

TEST(MaxTravel, FollowsEquationTwoAndItsBound) {
  // 100 mandatory; 900 spare tests
  EXPECT_DOUBLE_EQ(travelScale(1000, 100, proportional(900)).scale, 1.0);
  EXPECT_DOUBLE_EQ(travelScale(1000, 100, proportional(1800)).scale, 0.5);
  EXPECT_DOUBLE_EQ(travelScale(1000, 100, proportional(3600)).scale, 0.25);
  EXPECT_DOUBLE_EQ(travelScale(1000, 100, proportional(90)).scale, 1.0);  // never beyond the bound
  const TravelBudget stuck = travelScale(100, 100, proportional(900));
  EXPECT_EQ(stuck.scale, 0.0);
  EXPECT_TRUE(stuck.deadlineMissed);
  EXPECT_DOUBLE_EQ(travelScale(1000, 0, TestsByTravel{}).scale, 1.0);  // nothing near
}

TEST(MaxTravel, TakesTheLargestTravelWhoseCountedTestsFit) {
  // a sweep that reaches a crowded block at scale 2/32: 5,000 tests more from there on
  TestsByTravel tests = proportional(320);
  for (std::size_t k = 2; k < tests.size(); ++k) tests[k] += 5000;
  const TravelBudget budget = travelScale(1100, 100, tests);
  EXPECT_FALSE(budget.deadlineMissed);
  // room for 1,000: 10 tests at 1/32, 5,020 at 2/32; linear in between
  EXPECT_DOUBLE_EQ(budget.scale, (1.0 + 990.0 / 5010.0) / kTravelSteps);
  // Eq. 2 by the proportion at full travel would let it move about 5 times as far, where the
  // sweeps take 5 times the capacity
  const double byProportion = travelScale(1100, 100, proportional(tests.back())).scale;
  EXPECT_GT(byProportion, 4.5 * budget.scale);
  EXPECT_GT(tests[static_cast<std::size_t>(byProportion * kTravelSteps)], 5000.0);
  // room for half a test: a twentieth of the first step
  EXPECT_DOUBLE_EQ(travelScale(100.5, 100, proportional(320)).scale, 0.05 / kTravelSteps);
}

TEST(MaxTravel, QueuesByValueAroundTheForceLayer) {
  // 4-bit fields: values 1 … 10, far 0; force layer 4
  EXPECT_EQ(queueCountFor(4, 10), 8);
  EXPECT_EQ(queueForValue(1, 4, 10), 0);
  EXPECT_EQ(queueForValue(4, 4, 10), 0);
  EXPECT_EQ(queueForValue(5, 4, 10), 1);
  EXPECT_EQ(queueForValue(10, 4, 10), 6);
  EXPECT_EQ(queueForValue(0, 4, 10), 7);
  // far lies beyond distance 8: six whole voxels (distances 8 … 3) before distance 2
  EXPECT_EQ(voxelsToContact(queueForValue(0, 4, 10)), 6);
}

}  // namespace
}  // namespace voxhap
