#include "haptics/dynamics/virtual_coupling.h"

#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "haptics/core/error.h"
#include "support/rigid_body_fixtures.h"

namespace voxhap {
namespace {

constexpr double kDtS = 1e-3;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

using test::offsetBoxModel;

/// A handle pose away from the loaded placement: shifted 2.7 cm and turned 0.54 rad about
/// the local origin, which puts the target of the centre of mass (0.37 m from that origin)
/// about 0.2 m from where it starts.
Pose displacedHandle() {
  return Pose{glm::dvec3(0.02, -0.01, 0.015), quatFromRotationVector(glm::dvec3(0.2, -0.3, 0.4))};
}

/// Distance of the body's centre of mass from its target, m, and angle to the handle, rad.
struct TrackingError {
  double positionM;
  double angleRad;
};

TrackingError trackingError(const RigidBodyModel& model, const RigidBodyState& state, const Pose& handle) {
  return {glm::length(apply(handle, model.comLocal) - state.comWorld),
          glm::length(rotationVector(handle.orientation * glm::conjugate(state.orientation)))};
}

/// Runs the body, starting at rest where it was loaded, coupled to a fixed handle for
/// `steps` frames; returns the error after every frame.
std::vector<TrackingError> settle(const RigidBodyModel& model, const CouplingGains& gains, const Pose& handle,
                                  int steps, RigidBodyState* finalState = nullptr) {
  RigidBodyState state = restingState(model);
  std::vector<TrackingError> errors;
  errors.reserve(static_cast<std::size_t>(steps));
  for (int i = 0; i < steps; ++i) {
    const CouplingWrench w = couplingWrench(gains, handle, glm::dvec3(0.0), glm::dvec3(0.0), model, state);
    integrate(model, state, w.forceWorld, w.torqueWorld, kDtS);
    errors.push_back(trackingError(model, state, handle));
  }
  if (finalState) *finalState = state;
  return errors;
}

CouplingGains scaledStiffness(CouplingGains gains, double multiple) {
  gains.linearStiffnessNPerM *= multiple;
  gains.angularStiffnessNmPerRad *= multiple;
  return gains;
}

TEST(Coupling, DefaultGainsFollowFromFrameRateMassAndSmallestInertia) {
  const RigidBodyModel model = offsetBoxModel(2.0);
  const CouplingGains g = defaultCouplingGains(model, kDtS);
  const double omega = 0.25 / kDtS;
  EXPECT_DOUBLE_EQ(g.linearStiffnessNPerM, 2.0 * omega * omega);
  EXPECT_DOUBLE_EQ(g.linearDampingNsPerM, 2.0 * 2.0 * omega);
  const double iMin = model.principalInertiaKgM2.x;
  EXPECT_DOUBLE_EQ(g.angularStiffnessNmPerRad, iMin * omega * omega);
  EXPECT_DOUBLE_EQ(g.angularDampingNmsPerRad, 2.0 * iMin * omega);
  // the smallest principal moment of the 10 × 5 × 2 cm box is about its long axis
  EXPECT_NEAR(iMin, 2.0 / 12.0 * (0.05 * 0.05 + 0.02 * 0.02), 1e-9);
}

TEST(Coupling, DeviceStiffnessLimitLowersGainsKeepingTheDampingRatio) {
  const RigidBodyModel model = offsetBoxModel(1.0);
  DeviceLimits limits;
  limits.maxLinearStiffnessNPerM = 3000.0;
  limits.maxAngularStiffnessNmPerRad = 2.0;
  const CouplingGains g = defaultCouplingGains(model, kDtS, limits);
  EXPECT_EQ(g.linearStiffnessNPerM, 3000.0);
  EXPECT_NEAR(g.linearDampingNsPerM, 2.0 * std::sqrt(3000.0 * 1.0), 1e-9);
  EXPECT_EQ(g.angularStiffnessNmPerRad, 2.0);
  EXPECT_NEAR(g.angularDampingNmsPerRad, 2.0 * std::sqrt(2.0 * model.principalInertiaKgM2.x), 1e-12);
  // limits above the defaults change nothing
  limits.maxLinearStiffnessNPerM = 1e9;
  limits.maxAngularStiffnessNmPerRad = 1e9;
  const CouplingGains unclamped = defaultCouplingGains(model, kDtS, limits);
  EXPECT_EQ(unclamped.linearStiffnessNPerM, defaultCouplingGains(model, kDtS).linearStiffnessNPerM);
}

TEST(Coupling, BadFramePeriodOrLimitsThrow) {
  const RigidBodyModel model = offsetBoxModel(1.0);
  EXPECT_THROW(defaultCouplingGains(model, 0.0), Error);
  EXPECT_THROW(defaultCouplingGains(model, kNaN), Error);
  DeviceLimits limits;
  limits.maxTorqueNm = -1.0;
  try {
    defaultCouplingGains(model, kDtS, limits);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("maxTorqueNm"), std::string::npos) << e.what();
  }
  limits = DeviceLimits{};
  limits.maxLinearStiffnessNPerM = 0.0;
  EXPECT_THROW(validateDeviceLimits(limits, "phantom"), Error);
}

TEST(Coupling, HandleAtTheBodyPoseGivesZeroWrench) {
  const RigidBodyModel model = offsetBoxModel(1.0);
  const CouplingGains gains = defaultCouplingGains(model, kDtS);
  const Pose pose = displacedHandle();
  const RigidBodyState state = restingState(model, pose);
  const CouplingWrench w = couplingWrench(gains, pose, glm::dvec3(0.0), glm::dvec3(0.0), model, state);
  EXPECT_LT(glm::length(w.forceWorld), 1e-9);
  EXPECT_LT(glm::length(w.torqueWorld), 1e-12);
}

TEST(Coupling, TranslatedHandlePullsThroughTheCentreOfMass) {
  const RigidBodyModel model = offsetBoxModel(1.0);
  const CouplingGains gains = defaultCouplingGains(model, kDtS);
  const RigidBodyState state = restingState(model);
  const glm::dvec3 shift(0.001, -0.002, 0.0005);
  const CouplingWrench w =
      couplingWrench(gains, Pose{shift, identityQuat()}, glm::dvec3(0.0), glm::dvec3(0.0), model, state);
  EXPECT_NEAR(glm::length(w.forceWorld - gains.linearStiffnessNPerM * shift), 0.0, 1e-9);
  EXPECT_EQ(w.torqueWorld, glm::dvec3(0.0));
}

TEST(Coupling, TurnedHandleTwistsTheShortWay) {
  const RigidBodyModel model = offsetBoxModel(1.0);
  const CouplingGains gains = defaultCouplingGains(model, kDtS);
  const RigidBodyState state = restingState(model);
  const glm::dvec3 z(0.0, 0.0, 1.0);
  const double deg = std::numbers::pi / 180.0;
  for (double turnDeg : {30.0, 350.0}) {
    const Pose handle{glm::dvec3(0.0), glm::angleAxis(turnDeg * deg, z)};
    const CouplingWrench w = couplingWrench(gains, handle, glm::dvec3(0.0), glm::dvec3(0.0), model, state);
    const double shortest = turnDeg > 180.0 ? turnDeg - 360.0 : turnDeg;
    EXPECT_NEAR(glm::length(w.torqueWorld - gains.angularStiffnessNmPerRad * shortest * deg * z), 0.0, 1e-9)
        << turnDeg;
    // the force pulls the centre of mass to where the turned handle puts it
    const glm::dvec3 target = handle.orientation * model.comLocal;
    EXPECT_NEAR(glm::length(w.forceWorld - gains.linearStiffnessNPerM * (target - state.comWorld)), 0.0,
                1e-6);
  }
}

TEST(Coupling, DampersActOnVelocityDifferences) {
  const RigidBodyModel model = offsetBoxModel(1.0);
  const CouplingGains gains = defaultCouplingGains(model, kDtS);
  // body moving, handle still at the same pose
  RigidBodyState moving = restingState(model);
  moving.linearVelocityWorld = glm::dvec3(0.1, 0.0, -0.2);
  moving.angularVelocityWorld = glm::dvec3(0.0, 0.5, 0.0);
  CouplingWrench w = couplingWrench(gains, Pose{}, glm::dvec3(0.0), glm::dvec3(0.0), model, moving);
  EXPECT_NEAR(glm::length(w.forceWorld + gains.linearDampingNsPerM * moving.linearVelocityWorld), 0.0, 1e-12);
  EXPECT_NEAR(glm::length(w.torqueWorld + gains.angularDampingNmsPerRad * moving.angularVelocityWorld), 0.0,
              1e-15);
  // handle turning about its origin: its grasp point (the centre of mass) moves
  const RigidBodyState still = restingState(model);
  const glm::dvec3 spin(0.0, 0.0, 2.0);
  w = couplingWrench(gains, Pose{}, glm::dvec3(0.0), spin, model, still);
  EXPECT_NEAR(glm::length(w.forceWorld - gains.linearDampingNsPerM * glm::cross(spin, model.comLocal)), 0.0,
              1e-9);
  EXPECT_NEAR(glm::length(w.torqueWorld - gains.angularDampingNmsPerRad * spin), 0.0, 1e-15);
}

class CouplingSettles : public ::testing::TestWithParam<double> {};

// The body starts where it was loaded, the handle ~0.2 m and 0.54 rad away. The largest
// error in each 50 ms window must shrink from window to window (no growing or sustained
// oscillation) until it reaches rounding level, and be below 1e-6 after 2 s.
TEST_P(CouplingSettles, OnAFixedHandleAtDefaultGains) {
  const RigidBodyModel model = offsetBoxModel(GetParam());
  const Pose handle = displacedHandle();
  const std::vector<TrackingError> errors = settle(model, defaultCouplingGains(model, kDtS), handle, 2000);
  constexpr std::size_t kWindow = 50;
  TrackingError previous{kInf, kInf};
  for (std::size_t start = 0; start < errors.size(); start += kWindow) {
    TrackingError envelope{0.0, 0.0};
    for (std::size_t i = start; i < start + kWindow; ++i) {
      envelope.positionM = std::max(envelope.positionM, errors[i].positionM);
      envelope.angleRad = std::max(envelope.angleRad, errors[i].angleRad);
    }
    if (previous.positionM > 1e-13) {
      EXPECT_LT(envelope.positionM, previous.positionM) << "window at " << start;
    }
    if (previous.angleRad > 1e-13) {
      EXPECT_LT(envelope.angleRad, previous.angleRad) << "window at " << start;
    }
    previous = envelope;
  }
  EXPECT_LT(errors.back().positionM, 1e-6);
  EXPECT_LT(errors.back().angleRad, 1e-6);
}

INSTANTIATE_TEST_SUITE_P(Masses, CouplingSettles, ::testing::Values(0.01, 1.0, 1000.0));

class CouplingStiffer : public ::testing::TestWithParam<double> {};

TEST_P(CouplingStiffer, StillSettlesAtHigherStiffnessWithDefaultDamping) {
  for (double massKg : {0.01, 1.0, 1000.0}) {
    const RigidBodyModel model = offsetBoxModel(massKg);
    const CouplingGains gains = scaledStiffness(defaultCouplingGains(model, kDtS), GetParam());
    const TrackingError initial = trackingError(model, restingState(model), displacedHandle());
    const std::vector<TrackingError> errors = settle(model, gains, displacedHandle(), 2000);
    for (const TrackingError& e : errors) {  // overshoot, if any, stays below the initial error
      ASSERT_LT(e.positionM, initial.positionM) << massKg << " kg";
      ASSERT_LT(e.angleRad, initial.angleRad) << massKg << " kg";
    }
    EXPECT_LT(errors.back().positionM, 1e-6) << massKg << " kg";
    EXPECT_LT(errors.back().angleRad, 1e-6) << massKg << " kg";
  }
}

INSTANTIATE_TEST_SUITE_P(Multiples, CouplingStiffer, ::testing::Values(1.5, 3.0));

// Stability margin. For semi-implicit Euler with fixed damping, raising the stiffness by s
// stays stable while s·(ω_n·h)² + 4·ζ·ω_n·h < 4, i.e. s < 48 at the defaults
// (virtual_coupling.cpp). The full 6-DOF integrator has the same limit: bisecting it on this
// body gives 47.99 (the last bit is the slow decay right at the boundary). Check both sides.
TEST(Coupling, StiffnessMarginMatchesTheSemiImplicitEulerBound) {
  const RigidBodyModel model = offsetBoxModel(1.0);
  const CouplingGains defaults = defaultCouplingGains(model, kDtS);
  RigidBodyState state;
  const std::vector<TrackingError> stable =
      settle(model, scaledStiffness(defaults, 47.0), displacedHandle(), 2000);
  EXPECT_LT(stable.back().positionM, 1e-6);
  EXPECT_LT(stable.back().angleRad, 1e-6);
  const std::vector<TrackingError> unstable =
      settle(model, scaledStiffness(defaults, 49.0), displacedHandle(), 1000, &state);
  EXPECT_TRUE(unstable.back().positionM > 1.0 || state.skippedSteps > 0) << unstable.back().positionM;
}

TEST(Coupling, SameInputsGiveBitIdenticalStates) {
  const RigidBodyModel model = offsetBoxModel(1.0);
  const CouplingGains gains = defaultCouplingGains(model, kDtS);
  RigidBodyState a, b;
  settle(model, gains, displacedHandle(), 500, &a);
  settle(model, gains, displacedHandle(), 500, &b);
  EXPECT_EQ(std::memcmp(&a, &b, sizeof(RigidBodyState)), 0);
}

TEST(Coupling, DeviceFeedbackIsTheNegatedWrenchWithinLimits) {
  CouplingWrench onBody;
  onBody.forceWorld = glm::dvec3(1.0, -2.0, 3.0);
  onBody.torqueWorld = glm::dvec3(-0.1, 0.2, 0.0);
  const CouplingWrench f = deviceFeedback(onBody, DeviceLimits{});
  EXPECT_EQ(f.forceWorld, -onBody.forceWorld);
  EXPECT_EQ(f.torqueWorld, -onBody.torqueWorld);
  EXPECT_FALSE(f.forceClamped || f.torqueClamped || f.nonFiniteZeroed);
}

TEST(Coupling, DeviceFeedbackIsClampedByMagnitudeKeepingDirection) {
  CouplingWrench onBody;
  onBody.forceWorld = glm::dvec3(30.0, 40.0, 0.0);
  onBody.torqueWorld = glm::dvec3(0.0, 0.0, 0.5);
  DeviceLimits limits;
  limits.maxForceN = 10.0;
  limits.maxTorqueNm = 0.2;
  const CouplingWrench f = deviceFeedback(onBody, limits);
  EXPECT_NEAR(glm::length(f.forceWorld - glm::dvec3(-6.0, -8.0, 0.0)), 0.0, 1e-14);
  EXPECT_NEAR(glm::length(f.torqueWorld - glm::dvec3(0.0, 0.0, -0.2)), 0.0, 1e-15);
  EXPECT_TRUE(f.forceClamped);
  EXPECT_TRUE(f.torqueClamped);
  // huge but finite: no overflow on the way to the limit
  onBody.forceWorld = glm::dvec3(1e300, 1e300, 0.0);
  const CouplingWrench g = deviceFeedback(onBody, limits);
  EXPECT_NEAR(glm::length(g.forceWorld - 10.0 * glm::normalize(glm::dvec3(-1.0, -1.0, 0.0))), 0.0, 1e-13);
  // a zero limit renders nothing
  limits.maxForceN = 0.0;
  EXPECT_EQ(deviceFeedback(onBody, limits).forceWorld, glm::dvec3(0.0));
}

TEST(Coupling, DeviceFeedbackZeroesNonFiniteWrenches) {
  for (double bad : {kNaN, kInf, -kInf}) {
    CouplingWrench onBody;
    onBody.forceWorld = glm::dvec3(1.0, 2.0, 3.0);
    onBody.torqueWorld = glm::dvec3(0.0, bad, 0.0);
    const CouplingWrench f = deviceFeedback(onBody, DeviceLimits{});
    EXPECT_TRUE(f.nonFiniteZeroed);
    EXPECT_EQ(f.forceWorld, glm::dvec3(0.0));
    EXPECT_EQ(f.torqueWorld, glm::dvec3(0.0));
    std::swap(onBody.forceWorld, onBody.torqueWorld);
    EXPECT_TRUE(deviceFeedback(onBody, DeviceLimits{}).nonFiniteZeroed);
  }
}

}  // namespace
}  // namespace voxhap
