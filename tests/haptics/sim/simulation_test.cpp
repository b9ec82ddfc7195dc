#include <cmath>
#include <cstring>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "haptics/core/error.h"
#include "haptics/scene/builtin/builtin_scenes.h"
#include "haptics/sim/local_simulation.h"
#include "support/contact_scenes.h"

namespace voxhap {
namespace {

constexpr double kVoxel = 0.0005;  // m
const glm::dvec3 kGravity(0.0, 0.0, -9.81);

/// Runs `frames` free frames; calls `each(sim.state)` after every frame.
template <typename Each>
void runFree(LocalSimulation& sim, int frames, Each&& each) {
  for (int i = 0; i < frames; ++i) {
    sim.step();
    each(sim.state);
  }
}

Scene sphereOverPlate(double radiusM, double gapM) {
  Scene scene;
  scene.objects.push_back(test::plate());
  scene.objects.push_back(test::meshObject("ball", ObjectRole::Dynamic, [&](TriangleMesh& m) {
    appendGeodesicSphere(m, glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 0.0, radiusM + gapM)), radiusM,
                         4);
  }));
  return scene;
}

Scene boxOverPlate(double gapM) {
  Scene scene;
  scene.objects.push_back(test::plate());
  scene.objects.push_back(test::meshObject("box", ObjectRole::Dynamic, [&](TriangleMesh& m) {
    appendBox(m, glm::translate(glm::dmat4(1.0), glm::dvec3(0.0003, -0.0007, 0.005 + gapM)),
              glm::dvec3(0.01, 0.01, 0.005));
  }));
  return scene;
}

TEST(Simulation, SphereDroppedOnAPlateRestsWithAnExactGapAndNeverPenetrates) {
  const Scene scene = sphereOverPlate(0.01, 0.001);
  const SimModel model = test::freeModel(scene, {"ball"}, kVoxel, kGravity);
  LocalSimulation sim(model);
  SimState& state = sim.state;
  double lowest = 1e9;
  runFree(sim, 1500, [&](const SimState& s) {
    lowest = std::min(lowest, test::lowestZ(scene.objects[1], s.bodies[0].pose(model.objects[0].body)));
  });
  const double gap = test::lowestZ(scene.objects[1], objectPose(model, state, 0));
  EXPECT_GT(lowest, 0.0) << "exact surfaces interpenetrated";
  EXPECT_GE(gap, 0.0);
  EXPECT_LE(gap, 2.0 * kVoxel);
  EXPECT_LT(glm::length(state.bodies[0].linearVelocityWorld), 1e-3);
  // at rest the contacts carry the weight
  EXPECT_NEAR(sim.object(0).contactForceWorld.z, model.objects[0].body.massKg * 9.81,
              0.05 * model.objects[0].body.massKg * 9.81);
  EXPECT_GT(sim.object(0).contacts, 0u);
}

TEST(Simulation, RaisingTheForceLayerLiftsTheSphereByAVoxelPerLayer) {
  const Scene scene = sphereOverPlate(0.01, 0.001);
  const SimModel model = test::freeModel(scene, {"ball"}, kVoxel, kGravity);
  double gap[2];
  for (int k = 0; k < 2; ++k) {
    LocalSimulation sim(model);
    SimState& state = sim.state;
    ASSERT_TRUE(
        setForceLayer(model, state, sim.workspace, static_cast<std::uint8_t>(kDefaultForceLayer + 2 * k)));
    runFree(sim, 1500, [](const SimState&) {});
    gap[k] = test::lowestZ(scene.objects[1], objectPose(model, state, 0));
  }
  EXPECT_NEAR(gap[1] - gap[0], 2.0 * kVoxel, 0.5 * kVoxel);
  LocalSimulation sim(model);
  SimState& state = sim.state;
  EXPECT_FALSE(setForceLayer(model, state, sim.workspace, 0));
  EXPECT_FALSE(setForceLayer(model, state, sim.workspace, 11));
  EXPECT_EQ(state.forceLayer, kDefaultForceLayer);
}

