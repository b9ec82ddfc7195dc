// The replicated state: snapshots restore it bit for bit, refuse what is not one, and a
// fixed scene and script give a committed hash.

#include "haptics/sim/sim_state.h"

#include <cstring>
#include <string>

#include <gtest/gtest.h>

#include "haptics/core/error.h"
#include "haptics/sim/local_simulation.h"
#include "support/contact_scenes.h"

namespace voxhap {
namespace {

constexpr double kVoxel = 0.0005;  // m
const glm::dvec3 kGravity(0.0, 0.0, -9.81);

/// A box 0.8 mm over the plate, turned a little about x and y so that it lands on an edge.
Scene tiltedBoxOverPlate() {
  Scene scene;
  scene.objects.push_back(test::plate());
  scene.objects.push_back(test::meshObject("box", ObjectRole::Dynamic, [](TriangleMesh& m) {
    const glm::dmat4 place = glm::rotate(
        glm::rotate(test::at(0.0003, -0.0007, 0.0068), 0.05, glm::dvec3(1, 0, 0)), 0.03, glm::dvec3(0, 1, 0));
    appendBox(m, place, glm::dvec3(0.01, 0.01, 0.005));
  }));
  return scene;
}

/// `frames` frames of the box falling onto the plate.
void fall(LocalSimulation& sim, int frames) {
  for (int i = 0; i < frames; ++i) sim.step();
}

void expectErrorNaming(const SimModel& model, const std::vector<std::byte>& bytes, const std::string& words) {
  try {
    restoreState(model, bytes);
    ADD_FAILURE() << "restored a snapshot with " << words;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST(SimState, ASnapshotRestoresEveryBitAndTheRunGoesOnAlike) {
  const Scene scene = tiltedBoxOverPlate();
  SimModel model = test::freeModel(scene, {"box"}, kVoxel, kGravity);
  model.coherence.enabled = false;  // brute force: the workspace keeps no history that steers forces
  LocalSimulation original(model);
  fall(original, 150);
  original.state.owners[0] = 7;
  const std::vector<std::byte> bytes = saveState(original.state);
  const SimState restored = restoreState(model, bytes);
  EXPECT_EQ(saveState(restored), bytes);
  EXPECT_EQ(hashState(restored), hashState(original.state));
  EXPECT_EQ(restored.owners[0], 7u);

  LocalSimulation copy(model, restored);
  fall(original, 150);
  fall(copy, 150);
  EXPECT_GT(original.object(0).contacts, 0u) << "the box never landed";
  EXPECT_EQ(hashState(copy.state), hashState(original.state));
  EXPECT_EQ(std::memcmp(&copy.state.bodies[0], &original.state.bodies[0], sizeof(RigidBodyState)), 0);
}

TEST(SimState, TheHashSeesEveryReplicatedField) {
  const Scene scene = tiltedBoxOverPlate();
  const SimModel model = test::freeModel(scene, {"box"}, kVoxel, kGravity);
  const SimState base = makeSimState(model);
  const std::uint64_t h = hashState(base);
  auto differs = [&](auto change) {
    SimState s = base;
    change(s);
    return hashState(s) != h;
  };
  EXPECT_TRUE(differs([](SimState& s) { ++s.frame; }));
  EXPECT_TRUE(differs([](SimState& s) { s.timeS = std::nextafter(s.timeS, 1.0); }));
  EXPECT_TRUE(differs([](SimState& s) { ++s.forceLayer; }));
  EXPECT_TRUE(
      differs([](SimState& s) { s.bodies[0].comWorld.y = std::nextafter(s.bodies[0].comWorld.y, 1.0); }));
  EXPECT_TRUE(differs([](SimState& s) { s.bodies[0].orientation.z = -0.0; }));  // 0 and -0: different bits
  EXPECT_TRUE(differs([](SimState& s) { s.bodies[0].angularVelocityWorld.x = 1e-300; }));
  EXPECT_TRUE(differs([](SimState& s) { s.owners[0] = 2; }));
  EXPECT_FALSE(differs([](SimState& s) { ++s.bodies[0].skippedSteps; }));  // a local diagnostic
}

TEST(SimState, RestoreRefusesWhatIsNotASnapshotOfThisScene) {
  const Scene scene = tiltedBoxOverPlate();
  const SimModel model = test::freeModel(scene, {"box"}, kVoxel, kGravity);
  const std::vector<std::byte> good = saveState(makeSimState(model));
  ASSERT_NO_THROW(restoreState(model, good));

  std::vector<std::byte> bytes = good;
  bytes[0] = std::byte{'X'};
  expectErrorNaming(model, bytes, "not a Voxhap state snapshot");
  bytes = good;
  bytes[4] = std::byte{9};
  expectErrorNaming(model, bytes, "version 9");
  bytes = good;
  bytes.pop_back();
  expectErrorNaming(model, bytes, "truncated");
  bytes = good;
  bytes.push_back(std::byte{0});
  expectErrorNaming(model, bytes, "past its end");
  expectErrorNaming(model, {}, "truncated");

  SimState s = makeSimState(model);
  s.bodies[0].linearVelocityWorld.x = std::nan("");
  expectErrorNaming(model, saveState(s), "the body of box is not finite");
  s = makeSimState(model);
  s.bodies[0].orientation.w = 0.5;
  expectErrorNaming(model, saveState(s), "not a unit quaternion");
  s = makeSimState(model);
  s.forceLayer = 0;
  expectErrorNaming(model, saveState(s), "force layer 0");

  Scene two = tiltedBoxOverPlate();
  two.objects.push_back(test::meshObject("lid", ObjectRole::Dynamic, [](TriangleMesh& m) {
    appendBox(m, test::at(0.03, 0.03, 0.01), glm::dvec3(0.005, 0.005, 0.002));
  }));
  const SimModel twoModel = test::freeModel(two, {"box", "lid"}, kVoxel, kGravity);
  expectErrorNaming(twoModel, good, "1 moving objects, the scene has 2");
}

// A fixed scene and script give this hash, on any machine, in any build type. A change
// that moves it says why in its commit (and what it measured against ground truth).
constexpr std::uint64_t kGoldenHash = 0xf15d188a6c1293a9;

TEST(SimState, AFixedSceneAndScriptGiveTheCommittedHash) {
  const Scene scene = tiltedBoxOverPlate();
  SceneModelOptions options = test::ampleCapacityOptions();
  options.staticVoxelSizeM = kVoxel;
  options.pointSpacingM = kVoxel;
  options.sim.gravityWorld = kGravity;
  const SimModel model = buildSceneModel(scene, {"box"}, options);  // coupled, time-critical, fixed capacity
  LocalSimulation sim(model);
  // the handle presses the box 2 mm into the plate, then drags it 5 mm sideways, turning it
  for (int f = 0; f < 600; ++f) {
    const double t = std::min(1.0, f / 300.0);
    const HandleInput handle{{glm::dvec3(0.0003 + 0.005 * t, -0.0007, -0.0028 * t),
                              quatFromRotationVector(glm::dvec3(0.0, 0.0, 0.1 * t))},
                             {},
                             true};
    ASSERT_EQ(sim.step(std::span(&handle, 1)) & ~kFrameDeadlineMissed, 0u) << "frame " << f;
  }
  EXPECT_GT(sim.object(0).contacts, 0u);
  EXPECT_EQ(hashState(sim.state), kGoldenHash) << std::hex << "0x" << hashState(sim.state);
}

}  // namespace
}  // namespace voxhap
