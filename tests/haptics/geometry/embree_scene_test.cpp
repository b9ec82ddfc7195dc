#include "haptics/geometry/embree_scene.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "haptics/geometry/mesh_builder.h"

namespace voxhap {
namespace {

TriangleMesh unitCube() {
  TriangleMesh m;
  appendBox(m, glm::dmat4(1.0), glm::dvec3(0.5));
  return m;
}

TEST(EmbreeScene, RayThroughACubeCrossesTwiceAtTheFaces) {
  const TriangleMesh cube = unitCube();
  const TriangleMesh* meshes[] = {&cube};
  const EmbreeScene scene(meshes);
  std::vector<RayCrossing> hits;
  scene.allCrossings({-2.0, 0.1, 0.2}, {1, 0, 0}, 10.0, hits);
  ASSERT_EQ(hits.size(), 2u);
  std::sort(hits.begin(), hits.end(), [](auto& a, auto& b) { return a.t < b.t; });
  EXPECT_NEAR(hits[0].t, 1.5, 1e-6);
  EXPECT_NEAR(hits[1].t, 2.5, 1e-6);
  hits.clear();
  scene.allCrossings({-2.0, 0.7, 0.2}, {1, 0, 0}, 10.0, hits);
  EXPECT_TRUE(hits.empty());
}

// Two cubes that overlap: a point in both is inside their union, though any one ray from
// it crosses the scene's surfaces an even number of times (once per cube). And a point in
// the plane of a face, where a ray along an axis could run inside that face.
TEST(EmbreeScene, InsideAnyPartIsInsideTheUnionOfOverlappingParts) {
  const TriangleMesh a = unitCube();
  TriangleMesh b;
  appendBox(b, glm::translate(glm::dmat4(1.0), glm::dvec3(0.6, 0.0, 0.0)), glm::dvec3(0.5));
  const TriangleMesh* meshes[] = {&a, &b};
  const EmbreeScene scene(meshes);
  InsideVoteScratch vote;
  EXPECT_TRUE(scene.insideAnyPart({0.3, 0.1, 0.2}, 10.0, vote));   // in both
  EXPECT_TRUE(scene.insideAnyPart({-0.3, 0.1, 0.2}, 10.0, vote));  // in a only
  EXPECT_TRUE(scene.insideAnyPart({0.9, -0.2, 0.1}, 10.0, vote));  // in b only
  EXPECT_FALSE(scene.insideAnyPart({1.2, 0.1, 0.2}, 10.0, vote));
  EXPECT_FALSE(scene.insideAnyPart({0.3, 0.7, 0.2}, 10.0, vote));
  EXPECT_FALSE(scene.insideAnyPart({0.3, 0.5 + 1e-4, 0.0}, 10.0, vote));  // just over the top faces
  EXPECT_TRUE(scene.insideAnyPart({0.3, 0.5 - 1e-4, 0.0}, 10.0, vote));
  // one ray's parity over every crossing, as bench error had it, says outside in both
  std::vector<RayCrossing> hits;
  scene.allCrossings({0.3, 0.1, 0.2}, glm::normalize(glm::dvec3(0.267, 0.535, 0.802)), 10.0, hits);
  EXPECT_EQ(hits.size() % 2, 0u);
}

TEST(EmbreeScene, ClosestPointGivesExactDistanceAndOutwardNormal) {
  const TriangleMesh cube = unitCube();
  const TriangleMesh* meshes[] = {&cube};
  const EmbreeScene scene(meshes);
  const auto face = scene.closestPoint({2.0, 0.1, -0.2}, 10.0);
  ASSERT_TRUE(face);
  EXPECT_NEAR(face->distanceM, 1.5, 1e-6);
  EXPECT_NEAR(face->faceNormal.x, 1.0, 1e-12);
  const auto corner = scene.closestPoint({1.5, 1.5, 1.5}, 10.0);
  ASSERT_TRUE(corner);
  EXPECT_NEAR(corner->distanceM, std::sqrt(3.0), 1e-6);
  EXPECT_FALSE(scene.closestPoint({3.0, 0.0, 0.0}, 1.0));  // beyond the search radius
}

TEST(EmbreeScene, TrianglesWithinARadiusAreEveryTriangleThatComesThatClose) {
  const TriangleMesh cube = unitCube();
  const TriangleMesh other = [] {
    TriangleMesh m;
    appendBox(m, glm::translate(glm::dmat4(1.0), glm::dvec3(3.0, 0.0, 0.0)), glm::dvec3(0.5));
    return m;
  }();
  const TriangleMesh* meshes[] = {&cube, &other};
  const EmbreeScene scene(meshes);
  // 0.6 from the +x face's centre: its two triangles only (the others are further)
  std::vector<TriangleRef> near;
  scene.trianglesWithin({1.1, 0.0, 0.0}, 0.65, near);
  ASSERT_EQ(near.size(), 2u);
  for (const TriangleRef& t : near) {
    EXPECT_EQ(t.part, 0u);
    const glm::uvec3& v = cube.triangles[t.triangle];
    for (const unsigned i : {v.x, v.y, v.z}) EXPECT_EQ(cube.positionsWorld[i].x, 0.5f);
  }
  EXPECT_LT(near[0], near[1]);  // sorted, each once
  // a radius reaching both boxes: every triangle of the +x face of one and the −x of the other
  near.clear();
  scene.trianglesWithin({1.5, 0.0, 0.0}, 1.05, near);
  EXPECT_EQ(near.size(), 4u);
  // appended after what is there, nothing when out of reach
  scene.trianglesWithin({10.0, 0.0, 0.0}, 1.0, near);
  EXPECT_EQ(near.size(), 4u);
}

TEST(EmbreeScene, ClosestPointOnTriangleRegions) {
  const glm::dvec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  const glm::dvec3 inside = closestPointOnTriangle({0.2, 0.2, 5}, a, b, c);
  EXPECT_NEAR(glm::length(inside - glm::dvec3(0.2, 0.2, 0)), 0.0, 1e-15);
  EXPECT_EQ(closestPointOnTriangle({-1, -1, 0}, a, b, c), a);
  EXPECT_EQ(closestPointOnTriangle({0.5, -1, 0}, a, b, c), glm::dvec3(0.5, 0, 0));
  const glm::dvec3 onHypotenuse = closestPointOnTriangle({1, 1, 0}, a, b, c);
  EXPECT_NEAR(onHypotenuse.x, 0.5, 1e-12);
  EXPECT_NEAR(onHypotenuse.y, 0.5, 1e-12);
}

}  // namespace
}  // namespace voxhap
