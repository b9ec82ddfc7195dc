#include "haptics/pointshell/pointshell.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "haptics/core/error.h"
#include "haptics/geometry/mesh_builder.h"
#include "haptics/geometry/quasi_planar.h"
#include "haptics/voxel/tree_shape.h"

namespace voxhap {
namespace {

Pointshell shellOf(const TriangleMesh& mesh, double spacingM, double displacementM = 0.0, int threads = 0) {
  const TriangleMesh* meshes[] = {&mesh};
  const MeshFeatures features[] = {extractFeatures(mesh, spacingM)};
  PointshellOptions options;
  options.pointSpacingM = spacingM;
  options.displacementM = displacementM;
  options.threads = threads;
  return buildPointshell(meshes, features, options);
}

TriangleMesh sphere(double radiusM) {
  TriangleMesh m;
  appendGeodesicSphere(m, glm::dmat4(1.0), radiusM, 5);
  return m;
}

TEST(Pointshell, SphereNormalsAreUnitAndPointOutward) {
  const Pointshell s = shellOf(sphere(0.01), 0.0005);
  ASSERT_GT(s.size(), 1000u);
  for (std::size_t i = 0; i < s.size(); ++i) {
    const glm::dvec3 p(s.positionsLocal[i]);
    const glm::dvec3 n(s.normalsLocal[i]);
    ASSERT_NEAR(glm::length(n), 1.0, 1e-5);
    // outward: within a few degrees of the radial direction (facets are ~1 mm)
    ASSERT_GT(glm::dot(n, glm::normalize(p)), 0.98) << i;
    // a surface voxel's centre lies within half a voxel diagonal of the surface
    ASSERT_LT(std::abs(glm::length(p) - 0.01), 0.0005 * std::sqrt(3.0) / 2 + 1e-4) << i;
  }
}

TEST(Pointshell, CubeCornersAreVertexPointsWithDiagonalNormals) {
  TriangleMesh cube;
  appendBox(cube, glm::translate(glm::dmat4(1.0), glm::dvec3(0.00013, 0.00021, 0.00017)), glm::dvec3(0.005));
  const Pointshell s = shellOf(cube, 0.0005);
  EXPECT_EQ(s.count(PointFeature::Vertex), 8u);
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s.features[i] != PointFeature::Vertex) continue;
    const glm::dvec3 n(s.normalsLocal[i]);
    EXPECT_NEAR(std::abs(n.x), 1.0 / std::sqrt(3.0), 1e-6);
    EXPECT_NEAR(std::abs(n.y), 1.0 / std::sqrt(3.0), 1e-6);
    EXPECT_NEAR(std::abs(n.z), 1.0 / std::sqrt(3.0), 1e-6);
  }
  // 12 edges of 20 voxels, less the corners, give the edge points
  EXPECT_GE(s.count(PointFeature::Edge), 12u * 18u);
}

TEST(Pointshell, PointsOfAChunkAreContiguousAndCentroidsAreTheirMeans) {
  const Pointshell s = shellOf(sphere(0.01), 0.0005);
  ASSERT_EQ(s.chunkBegin.size(), s.chunkCount() + 1);
  EXPECT_EQ(s.chunkBegin.back(), s.size());
  const double chunkM = 0.0005 * kChunkEdgeVoxels;
  for (std::size_t c = 0; c < s.chunkCount(); ++c) {
    glm::dvec3 sum(0.0);
    for (std::uint32_t i = s.chunkBegin[c]; i < s.chunkBegin[c + 1]; ++i) {
      sum += glm::dvec3(s.positionsLocal[i]);
      // every point of the chunk lies within one chunk of its centroid
      EXPECT_LT(glm::length(glm::dvec3(s.positionsLocal[i]) - glm::dvec3(s.chunkCentroidsLocal[c])),
                chunkM * std::sqrt(3.0));
    }
    const double n = s.chunkBegin[c + 1] - s.chunkBegin[c];
    EXPECT_LT(glm::length(sum / n - glm::dvec3(s.chunkCentroidsLocal[c])), 1e-6);
  }
}

TEST(Pointshell, DisplacementMovesEveryPointAlongItsNormal) {
  const Pointshell plain = shellOf(sphere(0.01), 0.0005);
  const Pointshell inward = shellOf(sphere(0.01), 0.0005, -0.00025);
  ASSERT_EQ(plain.size(), inward.size());
  for (std::size_t i = 0; i < plain.size(); ++i) {
    const glm::dvec3 moved = glm::dvec3(inward.positionsLocal[i]) - glm::dvec3(plain.positionsLocal[i]);
    ASSERT_NEAR(glm::dot(moved, glm::dvec3(plain.normalsLocal[i])), -0.00025, 1e-7);
  }
}

TEST(Pointshell, SameShellWhateverTheThreadCount) {
  const Pointshell one = shellOf(sphere(0.01), 0.0005, 0.0, 1);
  const Pointshell two = shellOf(sphere(0.01), 0.0005, 0.0, 2);
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t i = 0; i < one.size(); ++i) {
    ASSERT_EQ(one.positionsLocal[i], two.positionsLocal[i]);
    ASSERT_EQ(one.normalsLocal[i], two.normalsLocal[i]);
    ASSERT_EQ(one.features[i], two.features[i]);
  }
}

