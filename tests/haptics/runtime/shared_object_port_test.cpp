#include "haptics/runtime/shared_object_port.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "support/rigid_body_fixtures.h"

namespace voxhap {
namespace {

constexpr double kDtS = 1e-3;
constexpr std::int64_t kStreamUs = 10'000;  // 100 Hz

using test::offsetBoxModel;

struct SharedObjectPortTest : testing::Test {
  RigidBodyModel model = offsetBoxModel(1.0);
  CouplingGains gains = defaultCouplingGains(model, kDtS);
  RigidBodyState local = restingState(model);
  RigidBodyState away = [this] {
    RigidBodyState s = restingState(model);
    s.comWorld.x += 0.003;
    return s;
  }();
  SharedObjectPort port;

  /// `peer`'s instance `away`, sent at 100 Hz from `fromUs` up to `toUs`, arriving at once
  /// (a one-way delay of 0), its ramp begun by a frame at `fromUs`.
  void stream(PeerId peer, std::int64_t fromUs, std::int64_t toUs) {
    for (std::int64_t t = fromUs; t <= toUs; t += kStreamUs) port.take(peer, {t, away}, 0.0, t);
    port.setDelay(peer, 0.0);
    forceXN(fromUs);
  }
  /// The pull of `away` (3 mm) through the spring of weight `ramp` × its delay's × its
  /// age's (its delay and the play-out delay; shared_coupling.h).
  double pullN(double ramp, double oneWayS) const {
    const double omegaRadS = std::sqrt(gains.linearStiffnessNPerM / model.massKg);
    const double ageS = oneWayS + JitterBuffer().playoutDelayS();
    return ramp * delayWeight(oneWayS) * ageWeight(ageS, omegaRadS) * gains.linearStiffnessNPerM * 0.003;
  }
  double forceXN(std::int64_t nowUs) {
    return port.step(nowUs, model, local, gains, false, kDtS).wrench.forceWorld.x;
  }
};

TEST_F(SharedObjectPortTest, ARemoteInstancePullsAsTheCouplingSaysOnceRampedIn) {
  stream(7, 0, 1'000'000);
  // half way through the ramp, half the pull; after it, the whole
  EXPECT_NEAR(forceXN(SharedObjectPort::kJoinRampUs / 2), pullN(0.5, 0.0), 1e-9);
  EXPECT_NEAR(forceXN(800'000), pullN(1.0, 0.0), 1e-9);
  EXPECT_GT(pullN(1.0, 0.0), 0.0);
  EXPECT_EQ(port.last().counted, 1u);
  // its one-way delay lowers it as k(τ) says
  port.setDelay(7, 0.25);
  EXPECT_NEAR(forceXN(800'000), pullN(1.0, 0.25), 1e-9);
  EXPECT_LT(pullN(1.0, 0.25), 0.75 * pullN(1.0, 0.0));
}

TEST_F(SharedObjectPortTest, AnInstanceWhoseDelayIsNotMeasuredYetDoesNotCountThenRampsIn) {
  for (std::int64_t t = 0; t <= 1'000'000; t += kStreamUs) port.take(7, {t, away}, 0.0, t);
  EXPECT_EQ(forceXN(600'000), 0.0);
  EXPECT_EQ(port.last().counted, 0u);
  port.setDelay(7, 0.5);  // measured now: from nothing, without a step
  EXPECT_EQ(forceXN(601'000), 0.0);
  EXPECT_NEAR(forceXN(601'000 + SharedObjectPort::kJoinRampUs / 2), pullN(0.5, 0.5), 1e-9);
}

TEST_F(SharedObjectPortTest, AStreamThatStopsFadesOutWithinASecondWithoutAStep) {
  stream(7, 0, 1'000'000);
  const double fullN = forceXN(1'000'000);
  double previousN = fullN;
  double largestStepN = 0.0;
  for (std::int64_t t = 1'001'000; t <= 2'200'000; t += 1'000) {
    const double f = forceXN(t);
    largestStepN = std::max(largestStepN, std::abs(f - previousN));
    previousN = f;
  }
  EXPECT_NEAR(fullN, pullN(1.0, 0.0), 1e-9);
  EXPECT_EQ(previousN, 0.0);
  EXPECT_LT(largestStepN, 0.002 * fullN);
}

TEST_F(SharedObjectPortTest, ADroppedPeerKeepsItsSlotUntilItHasFadedThenANewOneTakesIt) {
  for (PeerId p = 1; p <= SharedObjectPort::kMaxRemotes; ++p) stream(p, 0, 600'000);
  EXPECT_FALSE(port.take(99, {600'000, away}, 0.0, 600'000));  // no room
  port.drop(3);
  forceXN(700'000);
  EXPECT_FALSE(port.take(99, {700'000, away}, 0.0, 700'000));  // 3 is still fading
  for (PeerId p = 1; p <= SharedObjectPort::kMaxRemotes; ++p)
    if (p != 3) stream(p, 610'000, 1'800'000);
  forceXN(1'800'000);
  EXPECT_TRUE(port.take(99, {1'800'000, away}, 0.0, 1'800'000));
}

TEST_F(SharedObjectPortTest, WithPassivityOnTheOthersEnergyIsWhatItMayGiveOut) {
  // the remote instance has put nothing into its port: a pull on a moving instance gives
  // no energy out (the local one moves towards it, so the pull would do work)
  stream(7, 0, 1'000'000);
  local.linearVelocityWorld = glm::dvec3(0.001, 0.0, 0.0);
  const SharedObjectPort::Frame& f = port.step(800'000, model, local, gains, true, kDtS);
  EXPECT_GT(f.coupling.onLocal.forceWorld.x, 0.0);
  EXPECT_LE(glm::dot(f.wrench.forceWorld, local.linearVelocityWorld), 1e-12);
}

}  // namespace
}  // namespace voxhap
