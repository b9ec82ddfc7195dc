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
/// Beside the tree, chunkDistances_ holds one byte per chunk of the grid (x fastest):
/// the chessboard distance in chunks to the nearest voxel-bearing chunk (chunk_distance.h).
///
/// A lookup is two or three dependent loads, no branch on the bit width, no
/// allocation; any thread may read concurrently.
///
/// Paged (voxel_pager.h, Voxmap::paged): when the voxel words do not fit a memory budget,
/// voxelBytes_ is a pool of slots that a pager thread fills from the cache file, and a
/// mixed chunk's entry reads kUniform | kMissingWord until its words are resident; it
/// then holds the index of its slot. Every slot is followed by kPadBytes of padding, so
/// that the 4-byte read of a slot's last word never touches the next slot, which the
/// pager may be rewriting. word() returns kMissingWord for a chunk that is not
/// resident; callers of a paged voxmap check for it. Chunk entries are read with
/// sequentially consistent loads (a plain load on x86, ldar on ARMv8: what an acquire
/// load costs), which the pager's hand-over of slots relies on (voxel_pager.h says why).
/// A lookup that reads a resident chunk marks its slot with the use clock (a relaxed
/// load, compare and, once a tick, a relaxed store; no lock, no allocation), so that the
/// pager takes back the least recently used slots. An unpaged voxmap skips the mark on
/// one predictable branch.

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

#include <glm/vector_relational.hpp>

#include "haptics/voxel/sparse_surface_planes.h"
#include "haptics/voxel/voxel_encoding.h"
#include "haptics/voxel/voxel_grid.h"

namespace voxhap {

class Voxmap {
public:
  /// Marks a tree entry that holds a uniform word rather than an index.
  static constexpr std::uint32_t kUniform = 0x80000000u;
  /// What word() returns for a voxel whose chunk is paged out: no encoding makes it (its
  /// fields would run past 24 bits).
  static constexpr VoxelWord kMissingWord = 0x7FFFFFFFu;

  Voxmap() = default;
  /// Takes the flat tree (see above) and the chunk-level field, one byte per chunk of
  /// `grid`, x fastest. The arrays must be consistent (the voxelizer's output, or a
  /// cache file that passed validate()).
  Voxmap(VoxelGrid grid, VoxelEncoding encoding, std::vector<std::uint32_t> hyper,
         std::vector<std::uint32_t> chunks, std::vector<std::uint8_t> voxelBytes,
         std::vector<std::uint8_t> chunkDistances);

  /// A paged voxmap: the tables as above, but every mixed chunk entry reads
  /// kUniform | kMissingWord, and the words live in a pool of `slotCount` slots that a
  /// pager fills (pagedArrays()). Every slot's use mark starts at 0, as does the clock.
  static Voxmap paged(VoxelGrid grid, VoxelEncoding encoding, std::vector<std::uint32_t> hyper,
                      std::vector<std::uint32_t> chunks, std::size_t slotCount,
                      std::vector<std::uint8_t> chunkDistances);

  /// Why these arrays do not make a voxmap (an index out of range, a size that does
  /// not match the grid), or an empty string when they do. For data read from disk.
  static std::string validate(const VoxelGrid& grid, const VoxelEncoding& encoding,
                              std::span<const std::uint32_t> hyper, std::span<const std::uint32_t> chunks,
                              std::size_t voxelBytesSize, std::size_t chunkDistancesSize);

  const VoxelGrid& grid() const { return grid_; }
  const VoxelEncoding& encoding() const { return encoding_; }

  /// The packed word of voxel `ijkVoxel`; far (0) outside the grid.
  VoxelWord word(const glm::ivec3& ijkVoxel) const {
    if (!grid_.containsVoxel(ijkVoxel)) return 0;
    const std::uint32_t chunkEntry = treeEntry_(ijkVoxel);
    if (chunkEntry & kUniform) return chunkEntry & ~kUniform;
    if (!slotLastUse_.empty()) markUse_(chunkEntry);
    return wordInBlock_(chunkEntry, ijkVoxel);
  }

