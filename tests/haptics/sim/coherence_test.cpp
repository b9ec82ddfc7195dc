// Time-critical sampling in the frame (paper §5, DESIGN §4.5): checked against brute
// force, which tests every point every frame.
#include <cstring>
#include <random>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "haptics/device/scripted_device.h"
#include "support/contact_scenes.h"
#include "support/helper_thread.h"

namespace voxhap {
namespace {

constexpr double kVoxel = 0.0005;  // m
constexpr double kRadius = 0.01;   // m

Scene sphereOverPlate() {
  Scene scene;
  scene.objects.push_back(test::plate());
  scene.objects.push_back(test::meshObject("ball", ObjectRole::Dynamic, [](TriangleMesh& m) {
    appendGeodesicSphere(m, glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 0.0, kRadius + 0.002)), kRadius,
                         4);
  }));
  return scene;
}

/// A bar 60 mm tall standing 2 mm over the plate: most of its chunks are far from it.
Scene barOverPlate() {
  Scene scene;
  scene.objects.push_back(test::plate());
  scene.objects.push_back(test::meshObject("ball", ObjectRole::Dynamic, [](TriangleMesh& m) {
    appendBox(m, glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 0.0, 0.032)),
              glm::dvec3(0.004, 0.004, 0.03));
  }));
  return scene;
}

SimModel coupledModel(const Scene& scene, double capacityTests, bool awareness = true, bool drifting = true) {
  SceneModelOptions options;
  options.sim.geometricalAwareness = awareness;
  options.sim.coherence.pointDrifting = drifting;
  options.staticVoxelSizeM = kVoxel;
  options.pointSpacingM = kVoxel;
  options.sim.coherence.capacityTests = capacityTests;
  return buildSceneModel(scene, {"ball"}, options);
}

/// Points of object 0 at or inside the force layer where it stands now, by testing all.
std::vector<PointContact> bruteForceContacts(const SimModel& model, const SimState& state) {
  const PairModel& pair = model.pairs.front();
  const Voxmap& voxmap = model.voxmapOf(pair);
  const Pointshell& shell = model.objects[0].shell;
  const VoxelTransform transform = VoxelTransform::make(objectPose(model, state, 0), voxmap.grid());
  std::vector<PointContact> contacts(shell.size());
  contacts.resize(samplePoints(shell, voxmap, transform, pair.fieldShifts, state.forceLayer, 0,
                               static_cast<std::uint32_t>(shell.size()), contacts.data()));
  return contacts;
}

/// A handle that jumps between random poses every `periodS`, turned up to `turnRad` about
/// `centre`, faster than MaxTravel lets the part follow: down to 2.5 mm into the plate, and
/// in one run of eight poses out of four lifted 40 mm, out of the plate's grid.
MotionScript randomMotion(unsigned seed, double periodS, double durationS,
                          const glm::dvec3& centre = glm::dvec3(0.0, 0.0, kRadius + 0.002),
                          double turnRad = 1.5) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<MotionKeyframe> keys;
  for (double t = 0.0; t <= durationS; t += periodS) {
    const double lift = (keys.size() / 8) % 4 == 3 ? 0.04 : 0.0;
    const glm::dvec3 shift(0.006 * unit(random), 0.006 * unit(random), -0.0015 + 0.003 * unit(random) + lift);
    const glm::dquat turn =
        quatFromRotationVector(turnRad * glm::dvec3(unit(random), unit(random), unit(random)));
    keys.push_back({t, Pose{centre - turn * centre + shift, turn}});
  }
  return MotionScript(std::move(keys), "random motion");
}

struct RandomMotionCase {
  const char* name;
  Scene (*scene)();
  glm::dvec3 centre;  ///< of the part, which the handle turns about
  double turnRad;     ///< largest turn of the handle
  bool awareness;
  double capacityShare;  ///< point tests per frame over points: short enough to bind
  bool drifting;
};

class CoherenceUnderRandomMotion : public testing::TestWithParam<RandomMotionCase> {};

