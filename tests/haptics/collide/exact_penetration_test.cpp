#include "haptics/collide/exact_penetration.h"

#include <cmath>

#include <gtest/gtest.h>

#include "haptics/sim/scene_model.h"
#include "support/contact_scenes.h"

namespace voxhap {
namespace {

constexpr double kVoxel = 0.001;

/// The 100 × 100 × 10 mm plate (top face z = 0) with its voxmap.
struct Plate {
  SceneObject object = test::plate();
  Voxmap voxmap;
  Plate() {
    VoxelizeOptions options;
    options.voxelSizeM = kVoxel;
    const SceneObject* objects[] = {&object};
    voxmap = voxelizeObjects(objects, options, {});
  }
};

TEST(ExactPenetration, MeasuresTheDeepestVertexInsideAndTheClearanceOfTheOthers) {
  const Plate plate;
  const TriangleMesh* meshes[] = {&plate.object.parts[0].mesh};
  const glm::vec3 vertices[] = {{0.0101f, 0.0203f, -0.003f},  // 3 mm below the top face
                                {0.0101f, 0.0203f, -0.001f},  // 1 mm below
                                {-0.0202f, 0.0107f, 0.002f},  // 2 mm above
                                {0.3f, 0.0f, 0.0f},           // far away
                                {0.3f, 0.0f, 0.0f}};          // a duplicate, measured once
  ExactPenetration truth(meshes, vertices);
  EXPECT_EQ(truth.vertexCount(), 4u);

  const PenetrationSample at = truth.measure(Pose{}, plate.voxmap);
  EXPECT_EQ(at.inside, 2u);
  EXPECT_NEAR(at.depthM, 0.003, 1e-6);
  EXPECT_NEAR(at.deepestWorld.z, -0.003, 1e-6);
  EXPECT_NEAR(at.clearanceM, 0.002, 1e-6);

  // raised by 3.5 mm: nothing inside, the lowest vertex 0.5 mm above the face
  Pose raised;
  raised.position = {0.0, 0.0, 0.0035};
  const PenetrationSample above = truth.measure(raised, plate.voxmap);
  EXPECT_EQ(above.inside, 0u);
  EXPECT_EQ(above.depthM, 0.0);
  EXPECT_NEAR(above.clearanceM, 0.0005, 1e-6);

  // the inside vote itself, straight from the meshes
  EXPECT_TRUE(truth.inside({0.0, 0.0, -0.005}));
  EXPECT_FALSE(truth.inside({0.0, 0.0, 0.005}));
  EXPECT_FALSE(truth.inside({0.0, 0.06, -0.005}));  // beside the plate
}

}  // namespace
}  // namespace voxhap
