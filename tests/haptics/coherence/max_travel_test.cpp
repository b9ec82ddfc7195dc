#include "haptics/coherence/max_travel.h"

#include <span>
#include <utility>

#include <gtest/gtest.h>

namespace voxhap {
namespace {

/// Mandatory points and Σ n_i / d_i (tests per voxel of travel) of queues by count.
std::pair<double, double> mandatoryAndLoad(std::span<const std::uint32_t> counts) {
  double mandatory = 0.0, load = 0.0;
  for (std::size_t i = 0; i < counts.size(); ++i) {
    if (static_cast<int>(i) < kMandatoryQueues) {
      mandatory += counts[i];
    } else {
      load += counts[i] / static_cast<double>(voxelsToContact(static_cast<int>(i)));
    }
  }
  return {mandatory, load};
}

TEST(MaxTravel, FollowsEquationTwoAndItsBound) {
  // 100 mandatory; 900 spare tests for a load of 600/1 + 600/2 = 900 at full travel: scale 1
  const std::uint32_t counts[] = {60, 40, 600, 600};
  const auto [mandatory, load] = mandatoryAndLoad(counts);
  EXPECT_EQ(mandatory, 100.0);
  EXPECT_DOUBLE_EQ(load, 900.0);
  EXPECT_DOUBLE_EQ(travelScale(1000, 100, 900).scale, 1.0);
  EXPECT_DOUBLE_EQ(travelScale(1000, 100, 1800).scale, 0.5);
  EXPECT_DOUBLE_EQ(travelScale(1000, 100, 90).scale, 1.0);  // never beyond the bound
  const TravelBudget stuck = travelScale(100, 100, 900);
  EXPECT_EQ(stuck.scale, 0.0);
  EXPECT_TRUE(stuck.deadlineMissed);
  EXPECT_DOUBLE_EQ(travelScale(1000, 0, 0).scale, 1.0);  // nothing near
}

TEST(MaxTravel, QuotasTestEveryQueueOftenEnoughAndFitTheCapacity) {
  constexpr double s = 0.001;
  const std::uint32_t counts[] = {50, 300, 900, 2000, 10000, 7};
  const double capacity = 2000;
  const double boundM = 0.5 * s;
  const auto [mandatory, load] = mandatoryAndLoad(counts);
  const TravelBudget budget = travelScale(capacity, mandatory, load * boundM / s);
  ASSERT_FALSE(budget.deadlineMissed);
  ASSERT_LT(budget.scale, 1.0);
  const double travelM = budget.scale * boundM;
  double tests = mandatory;
  for (int i = kMandatoryQueues; i < 6; ++i) {
    const double distanceM = voxelsToContact(i) * s;
    const std::uint32_t m = sweepQuota(counts[i], travelM, distanceM);
    // a point of queue i is due again after n_i / m_i frames, in which it moves at most
    // that many MaxTravels: never as far as the i − 1 voxels it must cross
    EXPECT_LE(static_cast<double>(counts[i]) / m * travelM, distanceM * (1 + 1e-12));
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
  // far lies beyond distance 8: six whole voxels (distances 8 … 3) before distance 2
  EXPECT_EQ(voxelsToContact(queueForValue(0, 4, 10)), 6);
}

}  // namespace
}  // namespace voxhap
