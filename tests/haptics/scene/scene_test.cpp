#include "haptics/scene/scene.h"

#include <gtest/gtest.h>

namespace voxhap {
namespace {

Part triangle(float x) {
  TriangleMesh m;
  m.positionsWorld = {{x, 0, 0}, {x + 1, 0, 0}, {x, 2, 0}, {99, 99, 99}};  // vertex 3 unused
  m.triangles = {{0, 1, 2}};
  return makePart("t", glm::vec4(1.0f), m);
}

TEST(Scene, BoundsCoverUsedVerticesOnly) {
  SceneObject object{"o", {}, {triangle(0.0f), triangle(5.0f)}};
  const Bounds b = object.bounds();
  EXPECT_EQ(b.min, glm::dvec3(0, 0, 0));
  EXPECT_EQ(b.max, glm::dvec3(6, 2, 0));
  EXPECT_EQ(b.extent(), glm::dvec3(6, 2, 0));
}

TEST(Scene, CountsTrianglesByRoleAndFindsObjects) {
  Scene scene;
  scene.objects.push_back({"fixed", {ObjectRole::Static, {}, {}, {}}, {triangle(0.0f)}});
  scene.objects.push_back({"moving", {ObjectRole::Dynamic, {}, {}, {}}, {triangle(1.0f), triangle(2.0f)}});
  EXPECT_EQ(scene.triangleCount(), 3u);
  EXPECT_EQ(scene.triangleCount(ObjectRole::Static), 1u);
  EXPECT_EQ(scene.triangleCount(ObjectRole::Dynamic), 2u);
  ASSERT_NE(scene.find("moving"), nullptr);
  EXPECT_EQ(scene.find("moving")->parts.size(), 2u);
  EXPECT_EQ(scene.find("absent"), nullptr);
}

TEST(Scene, EmptyBoundsHaveZeroExtent) {
  const Bounds b;
  EXPECT_TRUE(b.empty());
  EXPECT_EQ(b.extent(), glm::dvec3(0.0));
}

}  // namespace
}  // namespace voxhap
