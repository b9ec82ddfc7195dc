#pragma once
/// Dynamic pre-fetching of voxel data (paper §5.3, DESIGN §4.6): the voxel words of a
/// static voxmap larger than its memory budget stay in the cache file and a pager thread
/// reads the chunks the haptic thread asks for into a fixed pool of slots.
///
/// The haptic thread asks (request(), a lock-free single-producer ring that drops
/// requests when full) when a chunk of a pointshell comes within reach of the voxmap's
/// voxel-bearing chunks, and when a lookup finds a chunk missing; it never waits. The
/// pager reads a missing chunk's words with pread into a free slot and publishes the
/// chunk's entry (Voxmap::PagedArrays::publish). When slots run short it takes back those
/// least recently asked for: it unpublishes their entries, then waits until the haptic
/// thread has begun two frames (beginFrame()) before reusing them, so that no lookup
/// still reads a slot being overwritten.
///
/// Load time (the constructor, makeResident()) allocates and may throw voxhap::Error; the
/// haptic thread's calls are noexcept, lock-free and allocation-free.

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <thread>
#include <vector>

#include <glm/vec3.hpp>

#include "haptics/voxel/voxmap.h"

namespace voxhap {

class VoxelPager {
public:
  /// Pages a voxmap (`arrays`, from Voxmap::pagedArrays()) whose mixed chunk entries all
  /// read missing; `fileBlockOfEntry[i]` is the block in `file` of chunk entry i
  /// (UINT32_MAX: not a mixed chunk), block b lying at `wordsOffset` + b · block bytes. The
  /// pool holds `slotCount` blocks. The voxmap must outlive the pager.
  VoxelPager(const Voxmap::PagedArrays& arrays, const std::filesystem::path& file, std::uint64_t wordsOffset,
             std::vector<std::uint32_t> fileBlockOfEntry, std::size_t slotCount);
  ~VoxelPager();
  VoxelPager(const VoxelPager&) = delete;
  VoxelPager& operator=(const VoxelPager&) = delete;

  /// Haptic thread: a frame begins (the grace period of slots taken back counts these).
  void beginFrame() noexcept { frame_.fetch_add(1, std::memory_order_seq_cst); }
  /// Haptic thread: asks for the chunks from `loChunk` to `hiChunk` (inclusive, chunk
  /// coordinates of the voxmap; clipped to its grid). Dropped when the ring is full.
  void request(const glm::ivec3& loChunk, const glm::ivec3& hiChunk) noexcept;

  /// Load time, before any frame: asks for the chunks and waits until the pager has read
  /// them (the caller stands in for the haptic thread, whose frames it counts).
  void makeResident(const glm::ivec3& loChunk, const glm::ivec3& hiChunk);

  std::size_t slotCount() const noexcept { return slotEntry_.size(); }
  std::uint64_t blocksRead() const noexcept { return blocksRead_.load(std::memory_order_relaxed); }
  std::uint64_t requestsDropped() const noexcept { return dropped_.load(std::memory_order_relaxed); }

private:
  struct Box {
    glm::ivec3 lo;
    glm::ivec3 hi;
  };
  static constexpr std::uint32_t kNone = 0xFFFFFFFFu;
  static constexpr std::size_t kRingSize = 4096;  // a power of two

  void run();
  /// Makes every chunk of `box` resident; false when the pager is stopping.
  bool serve(const Box& box);
  /// A free slot, taking back the least recently asked for when there is none; kNone
  /// when the pager is stopping.
  std::uint32_t freeSlot();

  Voxmap::PagedArrays arrays_;
  int fd_ = -1;
  std::uint64_t wordsOffset_;
  std::size_t blockBytes_;
  std::vector<std::uint32_t> fileBlockOfEntry_;
  std::vector<std::uint32_t> slotOfEntry_;     // pager thread only
  std::vector<std::uint32_t> slotEntry_;       // per slot, the chunk entry in it, or kNone
  std::vector<std::uint64_t> slotAskedFrame_;  // per slot, the frame it was last asked for
  std::vector<std::uint32_t> freeSlots_;
  std::size_t clockHand_ = 0;

  Box ring_[kRingSize];
  std::atomic<std::uint64_t> ringHead_{0};  // written by the haptic thread
  std::atomic<std::uint64_t> ringTail_{0};  // written by the pager
  std::atomic<std::uint64_t> frame_{0};
  std::atomic<std::uint64_t> blocksRead_{0};
  std::atomic<std::uint64_t> dropped_{0};
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace voxhap