// A point brute force finds in contact was tested in that frame: it is in the contact queue
// after the frame (untested points keep their queue, and the contact queue is tested every
// frame). With geometrical awareness a surface or edge point may pass from far to interior
// through the plate's face between two tests (max_travel.h): those are counted apart, and
// without drifting must be caught by their next test; every other contact must be tested
// in its frame.
TEST_P(CoherenceUnderRandomMotion, NoPointReachesTheForceLayerUntested) {
  const RandomMotionCase& param = GetParam();
  const Scene scene = param.scene();
  const SimModel bounded = coupledModel(scene, 0.0, param.awareness);
  const auto points = static_cast<double>(bounded.objects[0].shell.size());
  const SimModel model = coupledModel(scene, param.capacityShare * points, param.awareness, param.drifting);
  std::uint64_t scaledFrames = 0;
  std::uint64_t contactFrames = 0;
  std::uint64_t missedFrames = 0;
  std::uint64_t collapsedChunkFrames = 0;
  std::uint64_t outOfRangeFrames = 0;
  std::uint64_t lateThroughAFace = 0;
  std::uint64_t driftedTests = 0;
  double testedShare = 0.0;
  constexpr int kFrames = 3000;
  for (const unsigned seed : {1u, 2u, 3u}) {
    ScriptedDevice device(randomMotion(seed, 0.05, 3.0, param.centre, param.turnRad));
    HapticDevice* devices[] = {&device};
    LocalSimulation sim(model);
    SimState& state = sim.state;
    // per point, the travel allowed since it was first seen late in this run of contact
    // (−1: not late)
    std::vector<double> lateTravelM(model.objects[0].shell.size(), -1.0);
    for (int frame = 0; frame < kFrames; ++frame) {
      const std::vector<PointContact> expected = bruteForceContacts(model, state);
      const std::uint64_t skippedBefore = sim.workspace.counters.pairsSkipped;
      sim.stepWithDevices(devices);
      const PointQueues& queues = sim.workspace.coherence.front().queues();
      std::vector<double> stillLate(lateTravelM.size(),
                                    -1.0);  // a late run ends when the point leaves contact
      for (const PointContact& c : expected) {
        if (queues.queueOf(c.point) == 0) continue;
        const bool throughAFace = param.awareness && c.value == kValueInterior &&
                                  model.objects[0].shell.features[c.point] != PointFeature::Vertex;
        ASSERT_TRUE(throughAFace) << "seed " << seed << ", frame " << frame << ": point " << c.point
                                  << " reached value " << int(c.value) << " untested";
        ++lateThroughAFace;
        // without drifting the far queue, the furthest out, looks up within 6 voxels of
        // travel; with it a lookup waits for 4 voxels of drift, which a point circling
        // need never reach
        stillLate[c.point] = std::max(0.0, lateTravelM[c.point]) + sim.object(0).maxTravelM;
        if (!param.drifting) {
          ASSERT_LE(stillLate[c.point], 6.5 * kVoxel) << "seed " << seed << ", frame " << frame;
        }
      }
      lateTravelM.swap(stillLate);
      const PointQueues& chunks = sim.workspace.coherence.front().chunkQueues();
      collapsedChunkFrames += chunks.count(0) + chunks.count(1) < chunks.pointCount() ? 1 : 0;
      outOfRangeFrames += sim.workspace.counters.pairsSkipped - skippedBefore;
      missedFrames += sim.outputs.coherence.deadlineMissed ? 1 : 0;
      scaledFrames += sim.outputs.coherence.travelScale < 1.0 ? 1 : 0;
      contactFrames += expected.empty() ? 0 : 1;
      testedShare += sim.outputs.coherence.tested / points;
      driftedTests += sim.outputs.coherence.drifted;
    }
  }
  RecordProperty("late_through_a_face", static_cast<int>(lateThroughAFace));
  if (param.drifting) {
    EXPECT_GT(driftedTests, 0u);
  }
  // the run exercised what it claims to: contact, a short capacity, partial testing,
  // collapsed chunks, leaving range and coming back
  EXPECT_GT(contactFrames, 500u);
  EXPECT_GT(scaledFrames, 300u);
  EXPECT_LT(testedShare / (3 * kFrames), 0.25);
  EXPECT_GT(collapsedChunkFrames, 500u);
  EXPECT_GT(outOfRangeFrames, 100u);
  EXPECT_EQ(missedFrames, 0u);
}

const RandomMotionCase kRandomMotionCases[] = {
    {"SphereAware", sphereOverPlate, glm::dvec3(0.0, 0.0, kRadius + 0.002), 1.5, true, 0.08, true},
    {"SphereAwareNoDrifting", sphereOverPlate, glm::dvec3(0.0, 0.0, kRadius + 0.002), 1.5, true, 0.03, false},
    {"SphereUnaware", sphereOverPlate, glm::dvec3(0.0, 0.0, kRadius + 0.002), 1.5, false, 0.1, true},
    {"TallBarAware", barOverPlate, glm::dvec3(0.0, 0.0, 0.032), 0.1, true, 0.05, true},
    {"TallBarAwareNoDrifting", barOverPlate, glm::dvec3(0.0, 0.0, 0.032), 0.1, true, 0.03, false},
    {"TallBarUnaware", barOverPlate, glm::dvec3(0.0, 0.0, 0.032), 0.1, false, 0.1, true},
};

INSTANTIATE_TEST_SUITE_P(Scenes, CoherenceUnderRandomMotion, testing::ValuesIn(kRandomMotionCases),
                         [](const testing::TestParamInfo<RandomMotionCase>& info) {
                           return info.param.name;
                         });