TEST(Simulation, APartsOwnForceLayerHoldsItWhateverTheSessionsLayer) {
  // the sphere's own layer 4 (a mating part's, paper §3.2) against the session's 4 and 6
  Scene scene = sphereOverPlate(0.01, 0.001);
  const SimModel plain = test::freeModel(scene, {"ball"}, kVoxel, kGravity);
  scene.objects[1].settings.forceLayer = kDefaultForceLayer;
  const SimModel own = test::freeModel(scene, {"ball"}, kVoxel, kGravity);
  ASSERT_EQ(own.pairs.at(0).ownForceLayer, std::optional<std::uint8_t>(kDefaultForceLayer));
  const auto restingGapM = [&](const SimModel& model, std::uint8_t sessionLayer) {
    LocalSimulation sim(model);
    EXPECT_TRUE(setForceLayer(model, sim.state, sim.workspace, sessionLayer));
    runFree(sim, 1500, [](const SimState&) {});
    return test::lowestZ(scene.objects[1], objectPose(model, sim.state, 0));
  };
  const auto higher = static_cast<std::uint8_t>(kDefaultForceLayer + 2);
  const double plainGapM = restingGapM(plain, kDefaultForceLayer);
  EXPECT_NEAR(restingGapM(plain, higher) - plainGapM, 2.0 * kVoxel, 0.5 * kVoxel);  // the session's moves it
  EXPECT_EQ(restingGapM(own, higher), plainGapM);  // its own holds: the same frames, bit for bit
}

TEST(Simulation, AForceLayerOfItsOwnThatAPairCannotRenderIsRefusedNamingThePair) {
  Scene scene = sphereOverPlate(0.01, 0.001);
  scene.objects[1].settings.forceLayer = 2;  // surface contact pushes points up to layer 3
  try {
    test::freeModel(scene, {"ball"}, kVoxel, kGravity, true, true);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("ball against the static scene: its own force layer 2"),
              std::string::npos)
        << e.what();
  }
  scene.objects[1].settings.forceLayer = 200;  // beyond the voxmap's values
  EXPECT_THROW(test::freeModel(scene, {"ball"}, kVoxel, kGravity), Error);
  SceneModelOptions options = test::ampleCapacityOptions();
  options.staticVoxelSizeM = options.pointSpacingM = kVoxel;
  options.forceLayerOf["plate"] = 3;  // static: no pair of its own
  EXPECT_THROW(buildSceneModel(scene, {"ball"}, options), Error);
  options.forceLayerOf = {{"ball", 5}};  // over the scene's 200
  EXPECT_EQ(buildSceneModel(scene, {"ball"}, options).pairs.at(0).ownForceLayer,
            std::optional<std::uint8_t>(5));
}

TEST(Simulation, PointsFromAFreeLayerHoldTheSphereThatManyVoxelsHigher) {
  const Scene scene = sphereOverPlate(0.01, 0.003);
  double gap[2];
  for (int layer : {0, 2}) {
    SceneModelOptions options = test::ampleCapacityOptions();
    options.staticVoxelSizeM = kVoxel;
    options.pointSpacingM = kVoxel;
    options.pointFreeLayer = layer;
    options.sim.gravityWorld = kGravity;
    SimModel model = buildSceneModel(scene, {"ball"}, options);
    model.objects[0].coupled = false;
    LocalSimulation sim(model);
    SimState& state = sim.state;
    runFree(sim, 1500, [](const SimState&) {});
    gap[layer / 2] = test::lowestZ(scene.objects[1], objectPose(model, state, 0));
  }
  EXPECT_NEAR(gap[1] - gap[0], 2.0 * kVoxel, 0.75 * kVoxel);
}

