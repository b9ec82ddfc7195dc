#include "haptics/voxel/voxelizer.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "haptics/core/error.h"
#include "haptics/geometry/mesh_builder.h"

namespace voxhap {
namespace {

constexpr double kSide = 0.010;  // m
constexpr double kVoxel = 0.0005;

/// A cube of side kSide whose faces cut through voxels (not on voxel boundaries).
TriangleMesh offsetCube() {
  TriangleMesh m;
  appendBox(m, glm::translate(glm::dmat4(1.0), glm::dvec3(0.123 * kVoxel + kSide / 2)),
            glm::dvec3(kSide / 2));
  return m;
}

VoxelizedObject voxelizeOne(const TriangleMesh& mesh, double voxelSizeM, int threads = 0, int bits = 4) {
  const TriangleMesh* meshes[] = {&mesh};
  const MeshFeatures features[] = {extractFeatures(mesh, voxelSizeM)};
  VoxelizeOptions options;
  options.voxelSizeM = voxelSizeM;
  options.encoding = VoxelEncoding::forBits(bits);
  options.threads = threads;
  return voxelize(meshes, features, options);
}

/// Index range [first, last] of the voxels a slab [lo, hi] along one axis overlaps.
std::pair<int, int> voxelRange(const VoxelGrid& grid, int axis, double lo, double hi) {
  return {static_cast<int>(std::floor((lo - grid.originLocal[axis]) / grid.voxelSizeM)),
          static_cast<int>(std::floor((hi - grid.originLocal[axis]) / grid.voxelSizeM))};
}

TEST(Voxelizer, CubeSurfaceAndInteriorCountsAreExact) {
  const VoxelizedObject v = voxelizeOne(offsetCube(), kVoxel);
  // every voxel in [first, last]³ overlaps the solid cube; the outer layer holds its faces
  const double lo = 0.123 * kVoxel;
  const auto [first, last] = voxelRange(v.voxmap.grid(), 0, lo, lo + kSide);
  const std::uint64_t n = static_cast<std::uint64_t>(last - first + 1);
  EXPECT_EQ(v.stats.surfaceVoxels, n * n * n - (n - 2) * (n - 2) * (n - 2));
  EXPECT_EQ(v.stats.interiorVoxels, (n - 2) * (n - 2) * (n - 2));
  EXPECT_EQ(v.stats.voteDisagreements, 0u);
}

TEST(Voxelizer, DistanceFieldIsTheChessboardDistanceFromTheSurface) {
  const VoxelizedObject v = voxelizeOne(offsetCube(), kVoxel);
  const VoxelGrid& g = v.voxmap.grid();
  const double lo = 0.123 * kVoxel;
  const auto [first, last] = voxelRange(g, 0, lo, lo + kSide);
  const int middle = (first + last) / 2;
  // walking out of the +x face along x: surface, then 1 … 8, then far
  EXPECT_EQ(v.voxmap.value({last, middle, middle}, Field::Surface), kValueFeature);
  EXPECT_EQ(v.voxmap.value({last - 1, middle, middle}, Field::Surface), kValueInterior);
  for (int d = 1; d <= 8; ++d) {
    EXPECT_EQ(v.voxmap.value({last + d, middle, middle}, Field::Surface), distanceValue(d)) << d;
  }
  EXPECT_EQ(v.voxmap.value({last + 9, middle, middle}, Field::Surface), kValueFar);
  // diagonally off a corner the chessboard distance is the largest axis offset
  EXPECT_EQ(v.voxmap.value({last + 3, last + 5, last + 1}, Field::Surface), distanceValue(5));
  EXPECT_EQ(v.voxmap.value({first - 2, first - 2, first - 2}, Field::Surface), distanceValue(2));
}

TEST(Voxelizer, EdgeAndVertexFieldsMeasureFromTheCubesEdgesAndCorners) {
  const VoxelizedObject v = voxelizeOne(offsetCube(), kVoxel);
  const VoxelGrid& g = v.voxmap.grid();
  const double lo = 0.123 * kVoxel;
  const auto [first, last] = voxelRange(g, 0, lo, lo + kSide);
  const int middle = (first + last) / 2;
  // the middle of a face is more than 8 voxels from every edge and corner
  ASSERT_GT(middle - first, 9);
  EXPECT_EQ(v.voxmap.value({last, middle, middle}, Field::Edge), kValueFar);
  EXPECT_EQ(v.voxmap.value({last, middle, middle}, Field::Vertex), kValueFar);
  // on an edge of the cube, away from the corners
  EXPECT_EQ(v.voxmap.value({last, last, middle}, Field::Edge), kValueFeature);
  EXPECT_EQ(v.voxmap.value({last, last, middle}, Field::Vertex), kValueFar);
  EXPECT_EQ(v.voxmap.value({last + 2, last, middle}, Field::Edge), distanceValue(2));
  // at a corner, and 3 voxels from it
  EXPECT_EQ(v.voxmap.value({last, last, last}, Field::Vertex), kValueFeature);
  EXPECT_EQ(v.voxmap.value({last - 3, last, last}, Field::Vertex), distanceValue(3));
  EXPECT_EQ(v.stats.vertexVoxels, 8u);
}

TEST(Voxelizer, SphereVoxelsAgreeWithTheAnalyticSphere) {
  constexpr double r = 0.025;
  constexpr double s = 0.001;
  TriangleMesh sphere;
  appendGeodesicSphere(sphere, glm::dmat4(1.0), r, 5);
  const VoxelizedObject v = voxelizeOne(sphere, s);
  const VoxelGrid& g = v.voxmap.grid();
  // the polyhedron lies between its inscribed radius and r; allow half a voxel diagonal
  const double inscribed = r * 0.998;
  const double halfDiagonal = s * std::sqrt(3.0) / 2.0;
  int checked = 0;
  for (int z = 0; z < g.dimsVoxels().z; ++z) {
    for (int y = 0; y < g.dimsVoxels().y; ++y) {
      for (int x = 0; x < g.dimsVoxels().x; ++x) {
        const double d = glm::length(g.voxelCentre({x, y, z}));
        const std::uint8_t value = v.voxmap.value({x, y, z}, Field::Surface);
        if (d < inscribed - halfDiagonal) {
          ASSERT_EQ(value, kValueInterior) << x << " " << y << " " << z;
          ++checked;
        } else if (d > r + halfDiagonal) {
          ASSERT_NE(value, kValueInterior);
          ASSERT_NE(value, kValueFeature);
          ++checked;
        }
      }
    }
  }
  EXPECT_GT(checked, 50000);
  // volume: interior plus half the surface layer, against 4/3 π r³
  const double volume =
      (static_cast<double>(v.stats.interiorVoxels) + 0.5 * static_cast<double>(v.stats.surfaceVoxels)) * s *
      s * s;
  EXPECT_NEAR(volume, 4.0 / 3.0 * M_PI * r * r * r, 0.02 * 4.0 / 3.0 * M_PI * r * r * r);
}

TEST(Voxelizer, SameVoxmapWhateverTheThreadCount) {
  TriangleMesh sphere;
  appendGeodesicSphere(sphere, glm::dmat4(1.0), 0.025, 4);
  const VoxelizedObject one = voxelizeOne(sphere, 0.0007, 1);
  const VoxelizedObject two = voxelizeOne(sphere, 0.0007, 2);
  ASSERT_EQ(one.voxmap.grid().dimsHyper, two.voxmap.grid().dimsHyper);
  EXPECT_EQ(one.voxmap.memoryBytes(), two.voxmap.memoryBytes());
  const glm::ivec3 d = one.voxmap.grid().dimsVoxels();
  for (int z = 0; z < d.z; ++z) {
    for (int y = 0; y < d.y; ++y) {
      for (int x = 0; x < d.x; ++x) ASSERT_EQ(one.voxmap.word({x, y, z}), two.voxmap.word({x, y, z}));
    }
  }
  EXPECT_TRUE(std::ranges::equal(one.voxmap.chunkDistances(), two.voxmap.chunkDistances()));
}

TEST(Voxelizer, EveryBitWidthGivesTheSameSurfaceAndInterior) {
  const TriangleMesh cube = offsetCube();
  const VoxelizedObject four = voxelizeOne(cube, kVoxel, 0, 4);
  for (int bits : {2, 8}) {
    const VoxelizedObject other = voxelizeOne(cube, kVoxel, 0, bits);
    EXPECT_EQ(other.stats.surfaceVoxels, four.stats.surfaceVoxels) << bits;
    EXPECT_EQ(other.stats.interiorVoxels, four.stats.interiorVoxels) << bits;
  }
  // 2-bit fields reach one voxel only
  const VoxelizedObject two = voxelizeOne(cube, kVoxel, 0, 2);
  EXPECT_EQ(two.voxmap.encoding().rangeVoxels, 1);
}

TEST(Voxelizer, SmallHoleIsOutvotedAndReported) {
  TriangleMesh sphere;
  appendGeodesicSphere(sphere, glm::dmat4(1.0), 0.025, 4);
  sphere.triangles.erase(sphere.triangles.begin() + 100);  // a hole about 2 mm across
  const VoxelizedObject v = voxelizeOne(sphere, 0.001);
  EXPECT_EQ(v.voxmap.value(v.voxmap.grid().voxelOf({0.0, 0.0, 0.0}), Field::Surface), kValueInterior);
  const double volume = static_cast<double>(v.stats.interiorVoxels) * 1e-9;
  EXPECT_GT(volume, 0.9 * 4.0 / 3.0 * M_PI * 0.025 * 0.025 * 0.025);
}

TEST(Voxelizer, RefusesBadVoxelSizesBeforeAllocating) {
  const TriangleMesh cube = offsetCube();
  const TriangleMesh* meshes[] = {&cube};
  VoxelizeOptions options;
  for (double bad : {0.0, -1.0, std::nan("")}) {
    options.voxelSizeM = bad;
    EXPECT_THROW(voxelize(meshes, {}, options), Error) << bad;
  }
  options.voxelSizeM = 1e-7;
  options.memoryBudgetBytes = std::uint64_t{1} << 30;
  try {
    voxelize(meshes, {}, options);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("would need more than"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace voxhap
