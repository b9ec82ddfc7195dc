#include "haptics/dynamics/shared_coupling.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "support/delayed_stream.h"
#include "support/rigid_body_fixtures.h"

namespace voxhap {
namespace {

constexpr double kDtS = 1e-3;

using test::offsetBoxModel;

/// `model` as loaded, its centre of mass moved by `offsetM` and turned by `turnRad` about it.
RigidBodyState instance(const RigidBodyModel& model, const glm::dvec3& offsetM = glm::dvec3(0.0),
                        const glm::dvec3& turnRad = glm::dvec3(0.0)) {
  RigidBodyState s = restingState(model);
  s.comWorld += offsetM;
  s.orientation = quatFromRotationVector(turnRad) * s.orientation;
  return s;
}

TEST(SharedCoupling, TheWeightFallsLinearlyToZeroAtOneSecond) {
  EXPECT_EQ(delayWeight(0.0), 1.0);
  EXPECT_EQ(delayWeight(-0.01), 1.0);
  EXPECT_DOUBLE_EQ(delayWeight(0.25), 0.75);
  EXPECT_DOUBLE_EQ(delayWeight(0.5), 0.5);
  EXPECT_EQ(delayWeight(1.0), 0.0);
  EXPECT_EQ(delayWeight(3.0), 0.0);
  EXPECT_EQ(delayWeight(std::numeric_limits<double>::infinity()), 0.0);
  EXPECT_EQ(delayWeight(std::numeric_limits<double>::quiet_NaN()), 0.0);
}

TEST(SharedCoupling, AnInstancesAgeAllowsAStiffnessWhoseNaturalFrequencyTimesItIsAQuarter) {
  const double omegaRadS = 250.0;
  EXPECT_EQ(ageWeight(0.0, omegaRadS), 1.0);
  EXPECT_EQ(ageWeight(0.001, omegaRadS), 1.0);  // ω·a = 0.25
  EXPECT_DOUBLE_EQ(ageWeight(0.002, omegaRadS), 0.25);
  EXPECT_DOUBLE_EQ(ageWeight(0.030, omegaRadS), 1.0 / 900.0);
  EXPECT_EQ(ageWeight(std::numeric_limits<double>::quiet_NaN(), omegaRadS), 0.0);
  // the spring that weight leaves has ω_n·a = 0.25
  const RigidBodyModel model = offsetBoxModel(2.0);
  const CouplingGains gains = defaultCouplingGains(model, kDtS);
  const double ageS = 0.030;
  const std::vector<RemoteInstance> remotes = {{instance(model, glm::dvec3(0.003, 0.0, 0.0)), 0.0, ageS}};
  const SharedCoupling c = sharedCouplingWrench(gains, model, instance(model), remotes);
  const double stiffnessNPerM = c.onLocal.forceWorld.x / 0.003;
  EXPECT_NEAR(std::sqrt(stiffnessNPerM / model.massKg) * ageS, kSharedCouplingOmegaAge, 1e-9);
}

TEST(SharedCoupling, InstancesMovingTogetherDoNotPullOnEachOtherHoweverOldTheRemoteStateIs) {
  // the remote state, 30 ms old, is where the local instance was then: carried forward by
  // its age along its velocities, it is where the local one is now
  const RigidBodyModel model = offsetBoxModel(2.0);
  const CouplingGains gains = defaultCouplingGains(model, kDtS);
  const double ageS = 0.030;
  RigidBodyState local = instance(model);
  local.linearVelocityWorld = glm::dvec3(0.1, -0.05, 0.02);
  local.angularVelocityWorld = glm::dvec3(0.0, 0.0, 0.3);
  RigidBodyState then = local;
  then.comWorld -= local.linearVelocityWorld * ageS;
  then.orientation = quatFromRotationVector(-local.angularVelocityWorld * ageS) * local.orientation;
  const std::vector<RemoteInstance> remotes = {{then, 0.0, ageS, ageS}};
  const SharedCoupling c = sharedCouplingWrench(gains, model, local, remotes);
  EXPECT_GT(c.stiffnessShare, 0.0);
  EXPECT_LT(c.apartM, 1e-12);
  EXPECT_LT(glm::length(c.onLocal.forceWorld), 1e-9);
  EXPECT_LT(glm::length(c.onLocal.torqueWorld), 1e-9);
  // a lead beyond the age is cut to it: no push along the motion
  const std::vector<RemoteInstance> beyond = {{then, 0.0, ageS, 2.0 * ageS}};
  EXPECT_LT(glm::length(sharedCouplingWrench(gains, model, local, beyond).onLocal.forceWorld), 1e-9);
  // a lead short of the age leaves the state behind: a pull against the motion (damping)
  const std::vector<RemoteInstance> behind = {{then, 0.0, ageS, 0.5 * ageS}};
  EXPECT_LT(glm::dot(sharedCouplingWrench(gains, model, local, behind).onLocal.forceWorld,
                     local.linearVelocityWorld),
            0.0);
}

TEST(SharedCoupling, ARemoteInstanceAwayPullsWithTheFullStiffnessAtNoDelay) {
  const RigidBodyModel model = offsetBoxModel(2.0);
  const CouplingGains gains = defaultCouplingGains(model, kDtS);
  const glm::dvec3 awayM(0.003, -0.002, 0.001);
  const std::vector<RemoteInstance> remotes = {{instance(model, awayM), 0.0}};
  const SharedCoupling c = sharedCouplingWrench(gains, model, instance(model), remotes);
  EXPECT_EQ(c.stiffnessShare, 1.0);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(c.onLocal.forceWorld[k], gains.linearStiffnessNPerM * awayM[k], 1e-9);
    EXPECT_NEAR(c.onLocal.torqueWorld[k], 0.0, 1e-9);
  }
}

TEST(SharedCoupling, ARemoteInstanceTurnedAboutItsCentreOfMassTurnsTheLocalOneWithoutAForce) {
  const RigidBodyModel model = offsetBoxModel(2.0);  // the centre of mass 0.37 m from the origin
  const CouplingGains gains = defaultCouplingGains(model, kDtS);
  const glm::dvec3 turnRad(0.01, 0.02, -0.015);
  const std::vector<RemoteInstance> remotes = {{instance(model, glm::dvec3(0.0), turnRad), 0.0}};
  const SharedCoupling c = sharedCouplingWrench(gains, model, instance(model), remotes);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(c.onLocal.torqueWorld[k], gains.angularStiffnessNmPerRad * turnRad[k], 1e-9);
    EXPECT_NEAR(c.onLocal.forceWorld[k], 0.0, 1e-9);
  }
}