TEST(Coherence, MaxTravelHoldsEveryPointOfTheObject) {
  const Scene scene = sphereOverPlate();
  const SimModel model = coupledModel(scene, 200.0);
  ScriptedDevice device(randomMotion(4, 0.02, 1.0));
  HapticDevice* devices[] = {&device};
  LocalSimulation sim(model);
  SimState& state = sim.state;
  const Pointshell& shell = model.objects[0].shell;
  for (int frame = 0; frame < 1000; ++frame) {
    const Pose before = objectPose(model, state, 0);
    sim.stepWithDevices(devices);
    const Pose after = objectPose(model, state, 0);
    double farthestM = 0.0;
    for (const glm::vec3& p : shell.positionsLocal) {
      farthestM =
          std::max(farthestM, glm::length(apply(after, glm::dvec3(p)) - apply(before, glm::dvec3(p))));
    }
    ASSERT_LE(farthestM, sim.object(0).maxTravelM * (1.0 + 1e-9) + 1e-12) << "frame " << frame;
    ASSERT_LE(sim.object(0).maxTravelM, 0.5 * kVoxel);
  }
  EXPECT_GT(sim.workspace.counters.travelLimitedFrames, 100u);
}

TEST(Coherence, MoreMandatoryPointsThanCapacityStopsTheObjectOnceThenAbandonsTimeCriticality) {
  Scene scene = sphereOverPlate();
  // start the ball resting in the force layer; its handle lifts it 5 mm
  scene.objects[1] = test::meshObject("ball", ObjectRole::Dynamic, [](TriangleMesh& m) {
    appendGeodesicSphere(m, glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 0.0, kRadius)), kRadius, 4);
  });
  const SimModel model = coupledModel(scene, 10.0);
  LocalSimulation sim(model);
  SimState& state = sim.state;
  HandleInput handles[1] = {{Pose{glm::dvec3(0.0, 0.0, 0.005), identityQuat()}, {}}};
  const Pose start = objectPose(model, state, 0);
  sim.step(handles);
  // the first frame short of capacity: every mandatory point tested, nothing moves
  EXPECT_TRUE(sim.outputs.coherence.deadlineMissed);
  EXPECT_EQ(sim.workspace.counters.missedDeadlines, 1u);
  EXPECT_EQ(sim.object(0).maxTravelM, 0.0);
  EXPECT_EQ(objectPose(model, state, 0).position, start.position);
  EXPECT_EQ(sim.outputs.coherence.tested, sim.outputs.coherence.mandatory);
  EXPECT_GT(sim.object(0).contacts, 0u);
  // the next ones still short: full MaxTravel, however long they take, counted missed
  sim.step(handles);
  EXPECT_TRUE(sim.outputs.coherence.deadlineMissed);
  EXPECT_EQ(sim.workspace.counters.missedDeadlines, 2u);
  EXPECT_EQ(sim.object(0).maxTravelM, 0.5 * kVoxel);
  for (int frame = 0; frame < 100; ++frame) sim.step(handles);
  // pulled free: no contact left, deadlines met again
  EXPECT_FALSE(sim.outputs.coherence.deadlineMissed);
  EXPECT_EQ(sim.object(0).contacts, 0u);
  EXPECT_GT(objectPose(model, state, 0).position.z, start.position.z + 0.002);
}

TEST(Coherence, AnObjectOutOfRangeCostsNoPointTests) {
  Scene scene = sphereOverPlate();
  scene.objects[1] = test::meshObject("ball", ObjectRole::Dynamic, [](TriangleMesh& m) {
    appendGeodesicSphere(m, glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 0.0, 0.2)), kRadius, 4);
  });
  const SimModel model = coupledModel(scene, 1000.0);
  LocalSimulation sim(model);
  HandleInput handles[1] = {{Pose{}, {}}};
  for (int frame = 0; frame < 10; ++frame) {
    sim.step(handles);
    EXPECT_EQ(sim.outputs.coherence.tested, 0u);
    // far from everything MaxTravel rises to half a chunk (8 voxels)
    EXPECT_EQ(sim.object(0).maxTravelM, 4.0 * kVoxel);
  }
  EXPECT_EQ(sim.workspace.counters.pairsSkipped, 10u);
}

