#pragma once
/// Dynamic pre-fetching of voxel data (paper §5.3, DESIGN §4.6): the voxel words of a
/// static voxmap larger than its memory budget stay in the cache file and a pager thread
/// reads the chunks the haptic thread asks for into a fixed pool of slots (Voxmap::paged).
///
/// The haptic thread asks (request(), a lock-free single-producer ring that drops
/// requests when full) when a chunk of a pointshell comes within reach of the voxmap's
/// voxel-bearing chunks, and when a lookup finds a chunk missing; it never waits. The
/// pager reads a missing chunk's words into a free slot and publishes the chunk's entry
/// (Voxmap::PagedArrays::publish).
///
/// Eviction by last use. Every lookup that reads a resident chunk marks its slot with the
/// use clock (Voxmap::word: a relaxed load and, once a tick, a relaxed store). The clock
/// ticks at every beginFrame(), and, while the pager waits for a slot and no frame has
/// begun for kSelfTickInterval, once per such interval. Publishing a slot, and a request
/// for a chunk already resident, mark it as well. When no slot is free the pager takes
/// back the least recently used slots, never one used within the last kInUseTicks ticks
/// (this frame or the one before): it unpublishes their entries, then waits until the
/// haptic thread has begun two frames before reusing them, so that no lookup still reads
/// a slot being overwritten. When every slot is in use it waits, the frame that misses a
/// chunk stays suspended, and a suspension past 2 s stops the run with its error: a pool
/// smaller than the working set ends there instead of thrashing.
///
/// A failed or short read (BlockReader::read false) gives its slot back to the free pool,
/// counts in readFailures() and leaves the chunk missing; a later request tries again.
///
/// Load time (the constructors, makeResident()) allocates and may throw voxhap::Error; the
/// haptic thread's calls are noexcept, lock-free and allocation-free.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <thread>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "haptics/voxel/block_reader.h"
#include "haptics/voxel/voxmap.h"

namespace voxhap {

class VoxelPager {
public:
  /// A slot used within this many ticks of the use clock is in use and never taken back.
  static constexpr std::uint32_t kInUseTicks = 2;
  /// While the pager waits for a slot and no frame begins, it ticks the use clock this often.
  static constexpr std::chrono::milliseconds kSelfTickInterval{5};

  /// Pages a voxmap (`arrays`, from Voxmap::pagedArrays() of a Voxmap::paged) whose
  /// mixed chunk entries all read missing; `fileBlockOfEntry[i]` is the block of chunk
  /// entry i for `reader` (UINT32_MAX: not a mixed chunk). The pool holds `slotCount`
  /// blocks, as many as the voxmap's pool. The voxmap must outlive the pager.
  VoxelPager(const Voxmap::PagedArrays& arrays, std::unique_ptr<BlockReader> reader,
             std::vector<std::uint32_t> fileBlockOfEntry, std::size_t slotCount);
  /// As above, reading block b of `file` at `wordsOffset` + b · block bytes
  /// (FileBlockReader); throws voxhap::Error when the file cannot be opened.
  VoxelPager(const Voxmap::PagedArrays& arrays, const std::filesystem::path& file, std::uint64_t wordsOffset,
             std::vector<std::uint32_t> fileBlockOfEntry, std::size_t slotCount);
  ~VoxelPager();
  VoxelPager(const VoxelPager&) = delete;
  VoxelPager& operator=(const VoxelPager&) = delete;

  /// Haptic thread: a frame begins (the grace period of slots taken back counts these)
  /// and the use clock ticks.
  void beginFrame() noexcept;
  /// Haptic thread: asks for the chunks from `loChunk` to `hiChunk` (inclusive, chunk
  /// coordinates of the voxmap; clipped to its grid). Dropped when the ring is full.
  void request(const glm::ivec3& loChunk, const glm::ivec3& hiChunk) noexcept;

  /// Load time, before any frame: asks for the chunks and waits until the pager has
  /// served the request, beginning frames meanwhile (the caller stands in for the haptic
  /// thread). Chunks that could not be read, or kept, read missing.
  void makeResident(const glm::ivec3& loChunk, const glm::ivec3& hiChunk);

  std::size_t slotCount() const noexcept { return slotEntry_.size(); }
  /// Blocks read into slots (each a chunk made resident).
  std::uint64_t blocksRead() const noexcept { return blocksRead_.load(std::memory_order_relaxed); }
  /// Requests the ring had no room for.
  std::uint64_t requestsDropped() const noexcept { return dropped_.load(std::memory_order_relaxed); }
  /// Block reads that failed (their slots went back to the pool).
  std::uint64_t readFailures() const noexcept { return readFailures_.load(std::memory_order_relaxed); }
  /// Slots taken back from resident chunks (evictions).
  std::uint64_t slotsTakenBack() const noexcept { return takenBack_.load(std::memory_order_relaxed); }

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
  /// A free slot, taking back the least recently used when there is none; kNone when the
  /// pager is stopping.
  std::uint32_t freeSlot();
  /// Unpublishes the least recently used slots not in use (at most a batch) into `taken`.
  void takeBackLeastRecentlyUsed(std::vector<std::uint32_t>& taken);
  /// Waits until the haptic thread has begun two frames since now; false when stopping.
  bool waitForFrames();
  /// Sleeps a little; ticks the use clock when no frame has begun for kSelfTickInterval.
  void idleWhileWaiting();

  Voxmap::PagedArrays arrays_;
  std::unique_ptr<BlockReader> reader_;
  std::size_t blockBytes_;
  std::vector<std::uint32_t> fileBlockOfEntry_;
  // pager thread only
  std::vector<std::uint32_t> slotOfEntry_;  // per chunk entry, its slot or kNone
  std::vector<std::uint32_t> slotEntry_;    // per slot, the chunk entry in it, or kNone
  std::vector<std::uint32_t> freeSlots_;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> byAge_;  // scratch: (age in ticks, slot)
  std::uint32_t lastSeenClock_ = 0;
  std::chrono::steady_clock::time_point lastClockChange_{};

  Box ring_[kRingSize];
  std::atomic<std::uint64_t> ringHead_{0};  // written by the frame thread
  std::atomic<std::uint64_t> ringTail_{0};  // written by the pager
  std::atomic<std::uint64_t> frame_{0};     // frames begun
  std::atomic<std::uint64_t> blocksRead_{0};
  std::atomic<std::uint64_t> dropped_{0};
  std::atomic<std::uint64_t> readFailures_{0};
  std::atomic<std::uint64_t> takenBack_{0};
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace voxhap