TEST(SharedCoupling, FourRemoteInstancesPullNoHarderThanOne) {
  const RigidBodyModel model = offsetBoxModel(1.0);
  const CouplingGains gains = defaultCouplingGains(model, kDtS);
  const RemoteInstance away{instance(model, glm::dvec3(0.004, 0.0, 0.0), glm::dvec3(0.0, 0.0, 0.02)), 0.0};
  const std::vector<RemoteInstance> one = {away};
  const std::vector<RemoteInstance> four = {away, away, away, away};
  const SharedCoupling a = sharedCouplingWrench(gains, model, instance(model), one);
  const SharedCoupling b = sharedCouplingWrench(gains, model, instance(model), four);
  EXPECT_NEAR(glm::length(a.onLocal.forceWorld - b.onLocal.forceWorld), 0.0, 1e-9);
  EXPECT_NEAR(glm::length(a.onLocal.torqueWorld - b.onLocal.torqueWorld), 0.0, 1e-9);
  EXPECT_GT(glm::length(a.onLocal.forceWorld), 100.0);
}

TEST(SharedCoupling, HalfASecondsDelayHalvesTheStiffnessAndKeepsTheDampingRatio) {
  const RigidBodyModel model = offsetBoxModel(1.0);
  const CouplingGains gains = defaultCouplingGains(model, kDtS);
  RigidBodyState remote = instance(model, glm::dvec3(0.0, 0.002, 0.0));
  remote.linearVelocityWorld = glm::dvec3(0.0, 0.0, 0.1);
  const std::vector<RemoteInstance> remotes = {{remote, 0.5}};
  const SharedCoupling c = sharedCouplingWrench(gains, model, instance(model), remotes);
  EXPECT_DOUBLE_EQ(c.stiffnessShare, 0.5);
  EXPECT_NEAR(c.onLocal.forceWorld.y, 0.5 * gains.linearStiffnessNPerM * 0.002, 1e-9);
  EXPECT_NEAR(c.onLocal.forceWorld.z, std::sqrt(0.5) * gains.linearDampingNsPerM * 0.1, 1e-9);
}

