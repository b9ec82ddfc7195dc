#pragma once
/// The read-only voxmap the haptic thread samples (DESIGN §4.1): a 512-tree
/// flattened into three arrays, built once by the voxelizer and never changed.
///
///   hyper_[h]   per hyperchunk: kUniform | word when all its voxels hold one word,
///               else the index of its block of 512 chunk entries in chunks_
///   chunks_[c]  per chunk of a mixed hyperchunk: kUniform | word, or the index of
///               its block of 512 voxel words in voxelBytes_
///   voxelBytes_ packed words, encoding.bytesPerWord() bytes each, x fastest
///
/// A lookup is two or three dependent loads, no branch on the bit width, no
/// allocation; any thread may read concurrently.

#include <cstdint>
#include <cstring>
#include <vector>

#include "haptics/voxel/voxel_encoding.h"
#include "haptics/voxel/voxel_grid.h"

namespace voxhap {

class Voxmap {
public:
  /// Marks a tree entry that holds a uniform word rather than an index.
  static constexpr std::uint32_t kUniform = 0x80000000u;

  Voxmap() = default;
  Voxmap(VoxelGrid grid, VoxelEncoding encoding, std::vector<std::uint32_t> hyper,
         std::vector<std::uint32_t> chunks, std::vector<std::uint8_t> voxelBytes);

  const VoxelGrid& grid() const { return grid_; }
  const VoxelEncoding& encoding() const { return encoding_; }

  /// The packed word of voxel `ijkVoxel`; far (0) outside the grid.
  VoxelWord word(const glm::ivec3& ijkVoxel) const {
    if (!grid_.containsVoxel(ijkVoxel)) return 0;
    const glm::ivec3 h = ijkVoxel >> (kChunkEdgeLog2 + kHyperEdgeLog2);
    const std::uint32_t hyperEntry =
        hyper_[static_cast<std::size_t>(h.x + grid_.dimsHyper.x * (h.y + grid_.dimsHyper.y * h.z))];
    if (hyperEntry & kUniform) return hyperEntry & ~kUniform;
    const std::uint32_t chunkEntry =
        chunks_[std::size_t{hyperEntry} * kChunksPerHyper + chunkInHyper(ijkVoxel >> kChunkEdgeLog2)];
    if (chunkEntry & kUniform) return chunkEntry & ~kUniform;
    const std::size_t at =
        (std::size_t{chunkEntry} * kVoxelsPerChunk + voxelInChunk(ijkVoxel)) * bytesPerWord_;
    VoxelWord w;
    std::memcpy(&w, voxelBytes_.data() + at, sizeof w);  // the pool is padded for this read
    return w & wordMask_;
  }

  /// One field of voxel `ijkVoxel`.
  std::uint8_t value(const glm::ivec3& ijkVoxel, Field field) const {
    return encoding_.value(word(ijkVoxel), field);
  }

  /// Chunks stored voxel by voxel (the rest are uniform).
  std::size_t mixedChunkCount() const { return (voxelBytes_.size() - kPadBytes) / blockBytes(); }
  /// Bytes held by the tree's arrays.
  std::size_t memoryBytes() const {
    return hyper_.size() * sizeof(std::uint32_t) + chunks_.size() * sizeof(std::uint32_t) + voxelBytes_.size();
  }

  /// Bytes after the last block, so that a 4-byte read of the last word stays inside.
  static constexpr std::size_t kPadBytes = sizeof(VoxelWord);

private:
  std::size_t blockBytes() const { return std::size_t{kVoxelsPerChunk} * bytesPerWord_; }

  VoxelGrid grid_;
  VoxelEncoding encoding_;
  std::size_t bytesPerWord_ = 2;
  VoxelWord wordMask_ = 0;
  std::vector<std::uint32_t> hyper_;
  std::vector<std::uint32_t> chunks_;
  std::vector<std::uint8_t> voxelBytes_;
};

}  // namespace voxhap
