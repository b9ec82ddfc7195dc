#pragma once
/// Mutable sparse storage used while voxelizing: per hyperchunk, the 512-element
/// blocks of the chunks that hold something. Each hyperchunk is written by one thread
/// at a time, so hyperchunks can be built in parallel without locks, and the result
/// does not depend on which thread built which hyperchunk.

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "haptics/voxel/tree_shape.h"

namespace voxhap {

template <typename T>
class HyperchunkBlocks {
public:
  using Block = std::array<T, kVoxelsPerChunk>;

  explicit HyperchunkBlocks(const glm::ivec3& dimsHyper)
      : dimsHyper_(dimsHyper),
        hypers_(static_cast<std::size_t>(dimsHyper.x) * static_cast<std::size_t>(dimsHyper.y) *
                static_cast<std::size_t>(dimsHyper.z)) {}

  const glm::ivec3& dimsHyper() const { return dimsHyper_; }
  std::size_t hyperCount() const { return hypers_.size(); }
  std::size_t hyperIndex(const glm::ivec3& ijkHyper) const {
    return static_cast<std::size_t>(ijkHyper.x) +
           static_cast<std::size_t>(dimsHyper_.x) *
               (static_cast<std::size_t>(ijkHyper.y) +
                static_cast<std::size_t>(dimsHyper_.y) * static_cast<std::size_t>(ijkHyper.z));
  }
  bool containsHyper(const glm::ivec3& h) const {
    return h.x >= 0 && h.y >= 0 && h.z >= 0 && h.x < dimsHyper_.x && h.y < dimsHyper_.y && h.z < dimsHyper_.z;
  }

  /// The block of chunk `ijkChunk`, or nullptr when it holds nothing (or lies outside).
  const Block* find(const glm::ivec3& ijkChunk) const {
    const glm::ivec3 h = ijkChunk >> kHyperEdgeLog2;
    if (!containsHyper(h)) return nullptr;
    const Hyper* hyper = hypers_[hyperIndex(h)].get();
    if (!hyper) return nullptr;
    const std::int32_t b = hyper->blockOfChunk[chunkInHyper(ijkChunk)];
    return b < 0 ? nullptr : &hyper->blocks[static_cast<std::size_t>(b)];
  }

  /// The block of chunk `ijkChunk` (inside the grid), created filled with `fill` when
  /// absent. Only the thread that owns the chunk's hyperchunk may call this.
  Block& findOrCreate(const glm::ivec3& ijkChunk, T fill) {
    std::unique_ptr<Hyper>& hyper = hypers_[hyperIndex(ijkChunk >> kHyperEdgeLog2)];
    if (!hyper) {
      hyper = std::make_unique<Hyper>();
      hyper->blockOfChunk.fill(-1);
    }
    std::int32_t& b = hyper->blockOfChunk[chunkInHyper(ijkChunk)];
    if (b < 0) {
      b = static_cast<std::int32_t>(hyper->blocks.size());
      hyper->blocks.emplace_back().fill(fill);
    }
    return hyper->blocks[static_cast<std::size_t>(b)];
  }

  /// Whether hyperchunk `ijkHyper` holds any block.
  bool hyperHasBlocks(const glm::ivec3& ijkHyper) const {
    return containsHyper(ijkHyper) && hypers_[hyperIndex(ijkHyper)] != nullptr;
  }

  /// Blocks held in all, for memory figures.
  std::size_t blockCount() const {
    std::size_t n = 0;
    for (const auto& h : hypers_) n += h ? h->blocks.size() : 0;
    return n;
  }

private:
  struct Hyper {
    std::array<std::int32_t, kChunksPerHyper> blockOfChunk;
    std::vector<Block> blocks;
  };
  glm::ivec3 dimsHyper_;
  std::vector<std::unique_ptr<Hyper>> hypers_;
};

}  // namespace voxhap
