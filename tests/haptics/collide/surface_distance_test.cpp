// The distance at a point from its voxel's and the surrounding voxels' surface planes,
// against exact distances: around a box's edges and corners (convex) it is nearer the
// truth than the voxel's own plane and never above it; in a socket's cavity (concave) it
// is never above what the own plane gives.
#include "haptics/collide/surface_distance.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <random>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "haptics/geometry/embree_scene.h"
#include "haptics/geometry/mesh_builder.h"
#include "haptics/voxel/voxelizer.h"

namespace voxhap {
namespace {

constexpr double kVoxelM = 0.001;
/// The planes' quantization of distance and direction over 0.87 voxel, m.
constexpr double kQuantizationM = 2e-3 * kVoxelM;

Voxmap voxelizeWithPlanes(const TriangleMesh& mesh) {
  const TriangleMesh* meshes[] = {&mesh};
  VoxelizeOptions options;
  options.voxelSizeM = kVoxelM;
  options.buildFeatureFields = false;
  options.surfacePlanes = true;
  return voxelize(meshes, {}, options).voxmap;
}

/// The own plane's distance at `p` and surfaceDistance's, for a point of a voxel with a plane.
struct Estimates {
  double ownM = 0.0;
  double nearM = 0.0;
};

std::optional<Estimates> estimatesAt(const Voxmap& voxmap, const glm::dvec3& p) {
  const glm::ivec3 ijk = voxmap.grid().voxelOf(p);
  const PlaneWithSides plane = voxmap.surfacePlaneWithSides(ijk);
  if (!plane.plane) return std::nullopt;
  const OwnPlaneReading own = readOwnPlane(voxmap.grid(), ijk, plane, p);
  return Estimates{own.distanceM, surfaceDistance(voxmap, ijk, own).distanceM};
}

TEST(SurfaceDistance, AroundABoxsEdgesAndCornersIsNearerTheTruthThanTheVoxelsOwnPlaneAndNeverAboveIt) {
  const glm::dvec3 lo(0.00313, 0.00271, 0.00292);
  const glm::dvec3 half(0.006, 0.004, 0.005);
  TriangleMesh box;
  appendBox(box, glm::translate(glm::dmat4(1.0), lo + half), half);
  const Voxmap voxmap = voxelizeWithPlanes(box);
  const glm::dvec3 hi = lo + 2.0 * half;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double ownWorstM = 0.0;
  double nearWorstM = 0.0;
  int checked = 0;
  for (int i = 0; i < 20000; ++i) {
    // outside, within 1.5 voxels of the box, beyond its faces on at least two axes: near
    // an edge or a corner
    glm::dvec3 p;
    for (int k = 0; k < 3; ++k) p[k] = lo[k] - 1.5 * kVoxelM + unit(random) * (hi[k] - lo[k] + 3.0 * kVoxelM);
    const glm::dvec3 outside = glm::max(glm::max(lo - p, p - hi), glm::dvec3(0.0));
    const int beyond = (outside.x > 0.0) + (outside.y > 0.0) + (outside.z > 0.0);
    const double exactM = glm::length(outside);
    if (beyond < 2 || exactM > 1.5 * kVoxelM) continue;
    const auto e = estimatesAt(voxmap, p);
    if (!e) continue;
    ++checked;
    EXPECT_LE(e->nearM, exactM + kQuantizationM);
    EXPECT_GE(e->nearM, e->ownM);  // exactly: tangentPlaneWrench skips points by the own plane
    ownWorstM = std::max(ownWorstM, exactM - e->ownM);
    nearWorstM = std::max(nearWorstM, exactM - e->nearM);
  }
  std::printf(
      "near a box's edges and corners: own plane down to %.3f voxel under the truth, with the "
      "neighbours' %.3f voxel (%d points)\n",
      ownWorstM / kVoxelM, nearWorstM / kVoxelM, checked);
  EXPECT_GT(checked, 2000);
  EXPECT_GT(ownWorstM, 0.3 * kVoxelM);  // what the neighbours' planes are for
  EXPECT_LT(nearWorstM, 0.5 * ownWorstM);
}

TEST(SurfaceDistance, InASocketsCavityIsNeverAboveWhatTheOwnPlaneGives) {
  constexpr double kRadiusM = 0.012;
  TriangleMesh socket;
  appendSphericalSocket(socket, glm::translate(glm::dmat4(1.0), glm::dvec3(0.02)),
                        SocketSpec{kRadiusM, 0.02, 0.018, 0.6}, 64, 15);
  const Voxmap voxmap = voxelizeWithPlanes(socket);
  const TriangleMesh* meshes[] = {&socket};
  const EmbreeScene exact(meshes);
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int checked = 0;
  for (int i = 0; i < 20000; ++i) {
    // in the cavity within 1.5 voxels of its wall (of the sphere its vertices lie on), below its rim
    const glm::dvec3 direction =
        glm::normalize(glm::dvec3(unit(random), unit(random), -std::abs(unit(random))));
    const double depthM = 1.5 * kVoxelM * (0.5 + 0.5 * unit(random));
    const glm::dvec3 p = glm::dvec3(0.02) + direction * (kRadiusM - depthM);
    const auto e = estimatesAt(voxmap, p);
    const auto q = exact.closestPoint(p, 4.0 * kVoxelM);
    if (!e || !q) continue;
    ++checked;
    EXPECT_GE(e->nearM, e->ownM);
    EXPECT_LE(e->nearM, std::max(e->ownM, q->distanceM) + kQuantizationM)
        << e->ownM << " exact " << q->distanceM << " at " << p.x << " " << p.y << " " << p.z;
  }
  EXPECT_GT(checked, 10000);
}

}  // namespace
}  // namespace voxhap