TEST(Coherence, FarInRangeTheChunksCollapseAndMaxTravelRisesUntilTheyComeBack) {
  // a tall post makes the plate's grid tall: the ball is in range but far from every surface
  Scene scene = sphereOverPlate();
  scene.objects.push_back(test::meshObject("post", ObjectRole::Static, [](TriangleMesh& m) {
    appendBox(m, glm::translate(glm::dmat4(1.0), glm::dvec3(0.045, 0.045, 0.05)),
              glm::dvec3(0.004, 0.004, 0.05));
  }));
  scene.objects[1] = test::meshObject("ball", ObjectRole::Dynamic, [](TriangleMesh& m) {
    appendGeodesicSphere(m, glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 0.0, 0.05)), kRadius, 4);
  });
  const SimModel model = coupledModel(scene, 1e6);
  LocalSimulation sim(model);
  SimState& state = sim.state;
  const PairCoherence& coherence = sim.workspace.coherence.front();
  EXPECT_TRUE(coherence.onlyCollapsed());
  // the handle takes the ball down onto the plate, 40 mm in 0.2 s, and holds it there
  const std::vector<MotionKeyframe> keys = {{0.0, Pose{}},
                                            {0.2, Pose{glm::dvec3(0.0, 0.0, -0.0405), identityQuat()}},
                                            {0.5, Pose{glm::dvec3(0.0, 0.0, -0.0405), identityQuat()}}};
  ScriptedDevice device(MotionScript(keys, "down"));
  HapticDevice* devices[] = {&device};
  std::uint32_t farFrames = 0;
  std::uint32_t contactFrames = 0;
  for (int frame = 0; frame < 500; ++frame) {
    const std::size_t expected = bruteForceContacts(model, state).size();
    const bool far = coherence.onlyCollapsed();
    sim.stepWithDevices(devices);
    ASSERT_EQ(sim.object(0).contacts, expected) << "frame " << frame;
    if (far) {
      ++farFrames;
      EXPECT_EQ(sim.object(0).maxTravelM, 4.0 * kVoxel);
      // no point tests unless a chunk came back in this frame
      if (coherence.onlyCollapsed()) {
        EXPECT_EQ(sim.outputs.coherence.tested, 0u);
      }
    } else {
      EXPECT_EQ(sim.object(0).maxTravelM, 0.5 * kVoxel);
    }
    contactFrames += expected > 0 ? 1 : 0;
  }
  EXPECT_GT(farFrames, 10u);
  EXPECT_GT(contactFrames, 100u);
}

TEST(Coherence, SameInputsGiveTheSameBitsWithAFixedCapacity) {
  const Scene scene = sphereOverPlate();
  const SimModel model = coupledModel(scene, 300.0);
  RigidBodyState end[2];
  for (RigidBodyState& result : end) {
    ScriptedDevice device(randomMotion(5, 0.05, 0.5));
    HapticDevice* devices[] = {&device};
    LocalSimulation sim(model);
    SimState& state = sim.state;
    for (int frame = 0; frame < 500; ++frame) sim.stepWithDevices(devices);
    result = state.bodies[0];
  }
  EXPECT_EQ(std::memcmp(&end[0], &end[1], sizeof(RigidBodyState)), 0);
}

// A frame helper tests the last half of a frame's due points on a thread of its own: the
// frames give the same bits as the haptic thread alone, and the queues end the same.
TEST(Coherence, AFrameHelperGivesTheSameBitsAsOneThread) {
  const SimModel model = coupledModel(sphereOverPlate(), 3000.0);
  struct Run {
    std::vector<RigidBodyState> bodies;
    std::vector<std::uint32_t> contacts;
    std::vector<std::uint32_t> queueCounts;
    int helpedFrames = 0;  // frames with enough due points for the helper to take a share
  };
  Run runs[2];
  test::onAThreadOfItsOwn([&] {
    for (int helped = 0; helped < 2; ++helped) {
      Run& run = runs[helped];
      ScriptedDevice device(randomMotion(7, 0.05, 1.0));
      HapticDevice* devices[] = {&device};
      LocalSimulation sim(model);
      if (helped) sim.workspace.helper = std::make_shared<FrameHelper>();
      for (int frame = 0; frame < 1000; ++frame) {
        sim.stepWithDevices(devices);
        run.bodies.push_back(sim.state.bodies[0]);
        run.contacts.push_back(sim.object(0).contacts);
        run.helpedFrames += sim.outputs.coherence.tested >= PairCoherence::kHelpedTests ? 1 : 0;
      }
      const PointQueues& queues = sim.workspace.coherence.front().queues();
      for (int q = 0; q < queues.queueCount(); ++q) run.queueCounts.push_back(queues.count(q));
    }
    EXPECT_GT(runs[1].helpedFrames, 100);
    ASSERT_EQ(runs[0].bodies.size(), runs[1].bodies.size());
    for (std::size_t frame = 0; frame < runs[0].bodies.size(); ++frame) {
      ASSERT_EQ(std::memcmp(&runs[0].bodies[frame], &runs[1].bodies[frame], sizeof(RigidBodyState)), 0)
          << "frame " << frame;
    }
    EXPECT_EQ(runs[0].contacts, runs[1].contacts);
    EXPECT_EQ(runs[0].queueCounts, runs[1].queueCounts);
  });
}

}  // namespace
}  // namespace voxhap