TEST(Simulation, PreContactDampingSlowsTheApproachBeforeContact) {
  const Scene scene = sphereOverPlate(0.01, 0.004);
  double speedAtContact[2];
  for (int damped = 0; damped < 2; ++damped) {
    SceneModelOptions options = test::ampleCapacityOptions();
    options.staticVoxelSizeM = kVoxel;
    options.pointSpacingM = kVoxel;
    options.sim.preContactDamping = damped == 1;
    SimModel model = buildSceneModel(scene, {"ball"}, options);
    model.objects[0].coupled = false;
    LocalSimulation sim(model);
    SimState& state = sim.state;
    state.bodies[0].linearVelocityWorld = glm::dvec3(0.0, 0.0, -0.1);
    const double energyBefore = kineticEnergyJ(model.objects[0].body, state.bodies[0]);
    speedAtContact[damped] = -1.0;
    runFree(sim, 400, [&](const SimState& s) {
      if (speedAtContact[damped] < 0.0 && sim.object(0).contacts > 0) {
        speedAtContact[damped] = glm::length(s.bodies[0].linearVelocityWorld);
      }
      EXPECT_LE(kineticEnergyJ(model.objects[0].body, s.bodies[0]), energyBefore * (1.0 + 1e-9));
    });
    ASSERT_GT(speedAtContact[damped], 0.0) << "no contact";
  }
  EXPECT_LT(speedAtContact[1], 0.9 * speedAtContact[0]);
}

TEST(Simulation, BoxRestsFlatOnAPlateWithNegligibleTorque) {
  const Scene scene = boxOverPlate(0.0008);
  const SimModel model = test::freeModel(scene, {"box"}, kVoxel, kGravity);
  LocalSimulation sim(model);
  SimState& state = sim.state;
  double lowest = 1e9;
  runFree(sim, 1500, [&](const SimState& s) {
    lowest = std::min(lowest, test::lowestZ(scene.objects[1], s.bodies[0].pose(model.objects[0].body)));
  });
  const double weightN = model.objects[0].body.massKg * 9.81;
  const double tiltRad = glm::length(rotationVector(state.bodies[0].orientation));
  EXPECT_LT(tiltRad, 0.002);
  EXPECT_LT(glm::length(sim.object(0).contactTorqueWorld), 0.01 * weightN * 0.01);
  EXPECT_GT(lowest, 0.0);
  // the plate's top lies on a voxel boundary, so both voxel layers it touches are
  // surface voxels and the force layer sits half a voxel higher than usual
  const double gap = test::lowestZ(scene.objects[1], objectPose(model, state, 0));
  EXPECT_GE(gap, 0.0);
  EXPECT_LE(gap, 2.5 * kVoxel);
}

TEST(Simulation, TheContactSampleLiesUnderTheRestingBoxSpreadOverItsFoot) {
  const Scene scene = boxOverPlate(0.0008);
  // without geometrical awareness: every point of its foot in contact, not only its corners
  const SimModel model = test::freeModel(scene, {"box"}, kVoxel, kGravity, false);
  LocalSimulation sim(model);
  runFree(sim, 1500, [](const SimState&) {});
  const ObjectFrame& box = sim.object(0);
  ASSERT_GT(box.contacts, ContactSample::kCapacity);
  ASSERT_EQ(box.contactSample.count, ContactSample::kCapacity);
  // the points are where the box was when the frame began
  const double footZ =
      test::lowestZ(scene.objects[1], sim.workspace.beforeStep[0].pose(model.objects[0].body));
  glm::vec3 lo(1e9f);
  glm::vec3 hi(-1e9f);
  for (const glm::vec3& p : box.contactSample.points()) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  // the foot spans x 0.3 ± 10 mm, y −0.7 ± 10 mm; surface voxels' centres lie within half
  // a voxel of it
  const double halfM = 0.01 + 0.5 * kVoxel;
  EXPECT_GT(lo.x, 0.0003 - halfM);
  EXPECT_LT(hi.x, 0.0003 + halfM);
  EXPECT_GT(lo.y, -0.0007 - halfM);
  EXPECT_LT(hi.y, -0.0007 + halfM);
  EXPECT_GT(hi.x - lo.x, 0.015) << "the sample is not spread over the foot";
  EXPECT_GT(hi.y - lo.y, 0.015) << "the sample is not spread over the foot";
  EXPECT_GT(lo.z, footZ - 0.5 * kVoxel);
  EXPECT_LT(hi.z, footZ + 0.5 * kVoxel);
}

