// The jitter buffer plays a remote object's stream out smoothly a fixed delay behind its
// least delayed sample, whatever the clocks' offset, the jitter, losses and reordering.
#include "haptics/runtime/jitter_buffer.h"

#include <cmath>
#include <random>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "support/allocation_counter.h"

namespace voxhap {
namespace {

constexpr std::int64_t kDelayUs = 30'000;
constexpr double kSpeedMPerS = 0.1;   // along x
constexpr double kTurnRadPerS = 0.5;  // about z

/// The owner's object at its time `sentUs`: moving along x and turning about z.
RemoteSample truth(std::int64_t sentUs) {
  const double t = 1e-6 * static_cast<double>(sentUs);
  RemoteSample s;
  s.sentUs = sentUs;
  s.body.comWorld = glm::dvec3(kSpeedMPerS * t, 0.0, 0.0);
  s.body.orientation = glm::angleAxis(kTurnRadPerS * t, glm::dvec3(0.0, 0.0, 1.0));
  s.body.linearVelocityWorld = glm::dvec3(kSpeedMPerS, 0.0, 0.0);
  s.body.angularVelocityWorld = glm::dvec3(0.0, 0.0, kTurnRadPerS);
  return s;
}

TEST(JitterBuffer, NothingToPlayUntilASampleCame) {
  JitterBuffer buffer(kDelayUs);
  RigidBodyState out;
  out.comWorld = glm::dvec3(7.0);
  EXPECT_FALSE(buffer.playOut(1000, out));
  EXPECT_EQ(out.comWorld, glm::dvec3(7.0));
}

TEST(JitterBuffer, A100HzStreamWithJitterLossAndAnOffsetPlaysOutOnTheOwnersPath) {
  JitterBuffer buffer(kDelayUs);
  std::mt19937_64 random(12);
  std::uniform_int_distribution<std::int64_t> jitterUs(0, 20'000);
  std::bernoulli_distribution lost(0.05);
  // the owner's clock runs 1234.5 s ahead of ours, and the path takes 40 to 60 ms
  constexpr std::int64_t kOwnerAheadUs = 1'234'500'000;
  constexpr std::int64_t kPathUs = 40'000;
  std::int64_t nextSentUs = kOwnerAheadUs;
  double worstErrorM = 0.0;
  int played = 0;
  std::vector<std::pair<std::int64_t, RemoteSample>> inFlight;  // arrival (local), sample
  for (std::int64_t nowUs = 0; nowUs < 3'000'000; nowUs += 1000) {
    if (nowUs + kOwnerAheadUs >= nextSentUs) {
      if (!lost(random)) inFlight.push_back({nowUs + kPathUs + jitterUs(random), truth(nextSentUs)});
      nextSentUs += 10'000;
    }
    for (auto it = inFlight.begin(); it != inFlight.end();) {
      if (it->first <= nowUs) {
        buffer.push(it->second, nowUs);
        it = inFlight.erase(it);
      } else {
        ++it;
      }
    }
    RigidBodyState out;
    if (nowUs < 500'000 || !buffer.playOut(nowUs, out)) continue;
    // the owner's time it shows: now, less the least transit and the delay
    const RemoteSample expected = truth(nowUs - buffer.offsetUs() - kDelayUs);
    worstErrorM = std::max(worstErrorM, glm::length(out.comWorld - expected.body.comWorld));
    EXPECT_NEAR(glm::angle(out.orientation * glm::conjugate(expected.body.orientation)), 0.0, 1e-6);
    ++played;
  }
  EXPECT_EQ(played, 2500);
  // the path is linear in time, so interpolating between samples is exact up to rounding
  EXPECT_LT(worstErrorM, 1e-9);
  // the least delayed of the samples held came within a few ms of the 40 ms path
  EXPECT_GE(buffer.offsetUs() + kOwnerAheadUs, kPathUs);
  EXPECT_LT(buffer.offsetUs() + kOwnerAheadUs, kPathUs + 5'000);
}

TEST(JitterBuffer, DuplicatesAndOvertakenSamplesAreDropped) {
  JitterBuffer buffer(kDelayUs);
  EXPECT_TRUE(buffer.push(truth(10'000), 50'000));
  EXPECT_TRUE(buffer.push(truth(30'000), 70'000));
  EXPECT_FALSE(buffer.push(truth(30'000), 71'000));  // duplicated
  EXPECT_FALSE(buffer.push(truth(20'000), 72'000));  // overtaken
  EXPECT_EQ(buffer.size(), 2u);
}

TEST(JitterBuffer, WhenTheStreamStopsItRunsOnBrieflyThenHolds) {
  JitterBuffer buffer(kDelayUs);
  for (std::int64_t sent = 0; sent <= 100'000; sent += 10'000) buffer.push(truth(sent), sent + 1000);
  RigidBodyState out;
  // due at 100 ms + 1 ms + 30 ms on ours; 20 ms later it has run on 20 ms of its velocity
  ASSERT_TRUE(buffer.playOut(151'000, out));
  EXPECT_NEAR(out.comWorld.x, kSpeedMPerS * 0.12, 1e-12);
  // and after 50 ms it stops where its velocity took it
  ASSERT_TRUE(buffer.playOut(10'000'000, out));
  EXPECT_NEAR(out.comWorld.x, kSpeedMPerS * (0.1 + 1e-6 * JitterBuffer::kMaxExtrapolationUs), 1e-12);
  // before the oldest: the oldest
  ASSERT_TRUE(buffer.playOut(0, out));
  EXPECT_EQ(out.comWorld, truth(0).body.comWorld);
  buffer.clear();
  EXPECT_FALSE(buffer.playOut(151'000, out));
}

TEST(JitterBuffer, KeepsItsNewestSamplesAndNeverAllocates) {
  JitterBuffer buffer(kDelayUs);
  const test::AllocationCounter counter;
  RigidBodyState out;
  for (std::int64_t i = 0; i < 1000; ++i) {
    buffer.push(truth(i * 1000), i * 1000 + 500);
    buffer.playOut(i * 1000, out);
  }
  EXPECT_EQ(counter.count(), 0u);
  EXPECT_EQ(buffer.size(), JitterBuffer::kCapacity);
  ASSERT_TRUE(buffer.playOut(0, out));  // the oldest kept is 32 samples back
  EXPECT_EQ(out.comWorld, truth((1000 - JitterBuffer::kCapacity) * 1000).body.comWorld);
}

}  // namespace
}  // namespace voxhap
