#include "haptics/geometry/mesh_topology.h"

#include <gtest/gtest.h>

namespace voxhap {
namespace {

/// Unit cube with outward, counter-clockwise triangles and shared vertices.
TriangleMesh cube() {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i) m.positionsWorld.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  m.triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                 {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  return m;
}

TEST(MeshTopology, CubeIsClosedOrientedWithUnitVolume) {
  const MeshTopology t = computeTopology(cube());
  EXPECT_TRUE(t.closed());
  EXPECT_TRUE(t.consistentlyOriented());
  EXPECT_FALSE(t.firstOpenEdgeWorld);
  EXPECT_DOUBLE_EQ(signedVolume(cube()), 1.0);
}

TEST(MeshTopology, MissingTriangleLeavesThreeBoundaryEdgesAndSaysWhere) {
  TriangleMesh m = cube();
  m.triangles.pop_back();  // {1, 7, 5} on the x = 1 face
  const MeshTopology t = computeTopology(m);
  EXPECT_EQ(t.boundaryEdges, 3u);
  EXPECT_FALSE(t.closed());
  ASSERT_TRUE(t.firstOpenEdgeWorld);
  EXPECT_FLOAT_EQ(t.firstOpenEdgeWorld->x, 1.0f);
}

TEST(MeshTopology, FlippedTriangleIsMisoriented) {
  TriangleMesh m = cube();
  std::swap(m.triangles[0].y, m.triangles[0].z);
  const MeshTopology t = computeTopology(m);
  EXPECT_TRUE(t.closed());
  EXPECT_EQ(t.misorientedEdges, 3u);
}

TEST(MeshTopology, SplitVerticesAreWeldedByPosition) {
  // every triangle with its own three vertices, as exporters write flat-shaded meshes
  const TriangleMesh shared = cube();
  TriangleMesh split;
  for (const glm::uvec3& t : shared.triangles) {
    const auto base = static_cast<unsigned>(split.positionsWorld.size());
    for (int k = 0; k < 3; ++k) split.positionsWorld.push_back(shared.positionsWorld[t[k]]);
    split.triangles.emplace_back(base, base + 1, base + 2);
  }
  EXPECT_TRUE(computeTopology(split).closed());
  EXPECT_TRUE(computeTopology(split).consistentlyOriented());
}

TEST(MeshTopology, ThirdTriangleOnAnEdgeIsNonManifold) {
  TriangleMesh m = cube();
  m.positionsWorld.emplace_back(0.5f, 2.0f, 0.5f);
  m.triangles.emplace_back(2, 3, 8);  // a fin on the top edge 2-3
  const MeshTopology t = computeTopology(m);
  EXPECT_EQ(t.nonManifoldEdges, 1u);
  EXPECT_FALSE(t.closed());
}

TEST(MeshTopology, MakePartDropsAndCountsDegenerateTriangles) {
  TriangleMesh m = cube();
  m.positionsWorld.emplace_back(0.0f, 0.0f, 0.0f);  // 8: same place as vertex 0
  m.triangles.emplace_back(0, 0, 1);                // repeated index
  m.triangles.emplace_back(0, 8, 1);                // coincident positions
  m.triangles.emplace_back(0, 1, 1);                // repeated index
  const Part part = makePart("cube", glm::vec4(1.0f), m);
  EXPECT_EQ(part.degenerateTrianglesDropped, 3u);
  EXPECT_EQ(part.mesh.triangles.size(), 12u);
  EXPECT_TRUE(part.topology.closed());
}

}  // namespace
}  // namespace voxhap
