#pragma once
/// Distance-to-contact queues (paper §5, DESIGN §4.5).
///
/// Every point of a pointshell sits in exactly one queue: queue 0 holds the points in
/// contact (tested every frame), queue i ≥ 1 the points i voxels from contact. Each
/// queue is a bitmap over the whole pointshell, one bit per point, with a second level
/// of one summary bit per 32-bit word, so that a sparse queue is walked by skipping
/// empty words 32 at a time. Each queue keeps its own count and a round-robin cursor.
///
/// Sweeps go round the pointshell's blocks (runs of 1 to 32 words, at least 512 blocks
/// where there are that many words), not its indices in order: a queue's points crowd
/// into runs of indices (a part's mating face is one run of its pointshell's chunks), and
/// a sweep in index order that must cover a share of the indices each frame takes a whole
/// run at once, then nothing for many frames. The round visits neighbouring blocks at
/// steps spread evenly over it (a golden-section stride, the three-gap theorem), so a
/// share of the round holds about that share of any queue.
///
/// Sized once for a pointshell (allocates); every other call is noexcept and
/// allocation-free, for the 1 kHz frame. Not thread-safe: the haptic thread owns it.

#include <cstdint>
#include <span>
#include <vector>

namespace voxhap {

class PointQueues {
public:
  /// `queueCount` queues (≥ 1) over `pointCount` points, all empty.
  PointQueues(std::uint32_t pointCount, int queueCount);

  std::uint32_t pointCount() const noexcept { return pointCount_; }
  int queueCount() const noexcept { return static_cast<int>(counts_.size()); }
  /// Points in queue `q`.
  std::uint32_t count(int q) const noexcept { return counts_[static_cast<std::size_t>(q)]; }
  /// The queue holding `point`, or −1 when it is in none.
  int queueOf(std::uint32_t point) const noexcept;

  /// Puts `point` (in no queue) into queue `q`.
  void insert(std::uint32_t point, int q) noexcept;
  /// Takes `point` out of queue `q` (it must be there).
  void remove(std::uint32_t point, int q) noexcept;
  /// Moves `point` from queue `from` to queue `to`.
  void move(std::uint32_t point, int from, int to) noexcept;
  /// Puts points [first, last) (in no queue) into queue `q` (a chunk coming back in range).
  void insertRange(std::uint32_t first, std::uint32_t last, int q) noexcept;
  /// Empties every queue and puts all points into queue `q`, word by word.
  void assignAll(int q) noexcept;
  /// Empties every queue.
  void clear() noexcept;
  /// Moves every point of queue `from` into queue `to`, word by word.
  void mergeInto(int from, int to) noexcept;
  /// Takes points [first, last) out of whatever queue holds them (a chunk leaving range).
  void removeRange(std::uint32_t first, std::uint32_t last) noexcept;

  /// Blocks in a sweep's round.
  std::uint32_t sweepBlockCount() const noexcept { return blockCount_; }

  /// What one takeSweep call did.
  struct Sweep {
    std::uint32_t taken = 0;          ///< points written
    std::uint32_t coveredBlocks = 0;  ///< how far the cursor moved, in blocks (≤ sweepBlockCount())
  };
  /// Moves the cursor of queue `q` forward by `minBlocks` blocks of the round (at most one
  /// round) and writes the queue's points in those blocks to `out`, block by whole block,
  /// as far as `out` has room for whole blocks. Each point at most once per call. Over
  /// successive calls every point of the queue comes up in turn; one that is put in the
  /// queue at any time comes up before the cursor has moved a further sweepBlockCount()
  /// blocks.
  Sweep takeSweep(int q, std::uint32_t minBlocks, std::span<std::uint32_t> out) noexcept;

  /// For each of the non-decreasing `blockMarks`, how many points of queue `q` the next
  /// that many blocks of its sweeps (at most a round) hold, into `points`.
  void pointsAhead(int q, std::span<const std::uint32_t> blockMarks,
                   std::span<std::uint32_t> points) const noexcept;

  /// Writes every point of queue `q` in index order to `out`; returns how many.
  std::uint32_t takeAll(int q, std::span<std::uint32_t> out) const noexcept;

private:
  static constexpr std::uint32_t kWordBits = 32;
  static constexpr std::uint32_t kNoRoom = ~0u;
  std::uint32_t* words(int q) noexcept { return &bits_[static_cast<std::size_t>(q) * wordCount_]; }
  const std::uint32_t* words(int q) const noexcept {
    return &bits_[static_cast<std::size_t>(q) * wordCount_];
  }
  std::uint32_t* summary(int q) noexcept { return &summary_[static_cast<std::size_t>(q) * summaryCount_]; }
  const std::uint32_t* summary(int q) const noexcept {
    return &summary_[static_cast<std::size_t>(q) * summaryCount_];
  }
  /// Bit w set: word w of block `block` holds a point of queue `q`.
  std::uint32_t nonEmptyWords(int q, std::uint32_t block) const noexcept;
  /// Points of queue `q` in block `block`.
  std::uint32_t blockPoints(int q, std::uint32_t block) const noexcept;
  /// Writes the points of queue `q` in block `block` to `out` from `at`, if they all fit;
  /// returns how many, or kNoRoom.
  std::uint32_t takeBlock(int q, std::uint32_t block, std::span<std::uint32_t> out,
                          std::uint32_t at) const noexcept;

  std::uint32_t pointCount_;
  std::uint32_t wordCount_;                // 32-point words per queue
  std::uint32_t summaryCount_;             // 32-word summary words per queue
  std::uint32_t blockWords_;               // words per sweep block: a power of two, at most 32
  std::uint32_t blockCount_;               // sweep blocks
  std::vector<std::uint32_t> sweepOrder_;  // the block a sweep visits at each step of its round
  std::vector<std::uint32_t> bits_;
  std::vector<std::uint32_t> summary_;
  std::vector<std::uint32_t> counts_;
  std::vector<std::uint32_t> cursors_;  // per queue, the next step of its sweeps (0 … blockCount_ − 1)
};

}  // namespace voxhap
