#include "haptics/voxel/sparse_surface_planes.h"

#include <algorithm>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>
#include <gtest/gtest.h>

namespace voxhap {
namespace {

/// A plane for voxel `i` of chunk `chunk` that no other voxel gets.
SurfacePlane planeOf(std::uint32_t chunk, std::uint32_t i) {
  return SurfacePlane::make(0.001 * (chunk * kVoxelsPerChunk + i), glm::dvec3(0, 0, 1));
}

/// Chunk 0: every third voxel has a plane; chunk 1: every voxel; chunk 2: none; chunk
/// 3: only the last voxel of each mask's run of 64 and the very first.
bool hasPlane(std::uint32_t chunk, std::uint32_t i) {
  switch (chunk) {
    case 0:
      return i % 3 == 0;
    case 1:
      return true;
    case 2:
      return false;
    default:
      return i == 0 || i % 64 == 63;
  }
}

constexpr std::uint32_t kChunks = 4;

SparseSurfacePlanes pattern() {
  SparseSurfacePlanes store;
  for (std::uint32_t chunk = 0; chunk < kChunks; ++chunk) {
    std::vector<SurfacePlane> planes(kVoxelsPerChunk);
    for (std::uint32_t i = 0; i < kVoxelsPerChunk; ++i)
      if (hasPlane(chunk, i)) planes[i] = planeOf(chunk, i);
    store.appendChunk(planes);
  }
  return store;
}

void expectPattern(const SparseSurfacePlanes& store) {
  ASSERT_EQ(store.chunkCount(), kChunks);
  for (std::uint32_t chunk = 0; chunk < kChunks; ++chunk)
    for (std::uint32_t i = 0; i < kVoxelsPerChunk; ++i) {
      const SurfacePlane* plane = store.find(chunk, i);
      if (hasPlane(chunk, i)) {
        ASSERT_NE(plane, nullptr) << chunk << " " << i;
        EXPECT_EQ(*plane, planeOf(chunk, i)) << chunk << " " << i;
      } else {
        EXPECT_EQ(plane, nullptr) << chunk << " " << i;
      }
    }
}

TEST(SparseSurfacePlanes, FindsEachVoxelsOwnPlaneAndNoneWhereItHasNone) {
  const SparseSurfacePlanes store = pattern();
  expectPattern(store);
  // only the planes are stored: 171 + 512 + 0 + 9 of 2,048 voxels
  EXPECT_EQ(store.planeCount(), 171u + 512u + 9u);
  EXPECT_LT(store.memoryBytes(), kChunks * kVoxelsPerChunk * sizeof(SurfacePlane) / 2);
}

/// `store`'s planes in one array.
std::vector<SurfacePlane> planesOf(const SparseSurfacePlanes& store) {
  std::vector<SurfacePlane> planes;
  for (std::size_t k = 0; k < store.segmentCount(); ++k)
    planes.insert(planes.end(), store.segment(k).begin(), store.segment(k).end());
  return planes;
}

TEST(SparseSurfacePlanes, RebuildsFromItsArrays) {
  const SparseSurfacePlanes store = pattern();
  SparseSurfacePlanes copy;
  ASSERT_EQ(copy.resetTo({store.occupancy().begin(), store.occupancy().end()}), "");
  ASSERT_EQ(copy.planeCount(), store.planeCount());
  EXPECT_FALSE(copy.complete());  // sized, not yet filled
  const std::vector<SurfacePlane> planes = planesOf(store);
  ASSERT_EQ(copy.segmentCount(), 1u);
  std::ranges::copy(planes, copy.segment(0).begin());
  EXPECT_TRUE(copy.complete());
  expectPattern(copy);
  EXPECT_TRUE(copy == store);
}

TEST(SparseSurfacePlanes, SegmentsHoldAMillionPlanesEachAndFindAcrossThem) {
  SparseSurfacePlanes store;
  std::vector<SurfacePlane> chunk(kVoxelsPerChunk);
  const std::uint32_t chunks = (1u << SparseSurfacePlanes::kSegmentLog2) / kVoxelsPerChunk + 2;
  for (std::uint32_t c = 0; c < chunks; ++c) {
    for (std::uint32_t i = 0; i < kVoxelsPerChunk; ++i) chunk[i] = planeOf(c % 16, i);
    store.appendChunk(chunk);
  }
  EXPECT_EQ(store.segmentCount(), 2u);
  for (const std::uint32_t c : {0u, chunks - 3, chunks - 2, chunks - 1})
    for (const std::uint32_t i : {0u, 1u, 511u}) {
      const SurfacePlane* plane = store.find(c, i);
      ASSERT_NE(plane, nullptr);
      EXPECT_EQ(*plane, planeOf(c % 16, i)) << c << " " << i;
    }
}

TEST(SparseSurfacePlanes, RefusesMasksThatAreNotWholeChunks) {
  const SparseSurfacePlanes store = pattern();
  const std::vector<std::uint64_t> masks(store.occupancy().begin(), store.occupancy().end());
  SparseSurfacePlanes out;
  EXPECT_NE(out.resetTo({masks.begin(), masks.end() - 1}), "");
  EXPECT_TRUE(out.empty());
  EXPECT_EQ(out.resetTo(masks), "");
  EXPECT_EQ(out.chunkCount(), kChunks);
}

}  // namespace
}  // namespace voxhap
