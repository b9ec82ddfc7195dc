// What a frame takes from outside: external wrenches push objects as forces do, a remote
// peer's object moves as its stream says, and a non-finite input is dropped, reported,
// and harms nothing.

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "haptics/sim/local_simulation.h"
#include "support/contact_scenes.h"

namespace voxhap {
namespace {

constexpr double kVoxel = 0.0005;  // m

/// A box far above the plate (no contact), free or coupled to a handle.
SimModel boxInTheAir(bool coupled) {
  Scene scene;
  scene.objects.push_back(test::plate());
  scene.objects.push_back(test::meshObject("box", ObjectRole::Dynamic, [](TriangleMesh& m) {
    appendBox(m, test::at(0.0, 0.0, 0.03), glm::dvec3(0.01, 0.01, 0.005));
  }));
  SimModel model = test::freeModel(scene, {"box"}, kVoxel, glm::dvec3(0.0));
  model.objects[0].coupled = coupled;
  return model;
}

TEST(FrameInputs, AnExternalWrenchAcceleratesTheObjectAsNewtonSays) {
  const SimModel model = boxInTheAir(false);
  LocalSimulation sim(model);
  const double massKg = model.objects[0].body.massKg;
  const ExternalWrench push{glm::dvec3(0.0, 0.02, 0.0), glm::dvec3(0.0)};
  for (int f = 0; f < 100; ++f) ASSERT_EQ(sim.step({}, std::span(&push, 1)), kFrameOk);
  // semi-implicit Euler: v = F/m·t exactly (no contact, no gravity)
  EXPECT_NEAR(sim.state.bodies[0].linearVelocityWorld.y, 0.02 / massKg * 0.1, 1e-12);
  EXPECT_EQ(sim.state.bodies[0].linearVelocityWorld.x, 0.0);
  EXPECT_EQ(sim.object(0).contacts, 0u);
}

TEST(FrameInputs, ATorqueTurnsTheObjectAboutItsCentreOfMass) {
  const SimModel model = boxInTheAir(false);
  LocalSimulation sim(model);
  const glm::dvec3 comBefore = sim.state.bodies[0].comWorld;
  const ExternalWrench twist{glm::dvec3(0.0), glm::dvec3(0.0, 0.0, 1e-4)};
  for (int f = 0; f < 50; ++f) sim.step({}, std::span(&twist, 1));
  EXPECT_GT(sim.state.bodies[0].angularVelocityWorld.z, 0.0);
  EXPECT_EQ(sim.state.bodies[0].comWorld, comBefore);
}

TEST(FrameInputs, ANonFiniteWrenchIsDroppedAndReported) {
  const SimModel model = boxInTheAir(false);
  LocalSimulation sim(model);
  const RigidBodyState before = sim.state.bodies[0];
  const ExternalWrench bad{glm::dvec3(std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0), glm::dvec3(0.0)};
  EXPECT_EQ(sim.step({}, std::span(&bad, 1)), kFrameNonFiniteZeroed);
  EXPECT_EQ(sim.state.bodies[0].comWorld, before.comWorld);
  EXPECT_EQ(sim.state.bodies[0].linearVelocityWorld, glm::dvec3(0.0));
  EXPECT_EQ(sim.state.frame, 1u);  // the frame still ran
}

TEST(FrameInputs, ANonFiniteHandleHoldsNothingAndSendsNoForce) {
  const SimModel model = boxInTheAir(true);
  LocalSimulation sim(model);
  HandleInput handle{sim.state.bodies[0].pose(model.objects[0].body), {}, true};
  handle.poseWorld.position.z += 0.001;  // a finite handle 1 mm above pulls the box up
  EXPECT_EQ(sim.step(std::span(&handle, 1)), kFrameOk);
  EXPECT_LT(sim.object(0).feedback.forceWorld.z, 0.0);  // the user feels the box hang on the handle
  EXPECT_GT(sim.state.bodies[0].linearVelocityWorld.z, 0.0);

  LocalSimulation other(model);
  handle.poseWorld.orientation.x = std::numeric_limits<double>::infinity();
  EXPECT_EQ(other.step(std::span(&handle, 1)), kFrameNonFiniteZeroed);
  EXPECT_EQ(other.object(0).feedback.forceWorld, glm::dvec3(0.0));
  EXPECT_EQ(other.state.bodies[0].linearVelocityWorld, glm::dvec3(0.0));
}

TEST(FrameInputs, AnObjectWithoutADeviceIsFreeWhereverItIs) {
  const SimModel model = boxInTheAir(true);
  LocalSimulation sim(model);
  Pose away;  // 5 mm aside and turned: a device's handle at the scene placement would pull it back
  away.position.x = 0.005;
  away.orientation = glm::angleAxis(0.3, glm::dvec3(0.0, 0.0, 1.0));
  sim.state.bodies[0] = restingState(model.objects[0].body, away);
  const RigidBodyState before = sim.state.bodies[0];
  HapticDevice* const none = nullptr;
  for (int f = 0; f < 100; ++f) ASSERT_EQ(sim.stepWithDevices(std::span(&none, 1)), kFrameOk);
  EXPECT_EQ(sim.state.bodies[0].comWorld, before.comWorld);
  EXPECT_EQ(sim.state.bodies[0].orientation, before.orientation);
  EXPECT_EQ(sim.object(0).feedback.forceWorld, glm::dvec3(0.0));

  HandleInput released{away, {}, false};  // a handle that holds nothing pulls nothing
  released.poseWorld.position.x = 0.0;
  EXPECT_EQ(sim.step(std::span(&released, 1)), kFrameOk);
  EXPECT_EQ(sim.state.bodies[0].comWorld, before.comWorld);
}

/// A free box 3 mm above the plate and, 4 mm above it, a smaller box that a remote
/// peer moves (object 1, "upper").
Scene boxUnderARemoteBox() {
  Scene scene;
  scene.objects.push_back(test::plate());
  scene.objects.push_back(test::meshObject("lower", ObjectRole::Dynamic, [](TriangleMesh& m) {
    appendBox(m, test::at(0.0, 0.0, 0.006), glm::dvec3(0.01, 0.01, 0.003));
  }));
  scene.objects.push_back(test::meshObject("upper", ObjectRole::Dynamic, [](TriangleMesh& m) {
    appendBox(m, test::at(0.0, 0.0, 0.016), glm::dvec3(0.008, 0.008, 0.003));
  }));
  return scene;
}

SimModel remoteBoxModel(const Scene& scene) {
  return test::freeModel(scene, {"lower", "upper"}, kVoxel, glm::dvec3(0.0));
}

/// Kinematic inputs in which the upper box is a remote peer's, streamed where `sim` has it.
std::vector<KinematicInput> upperIsRemote(const LocalSimulation& sim) {
  std::vector<KinematicInput> kinematic(2);
  kinematic[1].active = true;
  kinematic[1].targetWorld = sim.state.bodies[1];
  return kinematic;
}

/// The remote upper box held still by its stream where `sim` has it, the lower box thrown up
/// into it at 0.5 m/s, 100 frames: the upper box must not move by a bit (fatal failure at the
/// first frame it does); `framesLimited` counts the frames in which the depth limits bound.
void throwTheLowerBoxIntoTheStillUpperOne(LocalSimulation& sim, std::vector<KinematicInput>& kinematic,
                                          std::uint32_t& framesLimited) {
  const RigidBodyState held = sim.state.bodies[1];
  kinematic[1].targetWorld = held;
  kinematic[1].targetWorld.linearVelocityWorld = kinematic[1].targetWorld.angularVelocityWorld =
      glm::dvec3(0.0);
  sim.state.bodies[0].linearVelocityWorld = glm::dvec3(0.0, 0.0, 0.5);
  framesLimited = 0;
  for (int f = 1; f <= 100; ++f) {
    ASSERT_EQ(sim.step({}, {}, kinematic) & kFrameNonFiniteZeroed, 0);
    framesLimited += sim.outputs.depthLimit.binding > 0 ? 1 : 0;
    ASSERT_EQ(sim.state.bodies[1].comWorld, held.comWorld) << "frame " << f;
    ASSERT_EQ(sim.state.bodies[1].orientation, held.orientation) << "frame " << f;
  }
}

TEST(FrameInputs, ARemoteObjectGoesWhereItsStreamSaysAndPushesTheLocalOnes) {
  const Scene scene = boxUnderARemoteBox();
  const SimModel model = remoteBoxModel(scene);
  LocalSimulation sim(model);
  std::vector<KinematicInput> kinematic = upperIsRemote(sim);
  // sideways at 20 mm/s, away from everything: exactly where the stream says, turning too
  kinematic[1].targetWorld.linearVelocityWorld = glm::dvec3(0.02, 0.0, 0.0);
  for (int f = 1; f <= 100; ++f) {
    kinematic[1].targetWorld.comWorld.x = 0.02 * f * model.dtS;
    kinematic[1].targetWorld.orientation = glm::angleAxis(0.001 * f, glm::dvec3(0.0, 0.0, 1.0));
    ASSERT_EQ(sim.step({}, {}, kinematic), kFrameOk);
    ASSERT_EQ(sim.state.bodies[1].comWorld, kinematic[1].targetWorld.comWorld);
    ASSERT_EQ(sim.state.bodies[1].orientation, kinematic[1].targetWorld.orientation);
  }
  EXPECT_EQ(sim.state.bodies[1].linearVelocityWorld, glm::dvec3(0.02, 0.0, 0.0));
  EXPECT_EQ(sim.state.bodies[0].comWorld, makeSimState(model).bodies[0].comWorld);  // untouched

  // then down onto the lower box at 50 mm/s and on, 10 mm past it: it pushes the lower box
  // away (exact non-penetration of remote parts: NonPenetration.ARemotePart…), and lags
  // its stream while it does
  const double startZ = kinematic[1].targetWorld.comWorld.z;
  kinematic[1].targetWorld.linearVelocityWorld = glm::dvec3(0.0, 0.0, -0.05);
  std::uint32_t contacts = 0;
  double lagM = 0.0;
  for (int f = 1; f <= 300; ++f) {
    kinematic[1].targetWorld.comWorld.z = startZ - 0.05 * f * model.dtS;
    ASSERT_EQ(sim.step({}, {}, kinematic) & kFrameNonFiniteZeroed, 0);
    contacts = std::max(contacts, sim.object(1).contacts);
    lagM = std::max(lagM, sim.state.bodies[1].comWorld.z - kinematic[1].targetWorld.comWorld.z);
  }
  EXPECT_GT(contacts, 0u);
  EXPECT_GT(glm::length(sim.state.bodies[0].comWorld - makeSimState(model).bodies[0].comWorld), 0.001);
  EXPECT_GT(lagM, 0.001);
}

TEST(FrameInputs, ARemoteObjectHeldStillStaysToTheBitWhileALocalOneRunsIntoIt) {
  const SimModel model = remoteBoxModel(boxUnderARemoteBox());
  LocalSimulation sim(model);
  std::vector<KinematicInput> kinematic = upperIsRemote(sim);
  // tilted, so that a rotation that is only rounded away would show
  kinematic[1].targetWorld.orientation = glm::angleAxis(0.3, glm::normalize(glm::dvec3(1.0, 2.0, 0.0)));
  kinematic[1].targetWorld.comWorld.z += 0.002;
  sim.state.bodies[1] = kinematic[1].targetWorld;
  std::uint32_t framesLimited = 0;
  ASSERT_NO_FATAL_FAILURE(throwTheLowerBoxIntoTheStillUpperOne(sim, kinematic, framesLimited));
  EXPECT_GT(framesLimited, 0u);  // the depth limits held the local box back, and only it
}

TEST(FrameInputs, ARemoteObjectLeftStillAfterItYieldedIsMovedByNothingElse) {
  for (const bool surface : {false, true}) {
    SCOPED_TRACE(surface ? "surface planes" : "voxel planes");
    const SimModel model =
        test::freeModel(boxUnderARemoteBox(), {"lower", "upper"}, kVoxel, glm::dvec3(0.0), true, surface);
    LocalSimulation sim(model);
    std::vector<KinematicInput> kinematic = upperIsRemote(sim);
    // down at 50 mm/s, 15 mm: it traps the lower box against the plate and yields
    const double startZ = kinematic[1].targetWorld.comWorld.z;
    kinematic[1].targetWorld.linearVelocityWorld = glm::dvec3(0.0, 0.0, -0.05);
    for (int f = 1; f <= 300; ++f) {
      kinematic[1].targetWorld.comWorld.z = startZ - 0.05 * f * model.dtS;
      ASSERT_EQ(sim.step({}, {}, kinematic) & kFrameNonFiniteZeroed, 0);
    }
    EXPECT_GT(sim.state.bodies[1].comWorld.z - kinematic[1].targetWorld.comWorld.z, 0.001);
    // its owner is gone: nobody moves it, so it stays where it is (as HapticLoop has it),
    // and the lower box, thrown up into it, moves it not at all
    std::uint32_t framesLimited = 0;
    ASSERT_NO_FATAL_FAILURE(throwTheLowerBoxIntoTheStillUpperOne(sim, kinematic, framesLimited));
    EXPECT_GT(framesLimited, 0u);
  }
}

TEST(FrameInputs, ARemoteObjectOnThePlateIsLeftToItsOwnerUntilItIsLocal) {
  const SimModel model = remoteBoxModel(boxUnderARemoteBox());
  LocalSimulation sim(model);
  std::vector<KinematicInput> kinematic = upperIsRemote(sim);
  // beside the lower box, its bottom 0.1 mm into the plate: a contact only its owner tests
  kinematic[1].targetWorld.comWorld = glm::dvec3(0.035, 0.0, 0.0029);
  sim.state.bodies[1] = kinematic[1].targetWorld;
  for (int f = 0; f < 10; ++f) {
    ASSERT_EQ(sim.step({}, {}, kinematic), kFrameOk);
    EXPECT_EQ(sim.object(1).contacts, 0u);
    EXPECT_EQ(sim.state.bodies[1].comWorld, kinematic[1].targetWorld.comWorld);
  }
  // handed over to this peer, it is tested at once and pushed out of the plate
  kinematic[1].active = false;
  ASSERT_EQ(sim.step({}, {}, kinematic) & kFrameNonFiniteZeroed, 0);
  EXPECT_GT(sim.object(1).contacts, 0u);
  EXPECT_GT(sim.object(1).contactForceWorld.z, 0.0);
}

TEST(FrameInputs, ANonFiniteRemoteStateIsDroppedAndReported) {
  const SimModel model = remoteBoxModel(boxUnderARemoteBox());
  LocalSimulation sim(model);
  std::vector<KinematicInput> kinematic = upperIsRemote(sim);
  kinematic[1].targetWorld.comWorld.x = std::numeric_limits<double>::quiet_NaN();
  const RigidBodyState before = sim.state.bodies[1];
  EXPECT_EQ(sim.step({}, {}, kinematic), kFrameNonFiniteZeroed);
  EXPECT_EQ(sim.state.bodies[1].comWorld, before.comWorld);
  kinematic[1].targetWorld = before;
  kinematic[1].targetWorld.orientation = glm::dquat(2.0, 0.0, 0.0, 0.0);  // not a rotation
  EXPECT_EQ(sim.step({}, {}, kinematic), kFrameNonFiniteZeroed);
  EXPECT_EQ(sim.state.bodies[1].orientation, before.orientation);
}

}  // namespace
}  // namespace voxhap
