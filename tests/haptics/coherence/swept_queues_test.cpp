#include "haptics/coherence/swept_queues.h"

#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace voxhap {
namespace {

// Members join queue 1 all the time, each tested (joined) at the pair's relative position
// then; the travel per frame jumps about, falling as often as it rises. Every member must be
// collected at the latest in the first frame that starts further than d from where it joined.
TEST(SweptQueues, EveryMemberIsCollectedBeforeThePairHasMovedItsDistance) {
  constexpr std::uint32_t kMembers = 20'000;
  constexpr double kDistanceM = 0.001;
  std::mt19937 random(5);
  std::uniform_real_distribution<double> share(0.0, 1.0);
  SweptQueues swept(kMembers, 2);
  swept.queues().assignAll(0);
  std::vector<double> joinedAtM(kMembers, -1.0);  // −1: not in queue 1
  std::vector<std::uint32_t> out(kMembers);
  double positionM = 0.0, lastTravelM = 0.0;
  std::uint64_t collected = 0;
  for (int frame = 0; frame < 3000; ++frame) {
    // up to half the distance, often a tenth of that, now and then nothing
    const double r = share(random);
    const double travelM = r < 0.1 ? 0.0 : (r < 0.5 ? 0.05 : 0.5) * kDistanceM * share(random);
    const std::uint32_t n = swept.collect(1, kDistanceM, lastTravelM, out);
    for (std::uint32_t i = 0; i < n; ++i) {
      swept.queues().move(out[i], 1, 0);
      joinedAtM[out[i]] = -1.0;
    }
    collected += n;
    for (std::uint32_t p = 0; p < kMembers; ++p) {
      ASSERT_FALSE(joinedAtM[p] >= 0.0 && positionM - joinedAtM[p] > kDistanceM)
          << "frame " << frame << ": member " << p << " moved " << (positionM - joinedAtM[p]) / kDistanceM
          << " of its distance untested";
    }
    for (int k = 0; k < 60; ++k) {  // tested this frame, found one distance away
      const auto p = static_cast<std::uint32_t>(random() % kMembers);
      if (swept.queues().queueOf(p) == 0) {
        swept.queues().move(p, 0, 1);
        joinedAtM[p] = positionM;
      }
    }
    positionM += travelM;
    lastTravelM = travelM;
  }
  EXPECT_GT(collected, 50'000u);
}

TEST(SweptQueues, CountsWhatItWouldCollectAtEachTravel) {
  std::mt19937 random(9);
  constexpr std::uint32_t kMembers = 50'000;
  SweptQueues swept(kMembers, 2);
  for (std::uint32_t p = 0; p < kMembers; ++p)
    swept.queues().insert(p, p % 7 == 0 || (p > 30'000 && p < 34'000) ? 1 : 0);
  std::vector<std::uint32_t> out(kMembers);
  swept.collect(1, 0.001, 0.0003, out);  // the cursor and what is owed somewhere
  TestsByTravel tests{};
  // in this frame, after 0.1 mm in the one before: what the next frame takes, by this one's travel
  swept.addTestsByTravel(1, 0.001, 0.0004, 0.0001, tests);
  for (int k : {0, 1, 5, 17, kTravelSteps}) {
    SweptQueues copy = swept;
    copy.collect(1, 0.001, 0.0001, out);
    const double travelM = 0.0004 * k / kTravelSteps;
    EXPECT_EQ(copy.collect(1, 0.001, travelM, out), tests[static_cast<std::size_t>(k)]) << "step " << k;
  }
  EXPECT_EQ(tests[0], 0.0);  // a frame that allows no travel owes the next nothing
  EXPECT_GT(tests[1], 0.0);
  EXPECT_GT(tests[kTravelSteps], tests[1]);
}

}  // namespace
}  // namespace voxhap
