#include "haptics/voxel/chunk_footprint.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "haptics/geometry/mesh_builder.h"
#include "haptics/voxel/voxelizer.h"

namespace voxhap {
namespace {

constexpr double kVoxel = 0.001;
constexpr double kChunk = kVoxel * kChunkEdgeVoxels;

/// A grid of 8³ hyperchunks (64 chunks a side) with its corner at the origin.
VoxelGrid grid64() {
  VoxelGrid grid;
  grid.voxelSizeM = kVoxel;
  grid.dimsHyper = glm::ivec3(8);
  return grid;
}

/// The square [x0, x0 + side]² at height z, as n × n cells of two triangles each.
TriangleMesh square(double x0, double side, double z, int n) {
  TriangleMesh m;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      m.positionsWorld.emplace_back(x0 + side * i / n, x0 + side * j / n, z);
    }
  }
  auto at = [n](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      m.triangles.emplace_back(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      m.triangles.emplace_back(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  }
  return m;
}

ChunkFootprint footprintOf(const TriangleMesh& mesh, int reach = 1, std::uint64_t most = 1u << 30) {
  const TriangleMesh* meshes[] = {&mesh};
  return chunkFootprint(meshes, grid64(), reach, most);
}

TEST(ChunkFootprint, AFlatSquareCountsItsChunksOnceHoweverFinelyTessellated) {
  // from inside chunk 10 to inside chunk 19 along x and y, at mid-height of chunk layer 30
  const double x0 = 10.3 * kChunk;
  const double side = 9.4 * kChunk;
  const double z = 30.5 * kChunk;
  for (const int n : {1, 7, 300}) {
    const ChunkFootprint f = footprintOf(square(x0, side, z, n));
    EXPECT_TRUE(f.complete);
    EXPECT_EQ(f.surfaceChunks, 10u * 10u) << n;
    EXPECT_EQ(f.mixedChunks, 12u * 12u * 3u) << n;
  }
  EXPECT_EQ(footprintOf(square(x0, side, z, 7), 2).mixedChunks, 14u * 14u * 5u);
}

TEST(ChunkFootprint, ATiltedTriangleCountsTheSameWholeAsInPieces) {
  // a large triangle across the grid (quartered inside) against 16 pieces of it
  const glm::dvec3 a(1.2 * kChunk, 2.7 * kChunk, 3.1 * kChunk);
  const glm::dvec3 b(60.4 * kChunk, 9.3 * kChunk, 40.8 * kChunk);
  const glm::dvec3 c(20.1 * kChunk, 58.6 * kChunk, 61.7 * kChunk);
  TriangleMesh whole;
  whole.positionsWorld = {glm::vec3(a), glm::vec3(b), glm::vec3(c)};
  whole.triangles = {{0, 1, 2}};
  TriangleMesh pieces;
  constexpr int n = 4;
  auto p = [&](int i, int j) { return glm::vec3(a + (b - a) * (double(i) / n) + (c - a) * (double(j) / n)); };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i + j < n; ++i) {
      const auto base = static_cast<std::uint32_t>(pieces.positionsWorld.size());
      pieces.positionsWorld.insert(pieces.positionsWorld.end(), {p(i, j), p(i + 1, j), p(i, j + 1)});
      pieces.triangles.emplace_back(base, base + 1, base + 2);
      if (i + j + 1 < n) {
        pieces.positionsWorld.insert(pieces.positionsWorld.end(),
                                     {p(i + 1, j), p(i + 1, j + 1), p(i, j + 1)});
        pieces.triangles.emplace_back(base + 3, base + 4, base + 5);
      }
    }
  }
  const ChunkFootprint w = footprintOf(whole);
  const ChunkFootprint q = footprintOf(pieces);
  EXPECT_EQ(w.surfaceChunks, q.surfaceChunks);
  EXPECT_EQ(w.mixedChunks, q.mixedChunks);
  // a plane meets at most about 1.8 chunks per chunk face of area, and its edges some more
  const double areaChunks = 0.5 * glm::length(glm::cross(b - a, c - a)) / (kChunk * kChunk);
  EXPECT_GT(double(w.surfaceChunks), areaChunks);
  EXPECT_LT(double(w.surfaceChunks), 1.8 * areaChunks + 3.0 * 64.0);
}

TEST(ChunkFootprint, StopsAtTheLimitWithLowerBounds) {
  const ChunkFootprint f = footprintOf(square(10.3 * kChunk, 9.4 * kChunk, 30.5 * kChunk, 7), 1, 40);
  EXPECT_FALSE(f.complete);
  EXPECT_GT(f.surfaceChunks, 40u);
  EXPECT_LE(f.surfaceChunks, 100u);
  EXPECT_EQ(f.mixedChunks, f.surfaceChunks);
}

TEST(ChunkFootprint, HoldsEveryChunkAVoxelizationStoresAndItsEstimateItsMemory) {
  TriangleMesh sphere;
  appendGeodesicSphere(sphere, glm::translate(glm::dmat4(1.0), glm::dvec3(0.0031, -0.0017, 0.0007)), 0.02, 6);
  const TriangleMesh* meshes[] = {&sphere};
  for (const bool planes : {false, true}) {
    VoxelizeOptions options;
    options.voxelSizeM = 0.0005;
    options.surfacePlanes = planes;
    const VoxelizedObject v = voxelize(meshes, {}, options);
    const ChunkFootprint f = chunkFootprint(meshes, v.voxmap.grid(), 1, 1u << 30);
    const std::size_t stored = v.voxmap.mixedChunkCount();
    EXPECT_LE(f.surfaceChunks, stored) << planes;
    EXPECT_GE(f.mixedChunks, stored) << planes;
    EXPECT_LT(f.mixedChunks, 2 * stored) << planes;
    const VoxelizeEstimate e =
        estimateVoxelizeBytes(meshes, v.voxmap.grid(), options, std::uint64_t{1} << 40);
    EXPECT_FALSE(e.lowerBound);
    EXPECT_GE(e.bytes, v.voxmap.memoryBytes()) << planes;
  }
}

}  // namespace
}  // namespace voxhap
