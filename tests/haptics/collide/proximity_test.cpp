#include "haptics/collide/proximity.h"

#include <cmath>

#include <gtest/gtest.h>

#include "haptics/geometry/embree_scene.h"
#include "support/contact_scenes.h"

namespace voxhap {
namespace {

constexpr double kVoxel = 0.0005;
constexpr double kGap = 0.002;

struct SphereOverPlate {
  Scene scene;
  Voxmap plate;
  Voxmap sphereVoxels;
  Pointshell sphere;
  SphereOverPlate() {
    scene.objects.push_back(test::plate());
    scene.objects.push_back(test::meshObject("ball", ObjectRole::Dynamic, [](TriangleMesh& m) {
      appendGeodesicSphere(m, glm::translate(glm::dmat4(1.0), glm::dvec3(0.0001, 0.0002, 0.01 + kGap)), 0.01,
                           4);
    }));
    VoxelizeOptions voxels;
    voxels.voxelSizeM = kVoxel;
    const SceneObject* plateObject[] = {&scene.objects[0]};
    plate = voxelizeObjects(plateObject, voxels, {});
    const SceneObject* ballObject[] = {&scene.objects[1]};
    sphereVoxels = voxelizeObjects(ballObject, voxels, {});
    PointshellOptions points;
    points.pointSpacingM = kVoxel;
    sphere = pointshellOf(scene.objects[1], points, {});
  }
};

TEST(Proximity, VertexDistancesAgreeWithExactDistancesWithinAVoxel) {
  const SphereOverPlate s;
  const TriangleMesh& mesh = s.scene.objects[1].parts[0].mesh;
  std::vector<float> distances;
  vertexDistancesM(mesh.positionsWorld, Pose{}, s.plate, distances);
  const TriangleMesh* plateMesh[] = {&s.scene.objects[0].parts[0].mesh};
  const EmbreeScene exact(plateMesh);
  int known = 0;
  for (std::size_t i = 0; i < distances.size(); ++i) {
    const auto truth = exact.closestPoint(glm::dvec3(mesh.positionsWorld[i]), 1.0);
    ASSERT_TRUE(truth);
    if (std::isinf(distances[i])) {
      EXPECT_GT(truth->distanceM, 7.5 * kVoxel) << i;  // beyond the 8-voxel field
      continue;
    }
    ++known;
    EXPECT_NEAR(distances[i], truth->distanceM, 1.0 * kVoxel) << i;
  }
  EXPECT_GT(known, 20);
}

TEST(Proximity, MinimumDistanceEstimateIsWithinAVoxelOfTheExactGap) {
  const SphereOverPlate s;
  EXPECT_NEAR(minimumDistanceM(s.sphere, Pose{}, s.plate), kGap, 1.5 * kVoxel);
  // far away: nothing known
  EXPECT_TRUE(
      std::isinf(minimumDistanceM(s.sphere, Pose{glm::dvec3(0.0, 0.0, 0.05), identityQuat()}, s.plate)));
}

TEST(Proximity, ShadowHoldsThePlateVoxelsUnderTheSphere) {
  const SphereOverPlate s;
  std::vector<glm::ivec3> shadow;
  surfaceVoxelsNear(s.plate, s.sphereVoxels, Pose{}, 0.003, shadow);
  ASSERT_FALSE(shadow.empty());
  const TriangleMesh* sphereMesh[] = {&s.scene.objects[1].parts[0].mesh};
  const EmbreeScene exact(sphereMesh);
  for (const glm::ivec3& v : shadow) {
    const auto truth = exact.closestPoint(s.plate.grid().voxelCentre(v), 1.0);
    ASSERT_TRUE(truth);
    // chessboard distance d·s ≤ 3 mm bounds the Euclidean one by √3·(d + ½)·s (proximity.h)
    EXPECT_LE(truth->distanceM, std::sqrt(3.0) * (0.003 + 0.5 * kVoxel));
  }
  // the voxel right under the sphere is in it, one 8 mm off to the side is not
  const auto under = s.plate.grid().voxelOf(glm::dvec3(0.0001, 0.0002, -0.0001));
  const auto aside = s.plate.grid().voxelOf(glm::dvec3(0.009, 0.009, -0.0001));
  EXPECT_NE(std::find(shadow.begin(), shadow.end(), under), shadow.end());
  EXPECT_EQ(std::find(shadow.begin(), shadow.end(), aside), shadow.end());
}

}  // namespace
}  // namespace voxhap
