#include "haptics/voxel/voxmap.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "haptics/geometry/mesh_builder.h"
#include "haptics/voxel/voxelizer.h"

namespace voxhap {
namespace {

constexpr double kVoxel = 0.001;  // m
constexpr double kSide = 0.012;   // m

/// Voxel index range [first, last] that the slab [lo, lo + kSide] overlaps along `axis`.
std::pair<int, int> cubeVoxels(const VoxelGrid& grid, int axis, double lo) {
  return {static_cast<int>(std::floor((lo - grid.originLocal[axis]) / grid.voxelSizeM)),
          static_cast<int>(std::floor((lo + kSide - grid.originLocal[axis]) / grid.voxelSizeM))};
}

int floorDiv(int a, int b) {
  return a >= 0 ? a / b : -((-a + b - 1) / b);
}

/// Two cubes 0.3 m apart along x (so that the grid holds chunks far from both), faces
/// cutting through voxels.
struct TwoCubes {
  glm::dvec3 corners[2] = {glm::dvec3(0.137 * kVoxel), glm::dvec3(0.3 + 0.411 * kVoxel, 0.0213, -0.0137)};
  VoxelizedObject voxelized;

  TwoCubes() {
    TriangleMesh mesh;
    for (const glm::dvec3& c : corners) {
      appendBox(mesh, glm::translate(glm::dmat4(1.0), c + kSide / 2), glm::dvec3(kSide / 2));
    }
    const TriangleMesh* meshes[] = {&mesh};
    const MeshFeatures features[] = {extractFeatures(mesh, kVoxel)};
    VoxelizeOptions options;
    options.voxelSizeM = kVoxel;
    voxelized = voxelize(meshes, features, options);
  }