  /// The words of voxel `ijkVoxel` and of its six face neighbours, in the order of
  /// kAroundSteps, as seven calls of word() give them: one tree walk where all seven lie in
  /// one chunk.
  static constexpr glm::ivec3 kAroundSteps[7] = {{0, 0, 0}, {-1, 0, 0}, {1, 0, 0}, {0, -1, 0},
                                                 {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
  std::array<VoxelWord, 7> wordsAround(const glm::ivec3& ijkVoxel) const {
    const glm::ivec3 inChunk = ijkVoxel & (kChunkEdgeVoxels - 1);
    const bool oneChunk = grid_.containsVoxel(ijkVoxel) &&
                          glm::all(glm::greaterThan(inChunk, glm::ivec3(0))) &&
                          glm::all(glm::lessThan(inChunk, glm::ivec3(kChunkEdgeVoxels - 1)));
    std::array<VoxelWord, 7> words;
    if (!oneChunk) {
      for (std::size_t n = 0; n < words.size(); ++n) words[n] = word(ijkVoxel + kAroundSteps[n]);
      return words;
    }
    const std::uint32_t chunkEntry = treeEntry_(ijkVoxel);
    if (chunkEntry & kUniform) {
      words.fill(chunkEntry & ~kUniform);
      return words;
    }
    if (!slotLastUse_.empty()) markUse_(chunkEntry);
    for (std::size_t n = 0; n < words.size(); ++n)
      words[n] = wordInBlock_(chunkEntry, ijkVoxel + kAroundSteps[n]);
    return words;
  }

  /// The surface plane of voxel `ijkVoxel` (surface_planes.h), or null: the voxmap has
  /// none, or the voxel lies outside the grid, in a uniform chunk or beyond the planes' band.
  const SurfacePlane* surfacePlane(const glm::ivec3& ijkVoxel) const {
    const std::uint32_t chunkEntry = planesEntry_(ijkVoxel);
    return chunkEntry & kUniform ? nullptr : planes_.find(chunkEntry, voxelInChunk(ijkVoxel));
  }
  /// The same, with the sides on which its neighbours' planes are convex with it.
  PlaneWithSides surfacePlaneWithSides(const glm::ivec3& ijkVoxel) const {
    const std::uint32_t chunkEntry = planesEntry_(ijkVoxel);
    return chunkEntry & kUniform ? PlaneWithSides{}
                                 : planes_.findWithSides(chunkEntry, voxelInChunk(ijkVoxel));
  }
  /// The surface planes of the voxels beside `ijkVoxel` along x, y and z, each on the side
  /// `side` names (−1 or +1 per axis), as surfacePlane() gives them: one tree walk for
  /// those in the chunk of `ijkVoxel`.
  std::array<const SurfacePlane*, 3> surfacePlanesBeside(const glm::ivec3& ijkVoxel,
                                                         const glm::ivec3& side) const {
    std::array<const SurfacePlane*, 3> beside{};
    if (planes_.empty()) return beside;
    const bool inGrid = grid_.containsVoxel(ijkVoxel);
    const std::uint32_t chunkEntry = inGrid ? treeEntry_(ijkVoxel) : kUniform;
    const glm::ivec3 chunk = ijkVoxel >> kChunkEdgeLog2;
    for (int axis = 0; axis < 3; ++axis) {
      glm::ivec3 v = ijkVoxel;
      v[axis] += side[axis];
      if (!inGrid || (v[axis] >> kChunkEdgeLog2) != chunk[axis]) {
        beside[static_cast<std::size_t>(axis)] = surfacePlane(v);
      } else if (!(chunkEntry & kUniform)) {
        beside[static_cast<std::size_t>(axis)] = planes_.find(chunkEntry, voxelInChunk(v));
      }
    }
    return beside;
  }
  /// Gives an unpaged voxmap its surface planes: one chunk of them per mixed chunk, in the
  /// order of the chunks' blocks of words (computeSurfacePlanes). Planes without their
  /// convex sides (computeSurfacePlanes' planes; a cache file's have them) get them here,
  /// on up to `threads` threads (0: all cores).
  void setSurfacePlanes(SparseSurfacePlanes planes, int threads);
  bool hasSurfacePlanes() const noexcept { return !planes_.empty(); }
  const SparseSurfacePlanes& surfacePlanes() const noexcept { return planes_; }

  /// One field of voxel `ijkVoxel`.
  std::uint8_t value(const glm::ivec3& ijkVoxel, Field field) const {
    return encoding_.value(word(ijkVoxel), field);
  }

  /// Chessboard distance, in chunks, from chunk `ijkChunk` to the nearest chunk holding a
  /// voxel whose surface field is not far; 0 for such a chunk, capped at 255. Outside
  /// the grid: the chessboard distance to the grid's box of chunks (a lower bound), at
  /// least 1, capped at 255.
  std::uint8_t chunkDistance(const glm::ivec3& ijkChunk) const noexcept {
    const glm::ivec3 d = grid_.dimsChunks();
    const glm::ivec3 below = glm::ivec3(0) - ijkChunk;
    const glm::ivec3 above = ijkChunk - (d - 1);
    const int outside = std::max({below.x, below.y, below.z, above.x, above.y, above.z});
    if (outside > 0 || chunkDistances_.empty()) return static_cast<std::uint8_t>(std::clamp(outside, 1, 255));
    return chunkDistances_[static_cast<std::size_t>(ijkChunk.x) +
                           static_cast<std::size_t>(d.x) *
                               (static_cast<std::size_t>(ijkChunk.y) +
                                static_cast<std::size_t>(d.y) * static_cast<std::size_t>(ijkChunk.z))];
  }

  /// The flat tree's arrays and the chunk-level field, for serialization; see above.
  std::span<const std::uint32_t> hyperEntries() const { return hyper_; }
  std::span<const std::uint32_t> chunkEntries() const { return chunks_; }
  /// Packed words of the mixed chunks, without the read padding (of a paged voxmap: its
  /// pool of padded slots, which is no such array).
  std::span<const std::uint8_t> voxelBytes() const {
    return {voxelBytes_.data(), voxelBytes_.size() - std::min(voxelBytes_.size(), kPadBytes)};
  }
  std::span<const std::uint8_t> chunkDistances() const { return chunkDistances_; }

  /// Chunks stored voxel by voxel (the rest are uniform); of a whole voxmap.
  std::size_t mixedChunkCount() const { return voxelBytes().size() / blockBytes(); }
  /// The chunk coordinates of each mixed chunk, by its block of words.
  std::vector<glm::ivec3> chunkOfEachBlock() const;
  /// Bytes held by the tree's arrays and the chunk-level field.
  std::size_t memoryBytes() const {
    return hyper_.size() * sizeof(std::uint32_t) + chunks_.size() * sizeof(std::uint32_t) +
           voxelBytes_.size() + chunkDistances_.size() + slotLastUse_.size() * sizeof(std::uint32_t) +
           planes_.memoryBytes();
  }

  /// Bytes after the last block, so that a 4-byte read of the last word stays inside. A
  /// paged voxmap pads every slot so: the read of a slot's last word must not touch the
  /// next slot, which the pager may be rewriting.
  static constexpr std::size_t kPadBytes = sizeof(VoxelWord);
  /// Bytes a paged voxmap spends per slot beside its words: the slot's padding and its use mark.
  static constexpr std::size_t kSlotOverheadBytes = kPadBytes + sizeof(std::uint32_t);

  /// The arrays a pager (voxel_pager.h) fills and reads: they live on the heap and stay
  /// where they are when the voxmap is moved. For an unpaged voxmap the use marks are null.
  struct PagedArrays {
    VoxelGrid grid;                        ///< the voxmap's grid
    const std::uint32_t* hyper = nullptr;  ///< hyperchunk entries (never paged)
    std::uint32_t* chunks = nullptr;       ///< entries: published with release, unpublished with seq_cst
    std::uint8_t* pool = nullptr;          ///< the slots, slot s at pool + s · slotStrideBytes
    std::size_t blockBytes = 0;            ///< bytes of a chunk's words
    std::size_t slotStrideBytes = 0;       ///< bytes from one slot to the next (padded)
    std::uint32_t* slotLastUse = nullptr;  ///< per slot, the use clock when a lookup last read it
    std::size_t slotCount = 0;
    std::uint32_t* useClock = nullptr;  ///< the use clock, in ticks (voxel_pager.h)

    /// The index in `chunks` of chunk `ijkChunk` (inside the grid), or −1 when its
    /// hyperchunk is uniform.
    std::int64_t chunkEntryIndex(const glm::ivec3& ijkChunk) const {
      const glm::ivec3 h = ijkChunk >> kHyperEdgeLog2;
      const std::uint32_t hyperEntry =
          hyper[static_cast<std::size_t>(h.x + grid.dimsHyper.x * (h.y + grid.dimsHyper.y * h.z))];
      if (hyperEntry & kUniform) return -1;
      return static_cast<std::int64_t>(std::size_t{hyperEntry} * kChunksPerHyper + chunkInHyper(ijkChunk));
    }
    /// Pager: entry `index` now names `slot`, whose words it has written: a release store,
    /// so that a lookup whose load reads the slot index also reads those words.
    void publish(std::size_t index, std::uint32_t slot) const {
      std::atomic_ref<std::uint32_t>(chunks[index]).store(slot, std::memory_order_release);
    }
    /// Pager: entry `index` reads missing again. Sequentially consistent, to be ordered
    /// before the pager's loads of reader epochs (voxel_pager.h).
    void unpublish(std::size_t index) const {
      std::atomic_ref<std::uint32_t>(chunks[index]).store(kUniform | kMissingWord, std::memory_order_seq_cst);
    }
    /// The use clock now, ticks.
    std::uint32_t clockNow() const {
      return std::atomic_ref<std::uint32_t>(*useClock).load(std::memory_order_relaxed);
    }
    /// Advances the use clock by one tick.
    void tick() const { std::atomic_ref<std::uint32_t>(*useClock).fetch_add(1, std::memory_order_relaxed); }
    /// The tick at which `slot` was last read (or published, or asked for).
    std::uint32_t lastUse(std::uint32_t slot) const {
      return std::atomic_ref<std::uint32_t>(slotLastUse[slot]).load(std::memory_order_relaxed);
    }
    /// Marks `slot` used at tick `now`.
    void markUse(std::uint32_t slot, std::uint32_t now) const {
      std::atomic_ref<std::uint32_t>(slotLastUse[slot]).store(now, std::memory_order_relaxed);
    }
  };
  /// The arrays an unpaged voxmap's lookup reads, for a vectorized lookup that does the
  /// same as word() eight voxels at a time (point_sampler_avx2.cpp). Its blocks of words
  /// follow each other: block b's words start at b · 512 words.
  struct LookupArrays {
    const std::uint32_t* hyper = nullptr;
    const std::uint32_t* chunks = nullptr;
    const std::uint8_t* words = nullptr;  ///< voxelBytes, padded for a 4-byte read of the last word
    std::size_t bytesPerWord = 0;
    VoxelWord wordMask = 0;
  };
  LookupArrays lookupArrays() const {
    return {hyper_.data(), chunks_.data(), voxelBytes_.data(), bytesPerWord_, wordMask_};
  }

  /// Whether its words are a pool of slots that a pager fills (Voxmap::paged).
  bool isPaged() const noexcept { return !slotLastUse_.empty(); }

  /// The arrays a pager fills, for VoxelPager (its use marks null unless Voxmap::paged).
  PagedArrays pagedArrays() {
    return {grid_,
            hyper_.data(),
            chunks_.data(),
            voxelBytes_.data(),
            blockBytes(),
            blockStrideBytes_,
            slotLastUse_.empty() ? nullptr : slotLastUse_.data(),
            slotLastUse_.size(),
            useClock_.empty() ? nullptr : useClock_.data()};
  }

private:
  /// The word of voxel `ijkVoxel` in the block of mixed chunk `chunkEntry`.
  VoxelWord wordInBlock_(std::uint32_t chunkEntry, const glm::ivec3& ijkVoxel) const {
    const std::size_t at =
        std::size_t{chunkEntry} * blockStrideBytes_ + voxelInChunk(ijkVoxel) * bytesPerWord_;
    VoxelWord w;
    std::memcpy(&w, voxelBytes_.data() + at, sizeof w);  // padded for this read: each slot, or the end
    return w & wordMask_;
  }
  /// Words of useClock_: the clock, then padding to a cache line of its own.
  static constexpr std::size_t kClockWords = 64 / sizeof(std::uint32_t);

  /// The chunk entry of `ijkVoxel` for a plane lookup: kUniform where it can have none
  /// (no planes, outside the grid, a uniform chunk).
  std::uint32_t planesEntry_(const glm::ivec3& ijkVoxel) const {
    return planes_.empty() || !grid_.containsVoxel(ijkVoxel) ? kUniform : treeEntry_(ijkVoxel);
  }
  /// The sides of voxel `ijkVoxel`, whose plane is `plane`, on which its neighbours' planes
  /// are convex with it.
  std::uint8_t convexSidesOf_(const glm::ivec3& ijkVoxel, const SurfacePlane& plane) const;
  /// The tree's entry for the chunk of `ijkVoxel` (inside the grid): kUniform | word, or
  /// the index of its block.
  std::uint32_t treeEntry_(const glm::ivec3& ijkVoxel) const {
    const glm::ivec3 h = ijkVoxel >> (kChunkEdgeLog2 + kHyperEdgeLog2);
    const std::uint32_t hyperEntry =
        hyper_[static_cast<std::size_t>(h.x + grid_.dimsHyper.x * (h.y + grid_.dimsHyper.y * h.z))];
    if (hyperEntry & kUniform) return hyperEntry;
    return chunkEntry_(std::size_t{hyperEntry} * kChunksPerHyper + chunkInHyper(ijkVoxel >> kChunkEdgeLog2));
  }
  std::uint32_t chunkEntry_(std::size_t index) const {
    // atomic_ref needs a non-const object; the entry is only read here. seq_cst: the
    // pager's grace period needs this load ordered after the reader's epoch store
    return std::atomic_ref<std::uint32_t>(const_cast<std::uint32_t&>(chunks_[index]))
        .load(std::memory_order_seq_cst);
  }
  /// Marks pool slot `slot` used now; the store only once a tick, so the line stays shared.
  void markUse_(std::uint32_t slot) const {
    const std::uint32_t now = std::atomic_ref<std::uint32_t>(const_cast<std::uint32_t&>(useClock_[0]))
                                  .load(std::memory_order_relaxed);
    std::atomic_ref<std::uint32_t> mark(const_cast<std::uint32_t&>(slotLastUse_[slot]));
    if (mark.load(std::memory_order_relaxed) != now) mark.store(now, std::memory_order_relaxed);
  }

  std::size_t blockBytes() const { return std::size_t{kVoxelsPerChunk} * bytesPerWord_; }

  VoxelGrid grid_;
  VoxelEncoding encoding_;
  std::size_t bytesPerWord_ = 2;
  std::size_t blockStrideBytes_ = 0;  // bytes from one block of words to the next
  VoxelWord wordMask_ = 0;
  std::vector<std::uint32_t> hyper_;
  std::vector<std::uint32_t> chunks_;
  std::vector<std::uint8_t> voxelBytes_;
  std::vector<std::uint8_t> chunkDistances_;
  std::vector<std::uint32_t> slotLastUse_;  // paged: per slot, the tick of its last use
  std::vector<std::uint32_t> useClock_;     // paged: [0] the use clock, the rest padding
  SparseSurfacePlanes planes_;              // unpaged, optional
};

}  // namespace voxhap