TEST(Simulation, GeometricalAwarenessRestsTheBoxAlikeWithFarFewerContacts) {
  const Scene scene = boxOverPlate(0.0008);
  double gap[2];
  std::uint32_t contacts[2];
  for (int aware = 0; aware < 2; ++aware) {
    const SimModel model = test::freeModel(scene, {"box"}, kVoxel, kGravity, aware == 1);
    LocalSimulation sim(model);
    SimState& state = sim.state;
    runFree(sim, 1200, [](const SimState&) {});
    gap[aware] = test::lowestZ(scene.objects[1], objectPose(model, state, 0));
    contacts[aware] = sim.object(0).contacts;
  }
  EXPECT_NEAR(gap[1], gap[0], kVoxel);
  EXPECT_GT(contacts[1], 0u);
  EXPECT_LT(contacts[1] * 10, contacts[0]) << "aware " << contacts[1] << ", unaware " << contacts[0];
}

TEST(Simulation, CrossedRodsPushApartAlongTheCommonNormal) {
  // two square rods turned 45° about their axes, so that an edge of each faces the
  // other; the upper one starts inside the force layer, free and without gravity
  const double half = 0.002;
  Scene scene;
  scene.objects.push_back(test::meshObject("lower", ObjectRole::Static, [&](TriangleMesh& m) {
    appendBox(m, glm::rotate(glm::dmat4(1.0), M_PI / 4, glm::dvec3(1.0, 0.0, 0.0)),
              glm::dvec3(0.03, half, half));
  }));
  const double edge = half * std::sqrt(2.0);  // height of the lower rod's top edge
  scene.objects.push_back(test::meshObject("upper", ObjectRole::Dynamic, [&](TriangleMesh& m) {
    glm::dmat4 t = glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 0.0, 2.0 * edge + kVoxel));
    appendBox(m, glm::rotate(t, M_PI / 4, glm::dvec3(0.0, 1.0, 0.0)), glm::dvec3(half, 0.03, half));
  }));
  const SimModel model = test::freeModel(scene, {"upper"}, kVoxel, glm::dvec3(0.0));
  LocalSimulation sim(model);
  SimState& state = sim.state;
  sim.step();
  const glm::dvec3 f = sim.object(0).contactForceWorld;
  EXPECT_GT(f.z, 0.0);
  EXPECT_LT(std::hypot(f.x, f.y), 0.1 * f.z) << f.x << " " << f.y << " " << f.z;
  double lowestGap = 1e9;
  runFree(sim, 300, [&](const SimState& s) {
    lowestGap =
        std::min(lowestGap, test::lowestZ(scene.objects[1], s.bodies[0].pose(model.objects[0].body)) - edge);
  });
  // pushed apart along the common normal (z), not sideways
  const glm::dvec3 moved = objectPose(model, state, 0).position;
  EXPECT_GT(moved.z, 0.0);
  EXPECT_GT(moved.z, 3.0 * std::hypot(moved.x, moved.y)) << moved.x << " " << moved.y << " " << moved.z;
  EXPECT_GT(lowestGap, 0.0) << "the edges crossed";
}