TEST(Pointshell, FreeLayerLiesOutsideAtItsDistanceWithOutwardNormals) {
  constexpr double s = 0.0005;
  constexpr int layer = 3;
  TriangleMesh cube;
  appendBox(cube, glm::translate(glm::dmat4(1.0), glm::dvec3(0.00013, 0.00021, 0.00017)), glm::dvec3(0.005));
  const TriangleMesh* meshes[] = {&cube};
  const MeshFeatures features[] = {extractFeatures(cube, s)};
  PointshellOptions options;
  options.pointSpacingM = s;
  options.freeLayer = layer;
  const Pointshell shell = buildPointshell(meshes, features, options);
  const Pointshell surface = shellOf(cube, s);
  EXPECT_GT(shell.size(), surface.size());
  const glm::dvec3 centre(0.00013, 0.00021, 0.00017);
  for (std::size_t i = 0; i < shell.size(); ++i) {
    const glm::dvec3 p = glm::dvec3(shell.positionsLocal[i]) - centre;
    // exact distance to the cube's surface from outside
    const glm::dvec3 out =
        glm::sign(p) * glm::max(glm::abs(p) - 0.005, 0.0);  // from the nearest surface point
    const double distance = glm::length(out);
    ASSERT_GT(distance, (layer - 0.5) * s) << i;
    ASSERT_LT(distance, std::sqrt(3.0) * (layer + 1.5) * s) << i;
    ASSERT_NEAR(glm::dot(glm::dvec3(shell.normalsLocal[i]), out / distance), 1.0, 1e-5) << i;
    // beyond a corner the nearest surface point is the corner, whose voxel is a vertex voxel
    if ((out.x != 0.0) + (out.y != 0.0) + (out.z != 0.0) == 3) {
      ASSERT_EQ(shell.features[i], PointFeature::Vertex) << i;
    }
  }
  EXPECT_GT(shell.count(PointFeature::Vertex), 8u);
  options.freeLayer = kMaxFreeLayer + 1;
  EXPECT_THROW(buildPointshell(meshes, features, options), Error);
}

// A square rod turned 45° about its axis (y), as two crossed rods meet edge on edge: on
// the surface, the points of its edge voxels lie on its edges, a spacing apart along them
// wherever the lattice falls, so that another part's edge cannot pass between them.
TEST(Pointshell, OnTheSurfaceEdgeVoxelsPointsLieOnTheEdgesASpacingApart) {
  constexpr double kSpacingM = 0.0005;
  constexpr double kHalfM = 0.002;
  const glm::dvec3 axis(0.00037, 0.0, 0.00011);  // off the lattice
  TriangleMesh rod;
  appendBox(rod, glm::rotate(glm::translate(glm::dmat4(1.0), axis), M_PI / 4, glm::dvec3(0.0, 1.0, 0.0)),
            glm::dvec3(kHalfM, 0.01, kHalfM));
  const TriangleMesh* meshes[] = {&rod};
  const MeshFeatures features[] = {extractFeatures(rod, kSpacingM)};
  PointshellOptions options;
  options.pointSpacingM = kSpacingM;
  options.onSurface = true;
  const Pointshell s = buildPointshell(meshes, features, options);
  // the four long edges, in the x–z plane, a diagonal of the square from the axis
  const double r = kHalfM * std::sqrt(2.0);
  const glm::dvec2 edges[] = {
      {axis.x + r, axis.z}, {axis.x - r, axis.z}, {axis.x, axis.z + r}, {axis.x, axis.z - r}};
  for (const glm::dvec2& edge : edges) {
    std::vector<double> along;
    for (std::size_t i = 0; i < s.size(); ++i) {
      const glm::dvec3 p(s.positionsLocal[i]);
      if (glm::length(glm::dvec2(p.x, p.z) - edge) < 1e-7 && std::abs(p.y) < 0.009) along.push_back(p.y);
    }
    std::sort(along.begin(), along.end());
    ASSERT_GT(along.size(), 30u);
    for (std::size_t k = 1; k < along.size(); ++k) EXPECT_LE(along[k] - along[k - 1], 1.001 * kSpacingM);
  }
  for (std::size_t i = 0; i < s.size(); ++i) {
    const glm::dvec3 p(s.positionsLocal[i]);
    if (s.features[i] == PointFeature::Surface || std::abs(p.y) > 0.0095) continue;
    double nearestM = 1.0;
    for (const glm::dvec2& edge : edges)
      nearestM = std::min(nearestM, glm::length(glm::dvec2(p.x, p.z) - edge));
    EXPECT_LT(nearestM, 1e-7) << "an edge voxel's point off the long edges, away from the ends";
  }
}

TEST(Pointshell, RejectsBadSpacing) {
  const TriangleMesh s = sphere(0.01);
  const TriangleMesh* meshes[] = {&s};
  for (double bad : {0.0, -0.001, std::nan("")}) {
    PointshellOptions options;
    options.pointSpacingM = bad;
    EXPECT_THROW(buildPointshell(meshes, {}, options), Error) << bad;
  }
}

}  // namespace
}  // namespace voxhap
