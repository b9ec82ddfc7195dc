// Contact finer than a voxel (SimOptions::surfaceContact): parts rest within half a point
// spacing of each other, measured on the exact meshes, and never pass into each other.

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "haptics/collide/exact_penetration.h"
#include "haptics/core/error.h"
#include "haptics/scene/builtin/builtin_scenes.h"
#include "haptics/sim/local_simulation.h"
#include "support/contact_scenes.h"

namespace voxhap {
namespace {

const glm::dvec3 kGravity(0.0, 0.0, -9.81);
constexpr double kVoxelsM[] = {0.001, 0.0007, 0.0005};

/// `moving` free under gravity at voxel size `voxelM`, points half a voxel apart, contact
/// by surface planes (or the paper's voxel planes when `surface` is false).
SimModel surfaceModel(const Scene& scene, const std::vector<std::string>& moving, double voxelM,
                      bool surface = true) {
  SceneModelOptions options = test::ampleCapacityOptions();
  options.staticVoxelSizeM = voxelM;
  options.pointSpacingM = 0.5 * voxelM;
  options.sim.gravityWorld = kGravity;
  options.sim.surfaceContact = surface;
  SimModel model = buildSceneModel(scene, moving, options);
  for (MovingObjectModel& object : model.objects) object.coupled = false;
  return model;
}

/// The built-in ball in its socket, 1 mm voxels and points, contact by surface planes.
SceneModelOptions seatedBallOptions() {
  SceneModelOptions options = test::ampleCapacityOptions();
  options.staticVoxelSizeM = 0.001;
  options.pointSpacingM = 0.001;
  options.sim.surfaceContact = true;
  return options;
}

/// The exact gap under a convex polyhedron over the plane z = `floorZ` after `frames`
/// frames at rest, and the least it reached on the way.
struct Rest {
  double gapM = 0.0;
  double lowestM = 1e9;
  glm::dvec3 velocity{0.0};
};

Rest settle(const Scene& scene, const SimModel& model, int frames, double floorZ = 0.0) {
  LocalSimulation sim(model);
  Rest r;
  for (int i = 0; i < frames; ++i) {
    sim.step();
    r.lowestM =
        std::min(r.lowestM, test::lowestZ(scene.objects[1], objectPose(model, sim.state, 0)) - floorZ);
  }
  r.gapM = test::lowestZ(scene.objects[1], objectPose(model, sim.state, 0)) - floorZ;
  r.velocity = sim.state.bodies[0].linearVelocityWorld;
  return r;
}

Scene onPlate(const std::string& name, const std::function<void(TriangleMesh&)>& append) {
  Scene scene;
  scene.objects.push_back(test::plate());
  scene.objects.push_back(test::meshObject(name, ObjectRole::Dynamic, append));
  return scene;
}

TEST(SurfaceContact, ASphereRestsWithinAQuarterVoxelOfThePlateAndNeverSinksIntoIt) {
  const Scene scene = onPlate(
      "ball", [](TriangleMesh& m) { appendGeodesicSphere(m, test::at(0.0001, -0.0002, 0.011), 0.01, 4); });
  for (const double voxelM : kVoxelsM) {
    const Rest r = settle(scene, surfaceModel(scene, {"ball"}, voxelM), 1500);
    EXPECT_GT(r.lowestM, 0.0) << voxelM;
    EXPECT_LE(r.gapM, 0.25 * voxelM) << voxelM;
    EXPECT_LT(glm::length(r.velocity), 1e-3) << voxelM;
    std::printf("sphere at %.2f mm voxels: rest gap %.3f voxel, least %.3f voxel\n", voxelM * 1e3,
                r.gapM / voxelM, r.lowestM / voxelM);
  }
}

TEST(SurfaceContact, ABoxRestsFlatWithinAQuarterVoxelWhereTheVoxelPlanesHoldItNearTwoVoxelsUp) {
  const Scene scene = onPlate("box", [](TriangleMesh& m) {
    appendBox(m, test::at(0.0003, -0.0007, 0.0058), glm::dvec3(0.01, 0.01, 0.005));
  });
  for (const double voxelM : kVoxelsM) {
    const Rest surface = settle(scene, surfaceModel(scene, {"box"}, voxelM), 1500);
    const Rest paper = settle(scene, surfaceModel(scene, {"box"}, voxelM, false), 1500);
    EXPECT_GT(surface.lowestM, 0.0) << voxelM;
    EXPECT_LE(surface.gapM, 0.25 * voxelM) << voxelM;
    EXPECT_GT(paper.gapM, 1.0 * voxelM) << voxelM;
    std::printf("box at %.2f mm voxels: rest gap %.3f voxel (voxel planes %.3f)\n", voxelM * 1e3,
                surface.gapM / voxelM, paper.gapM / voxelM);
  }
}

// Two square rods turned 45° about their axes, crossed, an edge of each facing the other:
// the upper one, held level by its handle, is let down onto the lower's edge and pressed
// 1 mm past it. Its lowest edge must rest within a quarter voxel of the lower's edge
// without crossing it, by exact probes (the rod cannot rest free: it tips off the edge
// like a seesaw). Only the points on the upper's edge can meet the lower's edge; when they
// lay wherever the lattice put the surface point nearest a voxel's centre, the edges
// crossed by up to 0.3 voxel (non_penetration_test.cpp, CrossedRodsPressedEdgeOnEdge).
TEST(SurfaceContact, CrossedRodsRestEdgeOnEdgeWithinAQuarterVoxelWithoutCrossing) {
  const double half = 0.002;
  const double edge = half * std::sqrt(2.0);
  for (const double voxelM : kVoxelsM) {
    Scene scene;
    scene.objects.push_back(test::meshObject("lower", ObjectRole::Static, [&](TriangleMesh& m) {
      appendBox(m, glm::rotate(test::at(0.0, 0.00013, 0.0), M_PI / 4, glm::dvec3(1.0, 0.0, 0.0)),
                glm::dvec3(0.03, half, half));
    }));
    scene.objects.push_back(test::meshObject("upper", ObjectRole::Dynamic, [&](TriangleMesh& m) {
      appendBox(m,
                glm::rotate(test::at(0.00021, 0.0, 2.0 * edge + 0.002), M_PI / 4, glm::dvec3(0.0, 1.0, 0.0)),
                glm::dvec3(half, 0.03, half));
    }));
    SimModel model = surfaceModel(scene, {"upper"}, voxelM);
    model.objects[0].coupled = true;
    LocalSimulation sim(model);
    ExactPenetration exact({{&scene.objects[1].parts[0].mesh}}, {{&scene.objects[0].parts[0].mesh}},
                           voxelM / kProbesPerVoxel);
    HandleInput handle;
    double deepestM = 0.0;
    PenetrationSample last;
    for (int frame = 1; frame <= 1000; ++frame) {
      handle.poseWorld.position.z = -0.003 * std::min(1.0, frame / 300.0);
      sim.step({&handle, 1});
      if (frame % 20 != 0) continue;
      last = exact.measure(objectPose(model, sim.state, 0), Pose{});
      deepestM = std::max(deepestM, last.depthM);
    }
    EXPECT_EQ(deepestM, 0.0) << "the edges crossed at " << voxelM;
    EXPECT_LE(last.clearanceM, 0.25 * voxelM) << voxelM;
    std::printf("crossed rods at %.2f mm voxels: rest gap %.3f voxel, deepest %.3f voxel\n", voxelM * 1e3,
                last.clearanceM / voxelM, deepestM / voxelM);
  }
}

// The seated ball, its points half a voxel inward (the clearance its limits need), turned
// about x by its handle, follows it. With each voxel's plane alone it did not (0.013 rad of
// the 1.57 asked in 0.5 s at 1 mm voxels): a plane extrapolated up to 0.87 voxel from its
// voxel's centre, across the socket's rim, lies under the true distance there, and rows at
// their own limits (depth_limit.h) refused the turn. The surrounding voxels' planes
// (surface_distance.h) give the rim its distance.
TEST(SurfaceContact, TheSeatedBallTurnsInItsSocket) {
  const Scene scene = makeBallAndSocket();
  SceneModelOptions options = seatedBallOptions();
  options.pointDisplacementM = -0.0005;
  const SimModel model = buildSceneModel(scene, {"ball"}, options);
  LocalSimulation sim(model);
  constexpr double kTurnRad = 0.5 * M_PI;
  HandleInput handle;
  for (int frame = 1; frame <= 500; ++frame) {
    handle.poseWorld.orientation = quatFromRotationVector(glm::dvec3(kTurnRad * frame / 500.0, 0.0, 0.0));
    sim.step({&handle, 1});
  }
  const double turnedRad = glm::length(rotationVector(objectPose(model, sim.state, 0).orientation));
  EXPECT_NEAR(turnedRad, kTurnRad, 0.1);
}

// The seated ball pressed 1 mm down into its socket by its handle: rows with limits of
// their own hold it while the coupling pulls far harder than the contacts' springs push.
// The contact force reported must still balance the pull and the weight at rest, the
// limits' share included (the HUD showed the springs' share alone, an eighth of the pull).
TEST(SurfaceContact, TheContactForceAtRestBalancesThePullAndTheWeight) {
  const Scene scene = makeBallAndSocket();
  SceneModelOptions options = seatedBallOptions();
  options.sim.gravityWorld = kGravity;
  const SimModel model = buildSceneModel(scene, {"ball"}, options);
  LocalSimulation sim(model);
  HandleInput handle;
  handle.poseWorld.position = glm::dvec3(0.0, 0.0, -0.001);
  for (int frame = 0; frame < 700; ++frame) sim.step({&handle, 1});
  const ObjectFrame& f = sim.object(0);
  const glm::dvec3 weight = model.objects[0].body.massKg * kGravity;
  EXPECT_GT(sim.outputs.depthLimit.rowLimits, 0u);
  EXPECT_GT(glm::length(f.feedback.forceWorld), 2.0 * glm::length(weight));
  // the device feels the opposite of the coupling's pull on the ball
  EXPECT_LT(glm::length(f.contactForceWorld + weight - f.feedback.forceWorld),
            0.1 * glm::length(f.feedback.forceWorld));
}

TEST(SurfaceContact, PointsMoreThanTwoVoxelsApartAreRefused) {
  const Scene scene =
      onPlate("ball", [](TriangleMesh& m) { appendGeodesicSphere(m, test::at(0, 0, 0.011), 0.01, 3); });
  SceneModelOptions options = test::ampleCapacityOptions();
  options.staticVoxelSizeM = 0.001;
  options.pointSpacingM = 0.0025;
  options.sim.surfaceContact = true;
  EXPECT_THROW(buildSceneModel(scene, {"ball"}, options), Error);
  options.pointSpacingM = 0.001;
  options.sim.forceLayer = distanceValue(0);
  EXPECT_THROW(buildSceneModel(scene, {"ball"}, options), Error);
}

TEST(SurfaceContact, AForceLayerThatDoesNotReachItsPointsIsRefusedWhileRunning) {
  const Scene scene =
      onPlate("ball", [](TriangleMesh& m) { appendGeodesicSphere(m, test::at(0, 0, 0.011), 0.01, 3); });
  for (const bool surface : {true, false}) {
    const SimModel model = surfaceModel(scene, {"ball"}, 0.001, surface);
    LocalSimulation sim(model);
    EXPECT_EQ(model.minForceLayer(), surface ? kSurfaceContactForceLayer : 1);
    // no force layer asked: each contact's own
    EXPECT_EQ(sim.state.forceLayer, surface ? kSurfaceContactForceLayer : kDefaultForceLayer);
    EXPECT_EQ(setForceLayer(model, sim.state, sim.workspace, distanceValue(0)), !surface);
    EXPECT_TRUE(setForceLayer(model, sim.state, sim.workspace, kSurfaceContactForceLayer));
  }
}

}  // namespace
}  // namespace voxhap