TEST(Simulation, BallStaysSeatedInItsSocket) {
  const Scene scene = makeBallAndSocket();
  SceneModelOptions options = test::ampleCapacityOptions();
  options.staticVoxelSizeM = 0.00035;
  options.pointSpacingM = 0.00035;
  options.pointDisplacementM = -0.5 * 0.00035;
  options.sim.gravityWorld = kGravity;
  SimModel model = buildSceneModel(scene, {"ball"}, options);
  model.objects[0].coupled = false;
  LocalSimulation sim(model);
  SimState& state = sim.state;
  runFree(sim, 300, [](const SimState&) {});
  const glm::dvec3 moved = objectPose(model, state, 0).position;
  EXPECT_LT(glm::length(moved), 0.00035) << "the ball sank or jumped";
  EXPECT_GT(sim.object(0).contacts, 0u);
  EXPECT_NEAR(sim.object(0).contactForceWorld.z, model.objects[0].body.massKg * 9.81,
              0.1 * model.objects[0].body.massKg * 9.81);
}

TEST(Simulation, PegSlidesIntoItsHoleWithoutJamming) {
  // a 6 mm peg over a hole with 0.2 mm of radial clearance, a voxel of 0.04 mm
  constexpr double voxel = 0.00004;
  Scene scene;
  scene.objects.push_back(test::meshObject("block", ObjectRole::Static, [](TriangleMesh& m) {
    appendBlockWithHole(m, glm::dmat4(1.0), {0.006, 0.008, 0.0032, 0.008}, 64);
  }));
  scene.objects.push_back(test::meshObject("peg", ObjectRole::Dynamic, [](TriangleMesh& m) {
    appendCylinder(m, glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 0.0, 0.0085)), 0.003, 0.010, 64);
  }));
  SceneModelOptions options = test::ampleCapacityOptions();
  options.staticVoxelSizeM = voxel;
  options.pointSpacingM = voxel;
  const SimModel model = buildSceneModel(scene, {"peg"}, options);
  // handle: off-centre by 0.1 mm, pushed 6 mm down over 0.6 s, then held
  std::vector<MotionKeyframe> keys = {{0.0, Pose{glm::dvec3(0.0001, 0.0, 0.0), identityQuat()}},
                                      {0.6, Pose{glm::dvec3(0.0001, 0.0, -0.006), identityQuat()}},
                                      {0.8, Pose{glm::dvec3(0.0001, 0.0, -0.006), identityQuat()}}};
  ScriptedDevice device(MotionScript(keys, "peg script"));
  HapticDevice* devices[] = {&device};
  LocalSimulation sim(model);
  SimState& state = sim.state;
  for (int i = 0; i < 800; ++i) sim.stepWithDevices(devices);
  const glm::dvec3 at = objectPose(model, state, 0).position;
  EXPECT_LT(at.z, -0.0057) << "the peg jammed at depth " << -at.z;
  EXPECT_LT(std::hypot(at.x, at.y), 0.0002);
}

TEST(Simulation, LongBarOnHundredsOfShallowContactsStaysCalm) {
  // without geometrical awareness a 90 mm bar lying on the plate touches it with
  // hundreds of points at once; the stiffness cap must hold their sum
  Scene scene;
  scene.objects.push_back(test::plate());
  scene.objects.push_back(test::meshObject("bar", ObjectRole::Dynamic, [](TriangleMesh& m) {
    appendBox(m, glm::translate(glm::dmat4(1.0), glm::dvec3(0.0002, 0.0001, 0.0025 + 0.0009)),
              glm::dvec3(0.045, 0.0025, 0.0025));
  }));
  const SimModel model = test::freeModel(scene, {"bar"}, kVoxel, kGravity, false);
  LocalSimulation sim(model);
  SimState& state = sim.state;
  std::uint32_t contacts = 0;
  double fastestSpin = 0.0;
  runFree(sim, 1500, [&](const SimState& s) {
    contacts = std::max(contacts, sim.object(0).contacts);
    if (s.frame > 1000) fastestSpin = std::max(fastestSpin, glm::length(s.bodies[0].angularVelocityWorld));
  });
  EXPECT_GT(contacts, 200u);
  EXPECT_LT(fastestSpin, 0.05) << "rad/s; now " << state.bodies[0].angularVelocityWorld.x << " "
                               << state.bodies[0].angularVelocityWorld.y << " "
                               << state.bodies[0].angularVelocityWorld.z;
  const glm::dvec3 v = state.bodies[0].linearVelocityWorld;
  EXPECT_LT(glm::length(v), 1e-3) << v.x << " " << v.y << " " << v.z;
}