TEST(SharedCoupling, AnInstanceOfWeightZeroOrNotFiniteChangesNothing) {
  const RigidBodyModel model = offsetBoxModel(1.0);
  const CouplingGains gains = defaultCouplingGains(model, kDtS);
  const RemoteInstance a{instance(model, glm::dvec3(0.001, 0.0, 0.0)), 0.02};
  RigidBodyState broken = instance(model);
  broken.comWorld.x = std::numeric_limits<double>::quiet_NaN();
  const std::vector<RemoteInstance> alone = {a};
  const std::vector<RemoteInstance> withOthers = {
      a, {instance(model, glm::dvec3(0.0, 0.05, 0.0)), 1.0}, {broken, 0.0}};
  const SharedCoupling x = sharedCouplingWrench(gains, model, instance(model), alone);
  const SharedCoupling y = sharedCouplingWrench(gains, model, instance(model), withOthers);
  EXPECT_EQ(x.onLocal.forceWorld, y.onLocal.forceWorld);
  EXPECT_EQ(x.onLocal.torqueWorld, y.onLocal.torqueWorld);
  EXPECT_EQ(x.stiffnessShare, y.stiffnessShare);
  const std::vector<RemoteInstance> none = {{broken, 0.0}};
  EXPECT_EQ(sharedCouplingWrench(gains, model, instance(model), none).stiffnessShare, 0.0);
}

TEST(SharedCoupling, AnInstanceWhoseStreamStopsFadesOutWithoutAStep) {
  // two remote instances on either side; one's newest state ages from 0 to 1 s, a frame at
  // a time: the force moves smoothly to the other's alone
  const RigidBodyModel model = offsetBoxModel(1.0);
  const CouplingGains gains = defaultCouplingGains(model, kDtS);
  const RemoteInstance stays{instance(model, glm::dvec3(0.002, 0.0, 0.0)), 0.03};
  RemoteInstance fades{instance(model, glm::dvec3(-0.004, 0.001, 0.0)), 0.03};
  glm::dvec3 previous =
      sharedCouplingWrench(gains, model, instance(model), std::vector{stays, fades}).onLocal.forceWorld;
  double largestStepN = 0.0;
  for (int frame = 1; fades.delayS < 1.0; ++frame) {
    fades.delayS = 0.03 + frame * kDtS;
    const glm::dvec3 f =
        sharedCouplingWrench(gains, model, instance(model), std::vector{stays, fades}).onLocal.forceWorld;
    largestStepN = std::max(largestStepN, glm::length(f - previous));
    previous = f;
  }
  const glm::dvec3 alone =
      sharedCouplingWrench(gains, model, instance(model), std::vector{stays}).onLocal.forceWorld;
  EXPECT_EQ(previous, alone);
  // the whole change spread over the second, no frame taking more than a few per cent of it
  const double changeN = glm::length(
      alone - sharedCouplingWrench(gains, model, instance(model), std::vector{stays, {fades.state, 0.03}})
                  .onLocal.forceWorld);
  EXPECT_GT(changeN, 100.0);
  EXPECT_LT(largestStepN, 0.01 * changeN);
}

TEST(SharedCoupling, InstancesFurtherApartThanTheBoundAreDivergentUntilBackWithinHalfOfIt) {
  const RigidBodyModel model = offsetBoxModel(1.0);
  const CouplingGains gains = defaultCouplingGains(model, kDtS);
  const DivergenceBound bound{0.01, 0.1};
  auto at = [&](double xM, double turnRad, bool was) {
    const std::vector<RemoteInstance> remote = {
        {instance(model, glm::dvec3(xM, 0.0, 0.0), glm::dvec3(0.0, 0.0, turnRad)), 0.0}};
    return sharedCouplingWrench(gains, model, instance(model), remote, bound, was);
  };
  // a wall 30 mm thick between them: divergent, and the spring pulls as at the bound, no harder
  const SharedCoupling wall = at(0.03, 0.0, false);
  EXPECT_TRUE(wall.divergent);
  EXPECT_NEAR(wall.apartM, 0.03, 1e-12);
  EXPECT_NEAR(wall.onLocal.forceWorld.x, gains.linearStiffnessNPerM * 0.01, 1e-9);
  // at the bound the pull is the same: no step as they pass it
  EXPECT_NEAR(at(0.01, 0.0, false).onLocal.forceWorld.x, wall.onLocal.forceWorld.x, 1e-9);
  EXPECT_FALSE(at(0.009, 0.0, false).divergent);
  EXPECT_TRUE(at(0.009, 0.0, true).divergent);  // coming back: still, until within half
  EXPECT_FALSE(at(0.0049, 0.0, true).divergent);
  // turned apart: the same in angle
  const SharedCoupling turned = at(0.0, 0.3, false);
  EXPECT_TRUE(turned.divergent);
  EXPECT_NEAR(turned.onLocal.torqueWorld.z, gains.angularStiffnessNmPerRad * 0.1, 1e-9);
  EXPECT_TRUE(at(0.0, 0.06, true).divergent);
  EXPECT_FALSE(at(0.0, 0.04, true).divergent);
}

