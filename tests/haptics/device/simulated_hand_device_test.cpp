// The simulated force-feedback device: the handle follows the hand's target, the
// feedback pushes it back by F/k, bad parameters are refused by name, the frame calls do
// not allocate; and, closed around the real engine, a box pressed onto a plate holds the
// hand back by the force it renders, within the device's limits, without sinking into the
// plate and without growing oscillation.
#include "haptics/device/simulated_hand_device.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "app/exact_checks.h"
#include "haptics/core/error.h"
#include "haptics/device/device_profile.h"
#include "support/allocation_counter.h"
#include "support/contact_scenes.h"
#include "support/fp_traps.h"
#include "support/sanitizers.h"

namespace voxhap {
namespace {

constexpr double kDtS = 1e-3;

Pose moved(double x, double y, double z, const glm::dvec3& rotationRad = glm::dvec3(0.0)) {
  return Pose{glm::dvec3(x, y, z), quatFromRotationVector(rotationRad)};
}

MotionScript still(const Pose& pose) {
  return MotionScript({{0.0, pose}}, "still");
}

/// Runs `frames` frames of the device alone: pose, velocity, then `feedback` (as the loop).
void runAlone(SimulatedHandDevice& device, int frames, const CouplingWrench& feedback = {}) {
  const int first = static_cast<int>(std::lround(device.timeS() / kDtS)) + 1;
  for (int i = first; i < first + frames; ++i) {
    device.handlePose(i * kDtS);
    device.handleVelocity(i * kDtS);
    device.setFeedback(feedback);
  }
}

double rotationErrorRad(const glm::dquat& a, const glm::dquat& b) {
  return glm::length(rotationVector(a * glm::conjugate(b)));
}

// ---------------------------------------------------------------------------------------
// the device alone

TEST(SimulatedHandDevice, FollowsAConstantTargetAndSettlesOnIt) {
  const Pose target = moved(0.01, -0.02, 0.005, glm::dvec3(0.0, 0.0, 0.3));
  SimulatedHandParams params;
  params.graspLocal = glm::dvec3(0.002, 0.0, 0.001);
  SimulatedHandDevice device(still(target), params);
  device.grabbed(Pose{});
  const double startErrorM = glm::length(device.graspWorld() - device.handTargetGraspWorld(0.0));
  // a body, not a teleport: after 10 ms it has covered little of the way (critically
  // damped at ω = 50 rad/s: (1 + ωt)·e^(−ωt) = 0.91 of the error left)
  runAlone(device, 10);
  EXPECT_GT(glm::length(device.graspWorld() - device.handTargetGraspWorld(0.01)), 0.8 * startErrorM);
  runAlone(device, 490);
  const Pose pose = device.handlePose(0.5);
  EXPECT_LT(glm::length(pose.position - target.position), 1e-7);
  EXPECT_LT(rotationErrorRad(pose.orientation, target.orientation), 1e-6);
  EXPECT_LT(glm::length(device.handleVelocity(0.5).linearWorld), 1e-6);
  EXPECT_EQ(device.steps(), 1000u);  // 1 ms frames in two 0.5 ms substeps
}

TEST(SimulatedHandDevice, ConstantFeedbackHoldsTheHandleAtTargetPlusForceOverStiffness) {
  const Pose target = moved(0.0, 0.0, -0.01);
  const SimulatedHandParams params;
  SimulatedHandDevice device(still(target), params);
  CouplingWrench feedback;
  feedback.forceWorld = glm::dvec3(1.0, -0.5, 3.0);
  feedback.torqueWorld = glm::dvec3(0.0, 0.01, 0.02);
  runAlone(device, 1000, feedback);
  const glm::dvec3 expectedM = target.position + feedback.forceWorld / params.handStiffnessNPerM;
  EXPECT_LT(glm::length(device.handlePose(1.0).position - expectedM), 1e-8);
  const glm::dvec3 expectedRad = feedback.torqueWorld / params.handAngularStiffnessNmPerRad;
  EXPECT_LT(glm::length(rotationVector(device.handlePose(1.0).orientation) - expectedRad), 1e-8);
  EXPECT_LT(glm::length(device.handForceWorld() + feedback.forceWorld), 1e-6);  // the hand holds it
  EXPECT_EQ(device.feedbackCount(), 1000u);
  EXPECT_DOUBLE_EQ(device.maxFeedbackForceN(), glm::length(feedback.forceWorld));
}

TEST(SimulatedHandDevice, FeedbackBeyondTheLimitsPushesOnlyAsHardAsTheLimits) {
  DeviceLimits limits = deviceProfile("desktop-6dof").limits;
  const SimulatedHandParams params;
  SimulatedHandDevice device(still(Pose{}), params, limits);
  CouplingWrench feedback;
  feedback.forceWorld = glm::dvec3(0.0, 0.0, 100.0);
  runAlone(device, 1000, feedback);
  EXPECT_NEAR(device.handlePose(1.0).position.z, limits.maxForceN / params.handStiffnessNPerM, 1e-8);
  EXPECT_DOUBLE_EQ(device.maxFeedbackForceN(), 100.0);  // recorded as given
  // a NaN is applied as nothing: the handle returns to the target
  feedback.forceWorld.x = std::numeric_limits<double>::quiet_NaN();
  runAlone(device, 1000, feedback);
  EXPECT_LT(glm::length(device.handlePose(2.0).position), 1e-8);
  EXPECT_EQ(device.nonFiniteFeedback(), 1000u);
}

TEST(SimulatedHandDevice, VelocityIsTheIntegratedOneAndReadingItDoesNotStep) {
  SimulatedHandParams params;
  params.graspLocal = glm::dvec3(0.0, 0.0, 0.05);
  SimulatedHandDevice device(still(moved(0.0, 0.01, 0.0, glm::dvec3(0.2, 0.0, 0.0))), params);
  device.grabbed(Pose{});
  const Pose before = device.handlePose(0.0);
  const Pose after = device.handlePose(kDtS);
  const std::uint64_t steps = device.steps();
  const HandleVelocity v = device.handleVelocity(kDtS);
  EXPECT_EQ(device.steps(), steps);
  EXPECT_EQ(device.handlePose(kDtS).position, after.position);
  // the local origin's velocity from the grasp point's and the turn about it
  const glm::dvec3 leverWorld = after.orientation * params.graspLocal;
  EXPECT_LT(glm::length(v.linearWorld + glm::cross(v.angularWorld, leverWorld) - device.graspVelocityWorld()),
            1e-15);
  EXPECT_GT(v.linearWorld.y, 0.0);
  EXPECT_GT(v.angularWorld.x, 0.0);
  EXPECT_GT(after.position.y, before.position.y);
}

TEST(SimulatedHandDevice, AStallIsCutToTheLongestIntervalAndDoesNotFlingTheHandle) {
  const SimulatedHandParams params;
  // the target jumps 20 cm at 1 s
  SimulatedHandDevice device(
      MotionScript({{0.0, Pose{}}, {1.0, Pose{}}, {1.001, moved(0.2, 0.0, 0.0)}}, "jump"), params);
  runAlone(device, 999);
  const std::uint64_t steps = device.steps();
  device.handlePose(3.0);  // two seconds late
  EXPECT_EQ(device.clampedIntervals(), 1u);
  EXPECT_EQ(device.steps() - steps, 20u);  // 10 ms in 0.5 ms substeps
  // 10 ms of the hand's pull: v ≤ (k/m)·0.2 m·10 ms = 5 m/s
  EXPECT_LT(glm::length(device.graspVelocityWorld()), 5.0);
  EXPECT_GT(device.graspWorld().x, 0.0);
  EXPECT_LT(device.graspWorld().x, 0.025);  // ½·(k/m)·0.2 m·(10 ms)²
  EXPECT_DOUBLE_EQ(device.timeS(), 3.0);
  // time running backwards restarts the clock without a step
  device.handlePose(1.5);
  EXPECT_EQ(device.steps() - steps, 20u);
  EXPECT_DOUBLE_EQ(device.timeS(), 1.5);
  // a grab starts the handle where the object is, at rest, and the clock at 0
  device.grabbed(moved(0.0, 0.01, 0.0));
  EXPECT_EQ(device.timeS(), 0.0);
  EXPECT_EQ(device.handlePose(0.0).position, glm::dvec3(0.0, 0.01, 0.0));
  EXPECT_EQ(device.handleVelocity(0.0).linearWorld, glm::dvec3(0.0));
}

TEST(SimulatedHandDevice, SameInputsGiveBitIdenticalHandles) {
  const MotionScript script({{0.0, Pose{}}, {0.3, moved(0.01, 0.0, -0.02, glm::dvec3(0.1, 0.2, 0.0))}}, "s");
  SimulatedHandDevice a(script);
  SimulatedHandDevice b(script);
  CouplingWrench feedback;
  for (int i = 1; i <= 500; ++i) {
    feedback.forceWorld = glm::dvec3(0.0, std::sin(0.01 * i), 2.0);
    const Pose pa = a.handlePose(i * kDtS);
    const Pose pb = b.handlePose(i * kDtS);
    ASSERT_EQ(std::memcmp(&pa, &pb, sizeof(Pose)), 0) << i;
    a.setFeedback(feedback);
    b.setFeedback(feedback);
  }
}

TEST(SimulatedHandDevice, RejectsBadParametersNamingTheField) {
  auto expectRefused = [](const std::function<void(SimulatedHandParams&)>& spoil, const std::string& field) {
    SimulatedHandParams params;
    spoil(params);
    try {
      SimulatedHandDevice device(still(Pose{}), params);
      ADD_FAILURE() << field << ": no error";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("simulated hand device (still): simulated hand " + field),
                std::string::npos)
          << e.what();
    }
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const double bad : {0.0, -1.0, nan, inf}) {
    expectRefused([&](SimulatedHandParams& p) { p.handleMassKg = bad; }, "handleMassKg");
    expectRefused([&](SimulatedHandParams& p) { p.handleInertiaKgM2 = bad; }, "handleInertiaKgM2");
    expectRefused([&](SimulatedHandParams& p) { p.handStiffnessNPerM = bad; }, "handStiffnessNPerM");
    expectRefused([&](SimulatedHandParams& p) { p.handDampingNsPerM = bad; }, "handDampingNsPerM");
    expectRefused([&](SimulatedHandParams& p) { p.handAngularStiffnessNmPerRad = bad; },
                  "handAngularStiffnessNmPerRad");
    expectRefused([&](SimulatedHandParams& p) { p.handAngularDampingNmsPerRad = bad; },
                  "handAngularDampingNmsPerRad");
    expectRefused([&](SimulatedHandParams& p) { p.maxSubstepS = bad; }, "maxSubstepS");
    expectRefused([&](SimulatedHandParams& p) { p.maxIntervalS = bad; }, "maxIntervalS");
  }
  expectRefused([&](SimulatedHandParams& p) { p.graspLocal.y = nan; }, "graspLocal.y");
  expectRefused([&](SimulatedHandParams& p) { p.maxIntervalS = 1e-4; }, "maxIntervalS");  // < a substep
  expectRefused([&](SimulatedHandParams& p) { p.maxIntervalS = 1.0; }, "maxIntervalS");   // 2000 substeps
  // stable but inaccurate: 5 ms substeps on a stiff hand (a + 2c = 2.25)
  expectRefused(
      [&](SimulatedHandParams& p) {
        p.maxSubstepS = 5e-3;
        p.maxIntervalS = 0.05;
        p.handStiffnessNPerM = 10000.0;
      },
      "maxSubstepS (a + 2c with handStiffnessNPerM");
  DeviceLimits limits;
  limits.maxForceN = inf;
  try {
    SimulatedHandDevice device(still(Pose{}), {}, limits);
    ADD_FAILURE() << "infinite force limit: no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("device limit maxForceN"), std::string::npos) << e.what();
  }
}

TEST(SimulatedHandDevice, FrameCallsAllocateNothing) {
  SimulatedHandDevice device(MotionScript({{0.0, Pose{}}, {0.5, moved(0.0, 0.0, -0.01)}}, "press"));
  CouplingWrench feedback;
  feedback.forceWorld = glm::dvec3(0.0, 0.0, 2.0);
  const test::AllocationCounter allocations;
  for (int i = 1; i <= 1000; ++i) {
    device.handlePose(i * kDtS);
    device.handleVelocity(i * kDtS);
    device.setFeedback(feedback);
  }
  device.grabbed(Pose{});
  device.handlePose(5.0);  // a stall
  EXPECT_EQ(allocations.count(), 0u);
  EXPECT_GT(device.steps(), 0u);
}

// ---------------------------------------------------------------------------------------
// closed loop with the engine

constexpr double kVoxelM = 0.001;
/// The box's bottom over the plate's top as loaded: beyond where the force layer holds it
/// (two voxels), so that it starts free.
constexpr double kGapM = 0.0025;
constexpr double kRampMPerS = 0.05;                             ///< how fast the hand's target goes down
constexpr int kFrames = 2000;                                   ///< 2 s at 1 kHz
constexpr int kCheckEvery = test::kAddressSanitizer ? 50 : 10;  ///< exact checks, frames
constexpr double kBoundVoxels = 0.1;                            ///< what the engine promises (depth_limit.h)

/// The test::plate (top face z = 0) and a 20 × 20 × 10 mm steel box kGapM over it.
Scene boxOverPlate() {
  Scene scene;
  scene.objects.push_back(test::plate());
  scene.objects.push_back(test::meshObject("box", ObjectRole::Dynamic, [](TriangleMesh& m) {
    appendBox(m, test::at(0.0003, -0.0002, kGapM + 0.005), glm::dvec3(0.01, 0.01, 0.005));
  }));
  return scene;
}

/// The hand's target: down at kRampMPerS to `pressM` below the contact (the box lowered
/// by kGapM), then held.
MotionScript pressBelowContact(double pressM) {
  const double downM = kGapM + pressM;
  return MotionScript({{0.0, Pose{}}, {downM / kRampMPerS, moved(0.0, 0.0, -downM)}}, "press");
}

struct LoopFigures {
  glm::dvec3 restFeedbackWorld{0.0};      ///< rendered at the end, N
  glm::dvec3 handleOverTargetWorld{0.0};  ///< handle grasp point − target's, at the end, m
  double boxOverTargetM = 0.0;            ///< box grasp point − target's, z, at the end, m
  double maxForceN = 0.0;                 ///< over the run
  double maxJumpN = 0.0;                  ///< largest frame-to-frame change of the rendered force
  int maxJumpFrame = 0;
  double maxHandleSpeedMPerS = 0.0;   ///< of the grasp point, over the run
  double depthM = 0.0;                ///< deepest exact penetration
  double firstHalfAmplitudeM = 0.0;   ///< peak-to-peak of the handle's z over 1.0–1.5 s
  double secondHalfAmplitudeM = 0.0;  ///< over 1.5–2.0 s
  double endSpeedMPerS = 0.0;         ///< handle grasp point, at the end
};

struct ClosedLoop {
  Scene scene = boxOverPlate();
  SceneModelOptions options;
  SimModel model;