TEST(Simulation, TwoMovingBoxesCollideWithEqualAndOppositeForces) {
  Scene scene;
  for (int i = 0; i < 2; ++i) {
    scene.objects.push_back(
        test::meshObject(i == 0 ? "left" : "right", ObjectRole::Dynamic, [&](TriangleMesh& m) {
          const double x = i == 0 ? -0.0062 : 0.0061;
          appendBox(m, glm::translate(glm::dmat4(1.0), glm::dvec3(x, 0.0003 * i, 0.0)),
                    glm::dvec3(0.005, 0.004, 0.003 + 0.001 * i));
        }));
  }
  const SimModel model = test::freeModel(scene, {"left", "right"}, kVoxel, glm::dvec3(0.0));
  ASSERT_EQ(model.pairs.size(), 1u);
  LocalSimulation sim(model);
  SimState& state = sim.state;
  state.bodies[0].linearVelocityWorld = glm::dvec3(0.05, 0.0, 0.0);
  auto momentum = [&] {
    return model.objects[0].body.massKg * state.bodies[0].linearVelocityWorld +
           model.objects[1].body.massKg * state.bodies[1].linearVelocityWorld;
  };
  const glm::dvec3 before = momentum();
  std::uint32_t contacts = 0;
  runFree(sim, 200, [&](const SimState&) {
    contacts = std::max(contacts, sim.object(0).contacts);
    EXPECT_LT(glm::length(sim.object(0).contactForceWorld + sim.object(1).contactForceWorld), 1e-12);
  });
  EXPECT_GT(contacts, 0u);
  EXPECT_LT(glm::length(momentum() - before), 1e-9 * glm::length(before));
  // the right box was pushed away, the left one slowed down
  EXPECT_GT(state.bodies[1].linearVelocityWorld.x, 0.01);
  EXPECT_LT(state.bodies[0].linearVelocityWorld.x, 0.04);
}

TEST(Simulation, PairsOutOfRangeCostNoPointTests) {
  const Scene scene = sphereOverPlate(0.01, 0.05);
  const SimModel model = test::freeModel(scene, {"ball"}, kVoxel, glm::dvec3(0.0));
  LocalSimulation sim(model);
  runFree(sim, 10, [&](const SimState&) { EXPECT_EQ(sim.object(0).tested, 0u); });
  EXPECT_EQ(sim.workspace.counters.pairsSkipped, 10u);
}

TEST(Simulation, SameInputsGiveTheSameBits) {
  const Scene scene = boxOverPlate(0.0008);
  const SimModel model = test::freeModel(scene, {"box"}, kVoxel, kGravity);
  LocalSimulation a(model);
  LocalSimulation b(model);
  runFree(a, 300, [](const SimState&) {});
  runFree(b, 300, [](const SimState&) {});
  EXPECT_EQ(std::memcmp(&a.state.bodies[0], &b.state.bodies[0], sizeof(RigidBodyState)), 0);
  EXPECT_EQ(hashState(a.state), hashState(b.state));
}

TEST(SceneModel, UnknownOrRepeatedObjectIsAnErrorNamingIt) {
  const Scene scene = boxOverPlate(0.001);
  SceneModelOptions options = test::ampleCapacityOptions();
  options.staticVoxelSizeM = kVoxel;
  options.pointSpacingM = kVoxel;
  try {
    buildSceneModel(scene, {"crate"}, options);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("crate"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("box"), std::string::npos) << e.what();
  }
  EXPECT_THROW(buildSceneModel(scene, {"box", "box"}, options), Error);
}

}  // namespace
}  // namespace voxhap