TEST(SharedCoupling, WhenTheWallGoesTheInstancesCloseWithNoMoreThanTheBoundsPull) {
  // two free instances held 50 mm apart (by a wall), then free: they meet, and no force
  // along the way is more than the bound's pull and its damping
  const RigidBodyModel model = offsetBoxModel(1.0);
  const CouplingGains gains = defaultCouplingGains(model, kDtS);
  std::array<RigidBodyState, 2> bodies = {instance(model), instance(model, glm::dvec3(0.05, 0.0, 0.0))};
  double strongestN = 0.0;
  bool divergentAtFirst = false;
  std::array<bool, 2> divergent{};
  for (int frame = 0; frame < 3000; ++frame) {
    std::array<SharedCoupling, 2> c{};
    for (std::size_t i = 0; i < 2; ++i) {
      const std::vector<RemoteInstance> other = {{bodies[1 - i], 0.0}};
      c[i] = sharedCouplingWrench(gains, model, bodies[i], other, {}, divergent[i]);
      divergent[i] = c[i].divergent;
      strongestN = std::max(strongestN, glm::length(c[i].onLocal.forceWorld));
    }
    if (frame == 0) divergentAtFirst = divergent[0] && divergent[1];
    for (std::size_t i = 0; i < 2; ++i)
      integrate(model, bodies[i], c[i].onLocal.forceWorld, c[i].onLocal.torqueWorld, kDtS);
  }
  EXPECT_TRUE(divergentAtFirst);
  EXPECT_FALSE(divergent[0] || divergent[1]);
  EXPECT_LT(glm::length(bodies[1].comWorld - bodies[0].comWorld), 1e-6);
  // the spring alone at 50 mm would pull 5 times as hard as at the bound
  EXPECT_LT(strongestN, 1.5 * gains.linearStiffnessNPerM * 0.01);
}

/// Two free instances integrated at 1 kHz, 5 mm apart at first, each coupled to the
/// other's state as it arrives (DelayedStream). Returns how far apart they
/// are after `seconds`, m.
double distanceApartM(const CouplingGains& shared, double delayS, double seconds) {
  const RigidBodyModel model = offsetBoxModel(1.0);
  std::array<RigidBodyState, 2> bodies = {restingState(model), instance(model, glm::dvec3(0.005, 0.0, 0.0))};
  const int delayFrames = static_cast<int>(std::lround(delayS / kDtS));
  std::array<test::DelayedStream, 2> streams = {test::DelayedStream(delayFrames),
                                                test::DelayedStream(delayFrames)};
  const int frames = static_cast<int>(std::lround(seconds / kDtS));
  for (int frame = 0; frame < frames; ++frame) {
    for (std::size_t i = 0; i < 2; ++i) streams[i].send(frame, bodies[i]);
    std::array<SharedCoupling, 2> coupling{};
    for (std::size_t i = 0; i < 2; ++i) {
      // the other's newest state that has arrived, as old as it is
      const test::DelayedStream::Sent* newest = streams[1 - i].newest(frame);
      if (newest == nullptr) continue;
      const std::vector<RemoteInstance> remote = {{newest->state, (frame - newest->frame) * kDtS}};
      coupling[i] = sharedCouplingWrench(shared, model, bodies[i], remote);
    }
    for (std::size_t i = 0; i < 2; ++i)
      integrate(model, bodies[i], coupling[i].onLocal.forceWorld, coupling[i].onLocal.torqueWorld, kDtS);
  }
  return glm::length(bodies[1].comWorld - bodies[0].comWorld);
}

TEST(SharedCoupling, TwoFreeInstancesMeetAcrossADelayWhenTheStiffnessIsWithinItsBound) {
  // ω_n·τ = 0.25, half the first-order bound (shared_coupling.h): they meet. At the
  // handle's ω_n across the same delay they do not
  const RigidBodyModel model = offsetBoxModel(1.0);
  const double delayS = 0.02;
  const CouplingGains stiffest = defaultCouplingGains(model, kDtS);
  const double omegaN = std::sqrt(stiffest.linearStiffnessNPerM / model.massKg);
  const CouplingGains soft = scaledCouplingGains(stiffest, model, std::pow(0.25 / delayS / omegaN, 2.0), 1.0);
  const double softM = distanceApartM(soft, delayS, 5.0);
  const double stiffM = distanceApartM(stiffest, delayS, 5.0);
  std::printf("[ figures  ] 20 ms apart, after 5 s: %.3g m (omega_n tau 0.25), %.3g m (the handle's, %.1f)\n",
              softM, stiffM, omegaN * delayS);
  EXPECT_LT(softM, 1e-6);
  EXPECT_FALSE(stiffM < 1e-3);
}

}  // namespace
}  // namespace voxhap
