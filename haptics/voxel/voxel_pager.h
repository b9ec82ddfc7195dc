#pragma once
/// Dynamic pre-fetching of voxel data (paper §5.3, DESIGN §4.6): the voxel words of a
/// static voxmap larger than its memory budget stay in the cache file and a pager thread
/// reads the chunks that are asked for into a fixed pool of slots (Voxmap::paged).
///
/// Threads. The *frame thread* (the haptic thread; at load, the thread building the
/// model) asks for chunks (request(), a lock-free single-producer ring that drops
/// requests when full) when a chunk of a pointshell comes within reach of the voxmap's
/// voxel-bearing chunks, and when a lookup finds a chunk missing; it never waits. It
/// reads the voxmap as the *frame reader*, whose quiescent point is beginFrame(). Any
/// other thread that reads the voxmap registers a Reader at load time (at most
/// kMaxReaders − 1 of them) and reads inside enter() … leave() (or a ReadSection). The
/// *pager thread* reads a missing chunk's words into a free slot and publishes the
/// chunk's entry.
///
/// Eviction by last use. Every lookup that reads a resident chunk marks its slot with the
/// use clock (Voxmap::word: a relaxed load and, once a tick, a relaxed store). The clock
/// ticks at every beginFrame(), and, while the pager waits for a slot and no frame has
/// begun for kSelfTickInterval, once per such interval (readers outside frames age too).
/// Publishing a slot, and a request for a chunk already resident, mark it as well. When
/// no slot is free the pager takes back the least recently used slots, never one used
/// within the last kInUseTicks ticks (this frame or the one before); when every slot is in
/// use it waits, the frame that misses a chunk stays suspended, and a suspension past 2 s
/// stops the run with its error: a pool smaller than the working set ends there instead
/// of thrashing.
///
/// A failed or short read (BlockReader::read false) gives its slot back to the free pool,
/// counts in readFailures() and leaves the chunk missing; a later request tries again.
///
/// Who writes what. The pager thread: slot words (plain bytes), chunk entries, the global
/// epoch, the ring's tail. The frame thread: the ring's boxes and head, the use clock and
/// its own epoch word. Each Reader: its own epoch word. Every reader and the pager: slot
/// use marks (relaxed; they only steer the choice of a slot, never its safety).
///
/// Why the slot hand-over is race-free. Slot words are written only while no reader can
/// reach them. Chunk entries, reader epochs and the global epoch are atomics, every
/// operation naming its order (no std::atomic_thread_fence: ThreadSanitizer does not
/// model fences, and GCC rejects them under -fsanitize=thread with -Werror).
///  1. Publish: the pager writes a slot's words (BlockReader), then stores the slot index
///     into the chunk's entry with release (PagedArrays::publish). A lookup loads the
///     entry with a seq_cst load (an acquire, and more: see 3); when it reads the index it
///     synchronizes with that release, so the words it then reads are the ones written.
///  2. Reader epochs: enter() loads the global epoch (seq_cst) and stores it, never 0,
///     into the reader's own epoch word (seq_cst); leave() stores 0 (release), after every
///     word the section read. beginFrame() is the frame reader's leave() and enter() in
///     one seq_cst store of the current epoch (a store is a release too).
///  3. Take back: the pager unpublishes the entry (seq_cst store of kMissingWord), bumps
///     the global epoch to E (seq_cst fetch_add), then waits until every reader's epoch
///     word reads 0 or at least E (seq_cst loads), and only then rewrites the slot.
///     * Sections that ended: a reader seen at 0, or at ≥ E, stored that value after every
///       read of its earlier sections; the pager's load reads that store (a release:
///       leave(), or the seq_cst store of enter()/beginFrame()), so those reads happen
///       before the rewrite.
///     * A section that began at ≥ E: its enter() read the epoch's fetch_add (or a later
///       one), which the unpublish precedes, so its entry loads read the entry missing
///       (or republished with a new slot, whose words the new release carries).
///     * A section that begins while the pager looks (the store-buffering case: the
///       reader loaded an epoch < E, the pager saw it at 0): the unpublish, the pager's
///       epoch load, the reader's epoch store and its entry loads are all seq_cst, so in
///       their single total order either the pager's load comes after the reader's store
///       (it sees the reader inside, < E, and waits) or the reader's entry loads come
///       after the unpublish (they read missing).
///     Hence no lookup reads a slot's words while the pager rewrites them, and every
///     lookup that reads an index reads the words published with it. The frame reader is
///     outside (0) until its first beginFrame() or makeResident(), inside from then on.
///
/// Load time (the constructors, addReader(), makeResident()) allocates and may throw
/// voxhap::Error; the frame reader's and Readers' calls are noexcept, lock-free and
/// allocation-free. A reader must not wait for the pager (makeResident) inside a section.

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
  /// Readers of one paged voxmap, the frame reader among them.
  static constexpr std::size_t kMaxReaders = 16;
  /// A slot used within this many ticks of the use clock is in use and never taken back.
  static constexpr std::uint32_t kInUseTicks = 2;
  /// While the pager waits for a slot and no frame begins, it ticks the use clock this often.
  static constexpr std::chrono::milliseconds kSelfTickInterval{5};

  /// A thread that reads the paged voxmap, registered by addReader(). Move-only; gives
  /// its place back on destruction, which must be outside a section.
  class Reader {
  public:
    /// An empty handle (registered with no pager).
    Reader() = default;
    /// Takes `other`'s place; `other` is left empty.
    Reader(Reader&& other) noexcept : pager_(std::exchange(other.pager_, nullptr)), index_(other.index_) {}
    /// Gives this handle's place back (outside a section), then takes `other`'s.
    Reader& operator=(Reader&& other) noexcept;
    /// Gives the place back; must be outside a section.
    ~Reader();
    Reader(const Reader&) = delete;
    Reader& operator=(const Reader&) = delete;

    /// Begins a read section: lookups of the voxmap may follow until leave(). Noexcept,
    /// lock-free, allocation-free (two atomic loads and a seq_cst store).
    void enter() noexcept;
    /// Ends the section: every word read since enter() is done with (a release store).
    void leave() noexcept;
    /// leave() then enter() in one store: a quiescent point of a reader that stays inside.
    void quiescent() noexcept;

  private:
    friend class VoxelPager;
    Reader(VoxelPager* pager, std::size_t index) : pager_(pager), index_(index) {}
    /// Gives the place back to the pager (outside a section); the handle is empty after.
    void release() noexcept;
    VoxelPager* pager_ = nullptr;
    std::size_t index_ = 0;
  };

  /// A read section of `reader` for the scope's lifetime.
  class ReadSection {
  public:
    /// Enters `reader`'s section; `reader` must outlive the section.
    explicit ReadSection(Reader& reader) noexcept : reader_(reader) { reader_.enter(); }
    /// Leaves it.
    ~ReadSection() { reader_.leave(); }
    ReadSection(const ReadSection&) = delete;
    ReadSection& operator=(const ReadSection&) = delete;

  private:
    Reader& reader_;
  };

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

  /// Frame thread: a frame begins. The frame reader passes a quiescent point (and is
  /// inside from now on) and the use clock ticks.
  void beginFrame() noexcept;
  /// Frame thread: asks for the chunks from `loChunk` to `hiChunk` (inclusive, chunk
  /// coordinates of the voxmap; clipped to its grid). Dropped when the ring is full.
  void request(const glm::ivec3& loChunk, const glm::ivec3& hiChunk) noexcept;

  /// Frame thread at load time, before any frame: asks for the chunks and waits until the
  /// pager has served the request, beginning frames meanwhile (no frame reads the voxmap
  /// yet). Chunks that could not be read, or kept, read missing.
  void makeResident(const glm::ivec3& loChunk, const glm::ivec3& hiChunk);

  /// Load time: registers a reader other than the frame reader. Throws voxhap::Error
  /// when kMaxReaders − 1 are registered already.
  Reader addReader();

  /// Slots of the pool (chunks that can be resident at once).
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
  /// One reader's epoch word, on its own cache line: 0 outside a section, else the global
  /// epoch when its section began.
  struct alignas(64) ReaderEpoch {
    std::atomic<std::uint64_t> epoch{0};
    std::atomic<bool> taken{false};
  };
  static constexpr std::uint32_t kNone = 0xFFFFFFFFu;
  static constexpr std::size_t kRingSize = 4096;  // a power of two
  static constexpr std::size_t kFrameReader = 0;

  void enter(std::size_t reader) noexcept;
  void leave(std::size_t reader) noexcept;
  void run();
  /// Makes every chunk of `box` resident; false when the pager is stopping.
  bool serve(const Box& box);
  /// A free slot, taking back the least recently used when there is none; kNone when the
  /// pager is stopping.
  std::uint32_t freeSlot();
  /// Unpublishes the least recently used slots not in use (at most a batch) into `taken`.
  void takeBackLeastRecentlyUsed(std::vector<std::uint32_t>& taken);
  /// Waits until every reader has passed a quiescent point since now; false when stopping.
  bool waitForReaders();
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
  std::atomic<std::uint64_t> epoch_{1};     // global epoch, advanced by the pager
  ReaderEpoch readers_[kMaxReaders];
  std::atomic<std::uint64_t> blocksRead_{0};
  std::atomic<std::uint64_t> dropped_{0};
  std::atomic<std::uint64_t> readFailures_{0};
  std::atomic<std::uint64_t> takenBack_{0};
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace voxhap
