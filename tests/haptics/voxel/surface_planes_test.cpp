#include "haptics/voxel/surface_planes.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <functional>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "haptics/geometry/mesh_builder.h"
#include "haptics/voxel/voxelizer.h"

namespace voxhap {
namespace {

constexpr double kVoxelM = 0.0005;

Voxmap voxelizeWithPlanes(const TriangleMesh& mesh, int threads = 0) {
  const TriangleMesh* meshes[] = {&mesh};
  VoxelizeOptions options;
  options.voxelSizeM = kVoxelM;
  options.buildFeatureFields = false;
  options.surfacePlanes = true;
  options.threads = threads;
  return voxelize(meshes, {}, options).voxmap;
}

/// Every voxel of the grid, with its centre.
template <typename Visit>
void forEachVoxel(const Voxmap& voxmap, Visit&& visit) {
  const glm::ivec3 d = voxmap.grid().dimsVoxels();
  for (int z = 0; z < d.z; ++z)
    for (int y = 0; y < d.y; ++y)
      for (int x = 0; x < d.x; ++x) visit(glm::ivec3(x, y, z), voxmap.grid().voxelCentre({x, y, z}));
}

TEST(SurfacePlane, KeepsDistanceAndDirectionToTheirQuantization) {
  const glm::dvec3 n = glm::normalize(glm::dvec3(0.3, -0.5, 0.8));
  const SurfacePlane plane = SurfacePlane::make(-1.2345, n);
  ASSERT_TRUE(plane.valid());
  EXPECT_NEAR(plane.distanceVoxels(), -1.2345, 0.5 / SurfacePlane::kDistanceStepsPerVoxel);
  EXPECT_NEAR(glm::length(plane.outwardUnit() - n), 0.0, 1e-4);
  EXPECT_NEAR(SurfacePlane::make(100.0, n).distanceVoxels(), 32.0, 0.01);  // clamped to what fits
  EXPECT_FALSE(SurfacePlane{}.valid());
}

TEST(SurfacePlanes, OfASphereGiveItsExactSignedDistanceNearItsSurface) {
  constexpr double kRadiusM = 0.004;
  const glm::dvec3 centre(0.0101, 0.0102, 0.0103);
  TriangleMesh sphere;
  appendGeodesicSphere(sphere, glm::translate(glm::dmat4(1.0), centre), kRadiusM, 5);
  const Voxmap voxmap = voxelizeWithPlanes(sphere);
  ASSERT_TRUE(voxmap.hasSurfacePlanes());
  int checked = 0;
  int band = 0;
  forEachVoxel(voxmap, [&](const glm::ivec3& ijk, const glm::dvec3& c) {
    const std::uint8_t value = voxmap.value(ijk, Field::Surface);
    const SurfacePlane* plane = voxmap.surfacePlane(ijk);
    const bool inBand = value >= kValueInterior && value <= distanceValue(kSurfacePlaneLayers);
    band += inBand ? 1 : 0;
    // every voxel of the band within reach of the surface has a plane, and none outside it
    const double exactM = glm::length(c - centre) - kRadiusM;
    if (inBand && -exactM < 0.9 * kSurfacePlaneReachVoxels * kVoxelM) {
      ASSERT_NE(plane, nullptr) << int(value);
    }
    if (!inBand) {
      ASSERT_EQ(plane, nullptr);
    }
    if (!plane) return;
    // the tessellation lies within 0.01 mm of the sphere
    EXPECT_NEAR(plane->distanceVoxels() * kVoxelM, exactM, 1.2e-5) << ijk.x << " " << ijk.y << " " << ijk.z;
    EXPECT_GT(glm::dot(plane->outwardUnit(), glm::normalize(c - centre)), 0.995);
    // a point anywhere in the voxel: the plane gives its distance less than the truth
    // (the distance outside a convex body is convex), by at most the sphere's curvature
    // over the offset, |p − c|² / 2(R + φ), and the tessellation's (facets within 0.012 mm
    // of the sphere, turned by up to a few degrees from it: 0.025 mm at 0.35 mm off c)
    const glm::dvec3 p = c + glm::dvec3(0.43, -0.41, 0.37) * kVoxelM;
    const double planeM = plane->distanceVoxels() * kVoxelM + glm::dot(p - c, plane->outwardUnit());
    const double exactAtPM = glm::length(p - centre) - kRadiusM;
    if (exactM > 0.0) {
      EXPECT_LE(planeM, exactAtPM + 1.2e-5);
    }
    const double offsetM = glm::length(p - c);
    EXPECT_NEAR(planeM, exactAtPM,
                offsetM * offsetM / (2.0 * (kRadiusM + std::min(exactM, exactAtPM))) + 2.5e-5);
    ++checked;
  });
  EXPECT_GT(checked, 1000);
  // kept only where a voxel has one: a chunk of them per mixed chunk, not every voxel's
  EXPECT_EQ(voxmap.surfacePlanes().chunkCount(), voxmap.mixedChunkCount());
  EXPECT_LT(voxmap.surfacePlanes().planeCount(), voxmap.mixedChunkCount() * kVoxelsPerChunk / 2);
  EXPECT_GT(band, checked / 2);
}

TEST(SurfacePlanes, AtABoxEdgePointAcrossTheEdgeNotDiagonallyAsTheChessboardField) {
  TriangleMesh box;
  const glm::dvec3 lo(0.00313, 0.00271, 0.00292);
  const glm::dvec3 half(0.003, 0.002, 0.0025);
  appendBox(box, glm::translate(glm::dmat4(1.0), lo + half), half);
  const Voxmap voxmap = voxelizeWithPlanes(box);
  const glm::dvec3 hi = lo + 2.0 * half;
  // a voxel one and a half voxels beyond the top edge along x (y in the middle): its
  // nearest surface point is on the edge, and the plane points from it
  const glm::dvec3 probe(hi.x + 1.2 * kVoxelM, lo.y + half.y, hi.z + 0.7 * kVoxelM);
  const glm::ivec3 ijk = voxmap.grid().voxelOf(probe);
  const SurfacePlane* plane = voxmap.surfacePlane(ijk);
  ASSERT_NE(plane, nullptr);
  const glm::dvec3 c = voxmap.grid().voxelCentre(ijk);
  const glm::dvec3 fromEdge(c.x - hi.x, 0.0, c.z - hi.z);
  const glm::dvec3 expected = c.x > hi.x && c.z > hi.z
                                  ? glm::normalize(fromEdge)
                                  : (c.z > hi.z ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0));
  EXPECT_NEAR(glm::length(plane->outwardUnit() - expected), 0.0, 1e-4);
  const double expectedM =
      c.x > hi.x && c.z > hi.z ? glm::length(fromEdge) : std::max(c.x - hi.x, c.z - hi.z);
  EXPECT_NEAR(plane->distanceVoxels() * kVoxelM, expectedM, 1e-6);
  // inside, a voxel centre near the +x face is its distance to that face, negative
  const glm::ivec3 in = voxmap.grid().voxelOf(glm::dvec3(hi.x - 1.5 * kVoxelM, lo.y + half.y, lo.z + half.z));
  const SurfacePlane* inner = voxmap.surfacePlane(in);
  ASSERT_NE(inner, nullptr);
  EXPECT_NEAR(inner->distanceVoxels() * kVoxelM, voxmap.grid().voxelCentre(in).x - hi.x, 1e-6);
  EXPECT_NEAR(glm::length(inner->outwardUnit() - glm::dvec3(1, 0, 0)), 0.0, 1e-4);
}

TEST(SurfacePlanes, AreTheSameBitsWhateverTheThreadCount) {
  TriangleMesh sphere;
  appendGeodesicSphere(sphere, glm::translate(glm::dmat4(1.0), glm::dvec3(0.003)), 0.0025, 4);
  const Voxmap one = voxelizeWithPlanes(sphere, 1);
  const Voxmap two = voxelizeWithPlanes(sphere, 2);
  EXPECT_TRUE(one.surfacePlanes() == two.surfacePlanes());
  EXPECT_GT(one.surfacePlanes().planeCount(), 0u);
}

TEST(SurfacePlanes, BesideAVoxelAreItsNeighboursPlanesOnEitherSideWithinChunksAcrossThemAndOutsideTheGrid) {
  TriangleMesh sphere;
  appendGeodesicSphere(sphere, glm::translate(glm::dmat4(1.0), glm::dvec3(0.003)), 0.0025, 4);
  const Voxmap voxmap = voxelizeWithPlanes(sphere);
  const glm::ivec3 dims = voxmap.grid().dimsVoxels();
  std::size_t planesBeside = 0;
  // every voxel of the grid and a layer beyond it, every side: voxels inside chunks, on
  // chunk faces, in uniform chunks, outside
  for (int z = -1; z <= dims.z; ++z)
    for (int y = -1; y <= dims.y; ++y)
      for (int x = -1; x <= dims.x; ++x)
        for (int sides = 0; sides < 8; ++sides) {
          const glm::ivec3 v(x, y, z);
          const glm::ivec3 side(sides & 1 ? 1 : -1, sides & 2 ? 1 : -1, sides & 4 ? 1 : -1);
          const std::array<const SurfacePlane*, 3> beside = voxmap.surfacePlanesBeside(v, side);
          for (int axis = 0; axis < 3; ++axis) {
            glm::ivec3 neighbour = v;
            neighbour[axis] += side[axis];
            ASSERT_EQ(beside[static_cast<std::size_t>(axis)], voxmap.surfacePlane(neighbour))
                << x << " " << y << " " << z << " side " << sides << " axis " << axis;
            planesBeside += beside[static_cast<std::size_t>(axis)] ? 1 : 0;
          }
        }
  // each plane is beside 24 (voxel, side, axis) of these: two voxels an axis, four sides each
  EXPECT_EQ(planesBeside, 24 * voxmap.surfacePlanes().planeCount());
}

/// Of the face-neighbour pairs whose voxels both have planes, the share whose planes are
/// convex with each other; checks every plane's convex sides against convexWith and against
/// the neighbour's own sides on the way.
double convexShare(const Voxmap& voxmap, const std::function<bool(const glm::dvec3&)>& counted) {
  std::size_t pairs = 0;
  std::size_t convex = 0;
  forEachVoxel(voxmap, [&](const glm::ivec3& ijk, const glm::dvec3& c) {
    const PlaneWithSides own = voxmap.surfacePlaneWithSides(ijk);
    EXPECT_EQ(own.plane, voxmap.surfacePlane(ijk));
    if (!own.plane) return;
    for (int axis = 0; axis < 3; ++axis)
      for (const int side : {-1, 1}) {
        glm::ivec3 v = ijk;
        v[axis] += side;
        const PlaneWithSides beside = voxmap.surfacePlaneWithSides(v);
        const bool bit = (own.convexSides & SurfacePlane::sideBit(axis, side)) != 0;
        const bool expected = beside.plane && own.plane->convexWith(*beside.plane, axis, side);
        ASSERT_EQ(bit, expected) << ijk.x << " " << ijk.y << " " << ijk.z << " axis " << axis << " side "
                                 << side;
        if (!beside.plane) continue;
        ASSERT_EQ(bit, (beside.convexSides & SurfacePlane::sideBit(axis, -side)) != 0);
        if (!counted(c)) continue;
        ++pairs;
        convex += bit ? 1 : 0;
      }
  });
  EXPECT_GT(pairs, 1000u);
  return static_cast<double>(convex) / static_cast<double>(pairs);
}

TEST(SurfacePlanes, ConvexSidesAreTheNeighboursWhosePlanesAgreeWithConvexityMostAroundABallFewInASocket) {
  TriangleMesh sphere;
  appendGeodesicSphere(sphere, glm::translate(glm::dmat4(1.0), glm::dvec3(0.006)), 0.005, 5);
  // the signed distance of a ball is convex inside and out: its planes, but for their
  // quantization, agree with convexity
  const double ballShare = convexShare(voxelizeWithPlanes(sphere), [](const glm::dvec3&) { return true; });
  EXPECT_GT(ballShare, 0.9);
  // in a socket's cavity the distance is concave: hardly a pair agrees
  constexpr double kCavityRadiusM = 0.006;
  const glm::dvec3 centre(0.01);
  TriangleMesh socket;
  appendSphericalSocket(socket, glm::translate(glm::dmat4(1.0), centre),
                        SocketSpec{kCavityRadiusM, 0.01, 0.009, 0.6}, 64, 15);
  const double cavityShare = convexShare(voxelizeWithPlanes(socket), [&](const glm::dvec3& c) {
    return c.z < centre.z && glm::length(c - centre) < kCavityRadiusM;
  });
  EXPECT_LT(cavityShare, 0.1);
  std::printf("[ figures  ] convex face-neighbour pairs: %.3f around a ball, %.3f in a socket's cavity\n",
              ballShare, cavityShare);
}

}  // namespace
}  // namespace voxhap
