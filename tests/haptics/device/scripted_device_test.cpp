#include "haptics/device/scripted_device.h"

#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "haptics/core/error.h"
#include "support/rigid_body_fixtures.h"

namespace voxhap {
namespace {

constexpr double kDtS = 1e-3;

/// Still until 1 s; then to (0.1, 0.2, −0.3) m and a quarter turn about z at 2 s; still after.
MotionScript moveAndTurn() {
  return parseMotionScript(
      "0 1 0 0 0 0 0 0\n"
      "1 1 0 0 0 0 0 0\n"
      "2 0.7071067811865476 0 0 0.7071067811865476 0.1 0.2 -0.3\n",
      "move.txt");
}

TEST(ScriptedDevice, HandlePoseIsTheScriptPose) {
  ScriptedDevice device(moveAndTurn());
  for (double t : {0.0, 0.5, 1.25, 1.5, 2.0, 3.0}) {
    const Pose expected = device.script().sample(t);
    const Pose actual = device.handlePose(t);
    EXPECT_EQ(actual.position, expected.position) << t;
    EXPECT_EQ(actual.orientation, expected.orientation) << t;
  }
}

TEST(ScriptedDevice, VelocityIsTheBackwardDifferenceOverOnePeriod) {
  ScriptedDevice device(moveAndTurn());
  // inside the moving segment the script moves at constant rates
  const HandleVelocity moving = device.handleVelocity(1.5);
  EXPECT_NEAR(glm::length(moving.linearWorld - glm::dvec3(0.1, 0.2, -0.3)), 0.0, 1e-9);
  EXPECT_NEAR(glm::length(moving.angularWorld - glm::dvec3(0.0, 0.0, std::numbers::pi / 2.0)), 0.0, 1e-9);
  // still before and after
  EXPECT_EQ(device.handleVelocity(0.5).linearWorld, glm::dvec3(0.0));
  EXPECT_EQ(device.handleVelocity(2.5).angularWorld, glm::dvec3(0.0));
  // the first period after the motion ends still sees the last bit of it (causal)
  EXPECT_GT(glm::length(device.handleVelocity(2.0005).linearWorld), 0.0);
}

TEST(ScriptedDevice, RecordsTheLastFeedback) {
  ScriptedDevice device(moveAndTurn());
  EXPECT_EQ(device.feedbackCount(), 0u);
  EXPECT_EQ(device.lastFeedback().forceWorld, glm::dvec3(0.0));
  CouplingWrench w;
  w.forceWorld = glm::dvec3(1.0, 2.0, 3.0);
  device.setFeedback(w);
  w.torqueWorld = glm::dvec3(0.0, 0.0, 0.25);
  device.setFeedback(w);
  EXPECT_EQ(device.feedbackCount(), 2u);
  EXPECT_EQ(device.lastFeedback().torqueWorld, glm::dvec3(0.0, 0.0, 0.25));
}

TEST(ScriptedDevice, RejectsBadPeriodOrLimits) {
  EXPECT_THROW(ScriptedDevice(moveAndTurn(), DeviceLimits{}, 0.0), Error);
  EXPECT_THROW(ScriptedDevice(moveAndTurn(), DeviceLimits{}, std::numeric_limits<double>::quiet_NaN()),
               Error);
  DeviceLimits limits;
  limits.maxForceN = -1.0;
  try {
    ScriptedDevice device(moveAndTurn(), limits);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("scripted device (move.txt): device limit maxForceN"),
              std::string::npos)
        << e.what();
  }
}

/// The 1 kHz loop in miniature: read the handle, couple, integrate, feed back.
struct LoopResult {
  RigidBodyState state;
  CouplingWrench lastFeedback;
  double worstFeedbackN = 0.0;
};

LoopResult runLoop(const RigidBodyModel& model, ScriptedDevice& device, int frames) {
  const CouplingGains gains = defaultCouplingGains(model, kDtS);
  LoopResult r;
  r.state = restingState(model);
  for (int i = 1; i <= frames; ++i) {
    const double t = i * kDtS;
    const HandleVelocity v = device.handleVelocity(t);
    const CouplingWrench onBody =
        couplingWrench(gains, device.handlePose(t), v.linearWorld, v.angularWorld, model, r.state);
    const CouplingWrench feedback = deviceFeedback(onBody, device.limits());
    device.setFeedback(feedback);
    r.worstFeedbackN = std::max(r.worstFeedbackN, glm::length(feedback.forceWorld));
    integrate(model, r.state, onBody.forceWorld, onBody.torqueWorld, kDtS);
  }
  r.lastFeedback = device.lastFeedback();
  return r;
}

TEST(ScriptedDevice, DrivesACoupledBodyToTheScriptsEndPose) {
  const RigidBodyModel model = test::offsetBoxModel(0.5);
  DeviceLimits limits;
  limits.maxForceN = 5.0;
  ScriptedDevice device(moveAndTurn(), limits);
  const LoopResult r = runLoop(model, device, 3000);
  EXPECT_EQ(device.feedbackCount(), 3000u);
  const Pose end = device.handlePose(3.0);
  EXPECT_LT(glm::length(r.state.pose(model).position - end.position), 1e-6);
  EXPECT_LT(glm::length(rotationVector(end.orientation * glm::conjugate(r.state.orientation))), 1e-6);
  EXPECT_LE(r.worstFeedbackN, 5.0 + 1e-12);
  EXPECT_LT(glm::length(r.lastFeedback.forceWorld), 1e-6);  // at rest: nothing to feel
}

TEST(ScriptedDevice, SameScriptGivesBitIdenticalRuns) {
  const RigidBodyModel model = test::offsetBoxModel(0.5);
  ScriptedDevice first(moveAndTurn());
  ScriptedDevice second(moveAndTurn());
  const LoopResult a = runLoop(model, first, 1500);
  const LoopResult b = runLoop(model, second, 1500);
  EXPECT_EQ(std::memcmp(&a.state, &b.state, sizeof(RigidBodyState)), 0);
  EXPECT_EQ(a.lastFeedback.forceWorld, b.lastFeedback.forceWorld);
  EXPECT_EQ(a.lastFeedback.torqueWorld, b.lastFeedback.torqueWorld);
}

}  // namespace
}  // namespace voxhap
