// The 1 kHz frame never allocates (CONVENTIONS): from the first frame on, stepping makes
// no heap allocation on the thread that steps (support/allocation_counter.h).
#include <memory>
#include <optional>

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "haptics/scene/builtin/builtin_scenes.h"
#include "support/allocation_counter.h"
#include "support/contact_scenes.h"
#include "support/helper_thread.h"

namespace voxhap {
namespace {

/// Two boxes on a plate pushed into each other and onto it by their handles, 200 frames.
void expectTwoBoxesAllocateNothing(bool surfaceContact) {
  Scene scene;
  scene.objects.push_back(test::plate());
  for (int i = 0; i < 2; ++i) {
    scene.objects.push_back(test::meshObject(i == 0 ? "a" : "b", ObjectRole::Dynamic, [&](TriangleMesh& m) {
      appendBox(m, glm::translate(glm::dmat4(1.0), glm::dvec3(0.0111 * i, 0.0, 0.0056)), glm::dvec3(0.005));
    }));
  }
  SceneModelOptions options = test::ampleCapacityOptions();
  options.staticVoxelSizeM = 0.0005;
  options.pointSpacingM = 0.0005;
  options.sim.gravityWorld = glm::dvec3(0.0, 0.0, -9.81);
  if (surfaceContact) {
    options.pointSpacingM = 0.00025;
    options.sim.surfaceContact = true;
  }
  const SimModel model = buildSceneModel(scene, {"a", "b"}, options);
  ASSERT_EQ(model.pairs.front().params.surfaceContactM > 0.0, surfaceContact);
  const MotionScript script({{0.0, Pose{}}, {0.2, Pose{glm::dvec3(0.002, 0.0, -0.001), identityQuat()}}},
                            "push");
  ScriptedDevice da(script);
  ScriptedDevice db(script);
  HapticDevice* devices[] = {&da, &db};
  LocalSimulation sim(model);
  const test::AllocationCounter allocations;
  for (int i = 0; i < 200; ++i) sim.stepWithDevices(devices);
  EXPECT_EQ(allocations.count(), 0u);
  EXPECT_GT(sim.object(0).contacts + sim.object(1).contacts, 0u) << "the frames tested no contact";
}

TEST(FrameAllocation, SteppingTwoCoupledObjectsInContactAllocatesNothing) {
  expectTwoBoxesAllocateNothing(false);
}

TEST(FrameAllocation, SteppingThemWithSurfacePlanesAllocatesNothing) {
  expectTwoBoxesAllocateNothing(true);
}

/// The built-in ball and socket, the ball held by its handle, turned and pushed into the
/// socket, 300 frames; time-critical sampling plans with the capacity measured from the
/// frames' times. With a frame helper, its thread must not allocate either.
void expectTheTurnedBallAllocatesNothing(bool helped) {
  constexpr double voxel = 0.0005;
  SceneModelOptions options;
  options.staticVoxelSizeM = voxel;
  options.pointSpacingM = voxel;
  options.pointDisplacementM = -0.5 * voxel;
  options.sim.gravityWorld = glm::dvec3(0.0, 0.0, -9.81);
  ASSERT_EQ(options.sim.coherence.capacityTests, 0.0) << "the capacity is not measured online";
  const SimModel model = buildSceneModel(makeBallAndSocket(), {"ball"}, options);
  ASSERT_TRUE(model.objects[0].coupled);
  LocalSimulation sim(model);
  std::optional<test::AllocationCounter> helperAllocations;
  if (helped) {
    sim.workspace.helper = std::make_shared<FrameHelper>();
    auto count = [&] { helperAllocations.emplace(); };
    sim.workspace.helper->run(count);
    sim.workspace.helper->finish();
  }
  const Pose seated = objectPose(model, sim.state, 0);
  HandleInput handle[1] = {{seated, {}}};
  const ExternalWrench push[1] = {{glm::dvec3(0.0, 0.0, -2.0), glm::dvec3(0.0)}};
  handle[0].velocity.angularWorld = glm::dvec3(0.0, 0.0, 0.002 / model.dtS);  // 2 mrad a frame
  std::uint64_t contactFrames = 0;
  const test::AllocationCounter allocations;
  for (int i = 0; i < 300; ++i) {
    handle[0].poseWorld.orientation =
        glm::angleAxis(0.002 * i, glm::dvec3(0.0, 0.0, 1.0)) * seated.orientation;
    sim.step(handle, push);
    contactFrames += sim.object(0).contacts > 0 ? 1 : 0;
  }
  EXPECT_EQ(allocations.count(), 0u);
  EXPECT_GT(contactFrames, 250u) << "the frames tested little contact";
  EXPECT_GT(sim.outputs.coherence.tested, PairCoherence::kHelpedTests)
      << "too few tests a frame for the helper to take a share";
  if (helped) {
    std::uint64_t helperCount = 0;
    auto read = [&] { helperCount = helperAllocations->count(); };
    sim.workspace.helper->run(read);
    sim.workspace.helper->finish();
    EXPECT_EQ(helperCount, 0u) << "on the helper's thread";
  }
}

TEST(FrameAllocation, TurningTheSeatedBallWithItsCapacityMeasuredOnlineAllocatesNothing) {
  expectTheTurnedBallAllocatesNothing(false);
}

TEST(FrameAllocation, TurningItWithAFrameHelperAllocatesNothingOnEitherThread) {
  test::onAThreadOfItsOwn([] { expectTheTurnedBallAllocatesNothing(true); });
}

}  // namespace
}  // namespace voxhap