  ClosedLoop() : options(makeOptions()), model(buildSceneModel(scene, {"box"}, options)) {}

  static SceneModelOptions makeOptions() {
    SceneModelOptions o = test::ampleCapacityOptions();
    o.staticVoxelSizeM = kVoxelM;
    o.pointSpacingM = kVoxelM;
    o.sim.deviceLimits = deviceProfile("desktop-6dof").limits;
    return o;
  }

  const glm::dvec3& comLocal() const { return model.objects[0].body.comLocal; }

  SimulatedHandParams handParams() const {
    SimulatedHandParams p;
    p.graspLocal = comLocal();
    return p;
  }

  /// Runs kFrames frames with `device` holding the box, checking exact penetration every
  /// kCheckEvery frames; `script` is the hand's target, for the figures at the end.
  LoopFigures run(const std::string& name, HapticDevice& device, const MotionScript& script) {
    LocalSimulation sim(model);
    cli::ExactChecks exact(scene, model, options, kVoxelM / kProbesPerVoxel);
    HapticDevice* devices[] = {&device};
    device.grabbed(objectPose(model, sim.state, 0));
    LoopFigures out;
    glm::dvec3 previousForce(0.0);
    glm::dvec3 previousGrasp = apply(objectPose(model, sim.state, 0), comLocal());
    double lowHigh[2][2] = {{1e9, -1e9}, {1e9, -1e9}};
    for (int frame = 0; frame < kFrames; ++frame) {
      {
        const test::FloatingPointTraps traps;
        sim.stepWithDevices(devices);
      }
      const glm::dvec3 force = sim.object(0).feedback.forceWorld;
      out.maxForceN = std::max(out.maxForceN, glm::length(force));
      if (glm::length(force - previousForce) > out.maxJumpN) {
        out.maxJumpN = glm::length(force - previousForce);
        out.maxJumpFrame = frame;
      }
      previousForce = force;
      const glm::dvec3 grasp = apply(sim.deviceHandles()[0].poseWorld, comLocal());
      const double speed = glm::length(grasp - previousGrasp) / kDtS;
      out.maxHandleSpeedMPerS = std::max(out.maxHandleSpeedMPerS, speed);
      out.endSpeedMPerS = speed;
      previousGrasp = grasp;
      if (frame >= kFrames / 2) {
        double* lh = lowHigh[frame >= 3 * kFrames / 4 ? 1 : 0];
        lh[0] = std::min(lh[0], grasp.z);
        lh[1] = std::max(lh[1], grasp.z);
      }
      if (frame % kCheckEvery == 0 || frame + 1 == kFrames) {
        for (const cli::ExactPairSample& pair : exact.measure(model, sim.state, false)) {
          out.depthM = std::max(out.depthM, pair.sample.depthM);
        }
      }
    }
    const double endS = sim.state.timeS;
    const glm::dvec3 targetGrasp = apply(script.sample(endS), comLocal());
    out.restFeedbackWorld = sim.object(0).feedback.forceWorld;
    out.handleOverTargetWorld = previousGrasp - targetGrasp;
    out.boxOverTargetM = apply(objectPose(model, sim.state, 0), comLocal()).z - targetGrasp.z;
    out.firstHalfAmplitudeM = lowHigh[0][1] - lowHigh[0][0];
    out.secondHalfAmplitudeM = lowHigh[1][1] - lowHigh[1][0];
    std::printf(
        "[ figures  ] %-32s rest feedback %.3f N, handle %.3f mm over target, box %.3f mm over target, "
        "max feedback %.3f N, max jump %.3f N (frame %d), handle up to %.1f mm/s, exact depth %.4f mm, "
        "amplitude %.2e then %.2e m\n",
        name.c_str(), glm::length(out.restFeedbackWorld), out.handleOverTargetWorld.z * 1e3,
        out.boxOverTargetM * 1e3, out.maxForceN, out.maxJumpN, out.maxJumpFrame,
        out.maxHandleSpeedMPerS * 1e3, out.depthM * 1e3, out.firstHalfAmplitudeM, out.secondHalfAmplitudeM);
    return out;
  }
};

TEST(SimulatedHandDevice, ClosedLoopTheBoxOnThePlateHoldsTheHandBack) {
  ClosedLoop loop;
  const CouplingGains& gains = loop.model.objects[0].gains;
  const DeviceLimits& limits = loop.model.deviceLimits;
  for (const double pressM : {0.01, 0.05}) {
    const std::string name = "hand " + std::to_string(int(pressM * 1e3)) + " mm below contact";
    const MotionScript script = pressBelowContact(pressM);
    SimulatedHandDevice device(script, loop.handParams(), limits);
    const LoopFigures f = loop.run(name, device, script);
    const double kHand = device.params().handStiffnessNPerM;
    const double restForceN = glm::length(f.restFeedbackWorld);

    // (a) the handle rests well above the hand's target, where the hand's spring balances
    // the rendered force: handle − target = F/k_hand
    EXPECT_GT(f.handleOverTargetWorld.z, 0.5 * std::min(pressM, limits.maxForceN / kHand)) << name;
    EXPECT_LT(glm::length(f.handleOverTargetWorld - f.restFeedbackWorld / kHand), 0.02 * restForceN / kHand)
        << name;
    // and the force is that of the coupling and the hand in series over the box's height
    // above the target, or the device's largest force
    const double kc = gains.linearStiffnessNPerM;
    const double seriesN = std::min(kc * kHand / (kc + kHand) * f.boxOverTargetM, limits.maxForceN);
    EXPECT_NEAR(restForceN, seriesN, 0.02 * seriesN) << name;
    EXPECT_GT(f.restFeedbackWorld.z, 0.0) << name << ": pushes the handle up, away from the plate";

    // (b) within the device's force, and continuous: the rendered force is the coupling's
    // spring-damper on the box–handle motion, which changes per frame by at most the
    // damper stopping the box (b_c·v, v ≤ the handle's speed) plus the spring over one
    // frame of both (k_c·(half a voxel of MaxTravel + v·dt))
    EXPECT_LE(f.maxForceN, limits.maxForceN + 1e-9) << name;
    EXPECT_LE(device.maxFeedbackForceN(), limits.maxForceN + 1e-9) << name;
    const double jumpBoundN = gains.linearDampingNsPerM * f.maxHandleSpeedMPerS +
                              kc * (0.5 * kVoxelM + f.maxHandleSpeedMPerS * kDtS);
    EXPECT_LE(f.maxJumpN, jumpBoundN) << name << " at frame " << f.maxJumpFrame;

    // (c) the box does not sink into the plate beyond the engine's promise
    EXPECT_LE(f.depthM, kBoundVoxels * kVoxelM) << name;

    // (d) the handle settles: the last half second moves no more than the one before, and
    // it ends at rest
    EXPECT_LE(f.secondHalfAmplitudeM, f.firstHalfAmplitudeM + 1e-9) << name;
    EXPECT_LT(f.secondHalfAmplitudeM, 1e-6) << name;
    EXPECT_LT(f.endSpeedMPerS, 1e-3) << name;
    EXPECT_EQ(device.feedbackCount(), static_cast<std::uint64_t>(kFrames));
  }
}

TEST(SimulatedHandDevice, ClosedLoopTheHandsGiveLowersTheForceAScriptedHandleWouldFeel) {
  // the same press through a rigid (scripted) handle: the handle reaches the target, the
  // coupling stretches over the whole 10 mm, and the device saturates; the hand's give
  // takes up most of that and the force stays below the limit
  ClosedLoop loop;
  const MotionScript script = pressBelowContact(0.01);
  SimulatedHandDevice hand(script, loop.handParams(), loop.model.deviceLimits);
  ScriptedDevice rigid(script, loop.model.deviceLimits);
  const LoopFigures withHand = loop.run("hand 10 mm below contact", hand, script);
  const LoopFigures withScript = loop.run("script 10 mm below contact", rigid, script);
  EXPECT_LT(glm::length(withScript.handleOverTargetWorld), 1e-9);
  EXPECT_NEAR(glm::length(withScript.restFeedbackWorld), loop.model.deviceLimits.maxForceN, 1e-9);
  EXPECT_LT(glm::length(withHand.restFeedbackWorld), 0.75 * loop.model.deviceLimits.maxForceN);
  EXPECT_LE(withScript.depthM, kBoundVoxels * kVoxelM);
}

}  // namespace
}  // namespace voxhap
