// buildSceneModel: a group of a CAD file (no Voxhap extras) moves as one rigid body with
// the mass of all its parts while everything else stays static; each object's points are
// displaced by its own point offset unless the options set one for all.
#include "haptics/sim/scene_model.h"

#include <map>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "haptics/core/error.h"
#include "haptics/dynamics/mass_properties.h"
#include "haptics/geometry/mesh_builder.h"
#include "haptics/scene/gltf_loader.h"
#include "haptics/sim/local_simulation.h"
#include "support/contact_scenes.h"
#include "support/gltf_fixtures.h"

namespace voxhap {
namespace {

constexpr double kVoxel = 0.0005;     // m
constexpr double kBlockTopZ = 0.010;  // m, pistonAssemblyDoc

class SceneModelGroup : public ::testing::Test {
protected:
  Scene pistonScene() const {
    return loadGltfScene(
        test::writeDoc(test::pistonAssemblyDoc(), dir_.path(), "piston", test::BufferStorage::Glb));
  }
  test::TempDir dir_;
};

/// Whether some point of `shell` lies inside the axis-aligned box [lo, hi] grown by `margin`.
bool hasPointIn(const Pointshell& shell, const glm::dvec3& lo, const glm::dvec3& hi, double margin) {
  for (const glm::vec3& p : shell.positionsLocal) {
    const glm::dvec3 q(p);
    if (glm::all(glm::greaterThanEqual(q, lo - margin)) && glm::all(glm::lessThanEqual(q, hi + margin)))
      return true;
  }
  return false;
}

TEST_F(SceneModelGroup, AGroupMovesAsOneObjectWithTheMassOfAllItsParts) {
  const Scene scene = pistonScene();
  SceneModelOptions options = test::ampleCapacityOptions();
  options.staticVoxelSizeM = kVoxel;
  options.pointSpacingM = kVoxel;
  std::vector<std::string> voxelized;
  options.voxelizeFn = [&voxelized](std::span<const SceneObject* const> objects, const VoxelizeOptions& o,
                                    const ProgressFn& progress) {
    for (const SceneObject* object : objects) voxelized.push_back(object->name);
    return voxelizeObjects(objects, o, progress);
  };
  const SimModel model = buildSceneModel(scene, {"piston"}, options);

  ASSERT_EQ(model.objects.size(), 1u);
  const MovingObjectModel& piston = model.objects[0];
  EXPECT_EQ(piston.name, "piston");
  EXPECT_EQ(voxelized, (std::vector<std::string>{"block"}));  // only the block is static
  // mass and centre of mass: those of the crown and the pin together
  const SceneObject& crown = *scene.find("crown");
  const SceneObject& pin = *scene.find("pin");
  const MassProperties crownMass = computeMassProperties(crown, objectDensityKgPerM3(crown));
  const MassProperties pinMass = computeMassProperties(pin, objectDensityKgPerM3(pin));
  EXPECT_NEAR(piston.body.massKg, crownMass.massKg + pinMass.massKg, 1e-12);
  EXPECT_NEAR(piston.body.massKg, kDefaultDensityKgPerM3 * (1e-6 + 6.4e-8), 1e-9);
  const glm::dvec3 com = (crownMass.massKg * crownMass.comLocal + pinMass.massKg * pinMass.comLocal) /
                         (crownMass.massKg + pinMass.massKg);
  EXPECT_LT(glm::length(piston.body.comLocal - com), 1e-9);
  // one pointshell over both parts
  EXPECT_TRUE(hasPointIn(piston.shell, {0.0, 0.0, 0.012}, {0.01, 0.01, 0.022}, kVoxel));
  EXPECT_TRUE(hasPointIn(piston.shell, {0.011, 0.003, 0.015}, {0.015, 0.007, 0.019}, kVoxel));
}

TEST_F(SceneModelGroup, AGroupFallsOntoTheBlockAsOneBody) {
  const Scene scene = pistonScene();
  const SimModel model = test::freeModel(scene, {"piston"}, kVoxel, glm::dvec3(0.0, 0.0, -9.81));
  LocalSimulation sim(model);
  SimState& state = sim.state;
  for (int frame = 0; frame < 600; ++frame) sim.step();
  const Pose pose = objectPose(model, state, 0);

  // the crown (the lower part) rests on the block within a voxel, the pin 3 mm above it
  EXPECT_NEAR(test::lowestZ(*scene.find("crown"), pose), kBlockTopZ, kVoxel);
  EXPECT_NEAR(test::lowestZ(*scene.find("pin"), pose), kBlockTopZ + 0.003, kVoxel);
  EXPECT_LT(std::abs(pose.position.x) + std::abs(pose.position.y), kVoxel);
  EXPECT_GT(sim.object(0).contacts, 0u);
}

TEST(SceneModelPointOffset, EachObjectHasItsOwnUnlessTheOptionsSetOneForAll) {
  Scene scene;
  scene.objects.push_back(test::plate());
  for (const char* name : {"seated", "plain"}) {
    scene.objects.push_back(test::meshObject(name, ObjectRole::Dynamic, [](TriangleMesh& m) {
      appendBox(m, test::at(0.0, 0.0, 0.02), glm::dvec3(0.005));
    }));
  }
  scene.objects[1].settings.pointOffsetM = -0.0005;
  SceneModelOptions options = test::ampleCapacityOptions();
  options.staticVoxelSizeM = 0.001;
  options.pointSpacingM = 0.001;
  std::map<std::string, double> displacementM;
  options.pointshellFn = [&displacementM](const SceneObject& object, const PointshellOptions& o,
                                          const ProgressFn& progress) {
    displacementM[object.name] = o.displacementM;
    return pointshellOf(object, o, progress);
  };
  buildSceneModel(scene, {"seated", "plain"}, options);
  EXPECT_EQ(displacementM, (std::map<std::string, double>{{"plain", 0.0}, {"seated", -0.0005}}));

  options.pointDisplacementM = 0.0002;
  buildSceneModel(scene, {"seated", "plain"}, options);
  EXPECT_EQ(displacementM, (std::map<std::string, double>{{"plain", 0.0002}, {"seated", 0.0002}}));
}

}  // namespace
}  // namespace voxhap
