#pragma once
/// Shape of the 512-tree (DESIGN §4.1): voxel → chunk of 8³ voxels → hyperchunk of
/// 8³ chunks (64³ voxels). Every branching factor in the engine comes from here.

#include <cstdint>

#include <glm/vec3.hpp>

namespace voxhap {

inline constexpr int kChunkEdgeLog2 = 3;                      ///< log2 voxels per chunk edge
inline constexpr int kChunkEdgeVoxels = 1 << kChunkEdgeLog2;  ///< 8
inline constexpr int kVoxelsPerChunk = kChunkEdgeVoxels * kChunkEdgeVoxels * kChunkEdgeVoxels;  ///< 512
inline constexpr int kHyperEdgeLog2 = 3;                      ///< log2 chunks per hyperchunk edge
inline constexpr int kHyperEdgeChunks = 1 << kHyperEdgeLog2;  ///< 8
inline constexpr int kChunksPerHyper = kHyperEdgeChunks * kHyperEdgeChunks * kHyperEdgeChunks;  ///< 512
inline constexpr int kHyperEdgeVoxels = kChunkEdgeVoxels * kHyperEdgeChunks;                    ///< 64

/// Index of a voxel inside its chunk (x fastest), 0 … 511, from voxel coordinates.
inline constexpr std::uint32_t voxelInChunk(const glm::ivec3& ijkVoxel) {
  constexpr int m = kChunkEdgeVoxels - 1;
  return static_cast<std::uint32_t>((ijkVoxel.x & m) | ((ijkVoxel.y & m) << kChunkEdgeLog2) |
                                    ((ijkVoxel.z & m) << (2 * kChunkEdgeLog2)));
}

/// Index of a chunk inside its hyperchunk (x fastest), 0 … 511, from chunk coordinates.
inline constexpr std::uint32_t chunkInHyper(const glm::ivec3& ijkChunk) {
  constexpr int m = kHyperEdgeChunks - 1;
  return static_cast<std::uint32_t>((ijkChunk.x & m) | ((ijkChunk.y & m) << kHyperEdgeLog2) |
                                    ((ijkChunk.z & m) << (2 * kHyperEdgeLog2)));
}

/// (x, y, z) of index `i` in a block of 8³ (x fastest): the inverse of voxelInChunk and
/// chunkInHyper.
inline constexpr glm::ivec3 cellOfIndex(std::uint32_t i) {
  constexpr std::uint32_t m = kChunkEdgeVoxels - 1;
  static_assert(kChunkEdgeVoxels == kHyperEdgeChunks);
  return {static_cast<int>(i & m), static_cast<int>((i >> kChunkEdgeLog2) & m),
          static_cast<int>(i >> (2 * kChunkEdgeLog2))};
}

}  // namespace voxhap