  /// Inclusive chunk box of the chunks holding a non-far voxel of cube `i`: its surface
  /// voxels grown by the field's range on every side (the chessboard ball is a cube).
  std::pair<glm::ivec3, glm::ivec3> bearingChunks(int i) const {
    const VoxelGrid& grid = voxelized.voxmap.grid();
    const int range = voxelized.voxmap.encoding().rangeVoxels;
    glm::ivec3 lo;
    glm::ivec3 hi;
    for (int axis = 0; axis < 3; ++axis) {
      const auto [first, last] = cubeVoxels(grid, axis, corners[i][axis]);
      lo[axis] = floorDiv(first - range, kChunkEdgeVoxels);
      hi[axis] = floorDiv(last + range, kChunkEdgeVoxels);
    }
    return {lo, hi};
  }
};

int chessboardToBox(const glm::ivec3& p, const glm::ivec3& lo, const glm::ivec3& hi) {
  const glm::ivec3 d = glm::max(glm::max(lo - p, p - hi), glm::ivec3(0));
  return std::max({d.x, d.y, d.z});
}

TEST(Voxmap, ChunkDistanceIsTheChessboardDistanceToTheCubesBearingChunks) {
  const TwoCubes cubes;
  const Voxmap& voxmap = cubes.voxelized.voxmap;
  const glm::ivec3 dims = voxmap.grid().dimsChunks();
  ASSERT_GT(dims.x, 40);  // the cubes are far apart in chunks
  const auto [lo0, hi0] = cubes.bearingChunks(0);
  const auto [lo1, hi1] = cubes.bearingChunks(1);
  int largest = 0;
  for (int z = 0; z < dims.z; ++z) {
    for (int y = 0; y < dims.y; ++y) {
      for (int x = 0; x < dims.x; ++x) {
        const glm::ivec3 c(x, y, z);
        const int expected = std::min(chessboardToBox(c, lo0, hi0), chessboardToBox(c, lo1, hi1));
        ASSERT_EQ(voxmap.chunkDistance(c), expected) << x << " " << y << " " << z;
        largest = std::max(largest, expected);
      }
    }
  }
  EXPECT_GT(largest, 15);
}

TEST(Voxmap, ChunkDistanceOutsideTheGridIsTheDistanceToTheGridAtLeastOne) {
  const TwoCubes cubes;
  const Voxmap& voxmap = cubes.voxelized.voxmap;
  const glm::ivec3 dims = voxmap.grid().dimsChunks();
  EXPECT_EQ(voxmap.chunkDistance({-1, 0, 0}), 1);
  EXPECT_EQ(voxmap.chunkDistance({-3, 2, 1}), 3);
  EXPECT_EQ(voxmap.chunkDistance({dims.x + 6, -2, dims.z}), 7);
  EXPECT_EQ(voxmap.chunkDistance({0, 0, dims.z + 1000}), 255);
  EXPECT_EQ(voxmap.chunkDistance({-100000, 100000, 0}), 255);
}

TEST(Voxmap, PointsByFeatureFollowTheCubesCornersAndEdges) {
  const TwoCubes cubes;
  const VoxelizeStats& stats = cubes.voxelized.stats;
  const auto [first, last] = cubeVoxels(cubes.voxelized.voxmap.grid(), 0, cubes.corners[0].x);
  const std::uint64_t n = static_cast<std::uint64_t>(last - first + 1);
  // per cube: 8 corner voxels, 12 edges of n voxels sharing the corners
  EXPECT_EQ(stats.vertexPoints, 2 * 8u);
  EXPECT_EQ(stats.edgePoints, 2 * 12 * (n - 2));
  EXPECT_EQ(stats.surfacePoints, 2 * 6 * (n - 2) * (n - 2));
  EXPECT_EQ(stats.vertexPoints + stats.edgePoints + stats.surfacePoints, stats.surfaceVoxels);
}

TEST(Voxmap, WordsAroundAVoxelAreItsAndItsSixNeighboursWordsInsideChunksAcrossThemAndOutsideTheGrid) {
  const TwoCubes cubes;
  const Voxmap& voxmap = cubes.voxelized.voxmap;
  const glm::ivec3 dims = voxmap.grid().dimsVoxels();
  // every voxel of a box around the first cube's corner, past the grid's low faces, and of
  // the grid's far corner: voxels inside chunks, on chunk faces, in uniform chunks, outside
  std::size_t differentNeighbours = 0;
  auto check = [&](const glm::ivec3& lo, const glm::ivec3& hi) {
    for (int z = lo.z; z <= hi.z; ++z)
      for (int y = lo.y; y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x) {
          const glm::ivec3 v(x, y, z);
          const std::array<VoxelWord, 7> around = voxmap.wordsAround(v);
          for (std::size_t n = 0; n < around.size(); ++n) {
            ASSERT_EQ(around[n], voxmap.word(v + Voxmap::kAroundSteps[n]))
                << x << " " << y << " " << z << " " << n;
          }
          differentNeighbours += around[1] != around[2] ? 1 : 0;
        }
  };
  check(glm::ivec3(-2), glm::ivec3(20));
  check(dims - 3, dims + 1);
  EXPECT_GT(differentNeighbours, 500u);  // the cube's faces and the field around them
}

TEST(Voxmap, ValidateRejectsIndicesBeyondTheArrays) {
  const TwoCubes cubes;
  const Voxmap& v = cubes.voxelized.voxmap;
  EXPECT_EQ(Voxmap::validate(v.grid(), v.encoding(), v.hyperEntries(), v.chunkEntries(),
                             v.voxelBytes().size(), v.chunkDistances().size()),
            "");
  std::vector<std::uint32_t> chunks(v.chunkEntries().begin(), v.chunkEntries().end());
  const auto mixed =
      std::find_if(chunks.begin(), chunks.end(), [](std::uint32_t e) { return !(e & Voxmap::kUniform); });
  ASSERT_NE(mixed, chunks.end());
  *mixed = static_cast<std::uint32_t>(v.mixedChunkCount());
  EXPECT_NE(Voxmap::validate(v.grid(), v.encoding(), v.hyperEntries(), chunks, v.voxelBytes().size(),
                             v.chunkDistances().size()),
            "");
  EXPECT_NE(Voxmap::validate(v.grid(), v.encoding(), v.hyperEntries(), v.chunkEntries(),
                             v.voxelBytes().size() - 1, v.chunkDistances().size()),
            "");
  EXPECT_NE(Voxmap::validate(v.grid(), v.encoding(), v.hyperEntries(), v.chunkEntries(),
                             v.voxelBytes().size(), v.chunkDistances().size() + 1),
            "");
}

}  // namespace
}  // namespace voxhap
