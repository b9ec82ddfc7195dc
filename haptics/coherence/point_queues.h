#pragma once
/// Distance-to-contact queues (paper §5, DESIGN §4.5).
///
/// Every point of a pointshell sits in exactly one queue: queue 0 holds the points in
/// contact (tested every frame), queue i ≥ 1 the points i voxels from contact. Each
/// queue is a bitmap over the whole pointshell, one bit per point, with a second level
/// of one summary bit per 32-bit word, so that a sparse queue is walked by skipping
/// empty words 32 at a time. Each queue keeps its own count and a round-robin cursor.
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

  /// What one takeSweep call did.
  struct Sweep {
    std::uint32_t taken = 0;           ///< points written
    std::uint64_t coveredIndices = 0;  ///< how far the cursor moved, in point indices (≤ pointCount)
  };
  /// Moves the cursor of queue `q` forward (wrapping round) and writes the points it passes
  /// to `out`: at least `minPoints` of them (fewer when the queue holds fewer), and all of
  /// those in the next `minIndices` indices. Each point at most once per call. Over
  /// successive calls every point of the queue comes up in turn; one that is put in the
  /// queue at any time comes up before the cursor has moved a further pointCount() indices.
  Sweep takeSweep(int q, std::uint32_t minPoints, std::uint64_t minIndices,
                  std::span<std::uint32_t> out) noexcept;

  /// Writes every point of queue `q` in index order to `out`; returns how many.
  std::uint32_t takeAll(int q, std::span<std::uint32_t> out) const noexcept;

private:
  static constexpr std::uint32_t kWordBits = 32;
  std::uint32_t* words(int q) noexcept { return &bits_[static_cast<std::size_t>(q) * wordCount_]; }
  const std::uint32_t* words(int q) const noexcept {
    return &bits_[static_cast<std::size_t>(q) * wordCount_];
  }
  std::uint32_t* summary(int q) noexcept { return &summary_[static_cast<std::size_t>(q) * summaryCount_]; }
  const std::uint32_t* summary(int q) const noexcept {
    return &summary_[static_cast<std::size_t>(q) * summaryCount_];
  }
  /// The first point ≥ `from` in queue `q`, or pointCount_ when there is none.
  std::uint32_t nextAtOrAfter(int q, std::uint32_t from) const noexcept;

  std::uint32_t pointCount_;
  std::uint32_t wordCount_;     // 32-point words per queue
  std::uint32_t summaryCount_;  // 32-word summary words per queue
  std::vector<std::uint32_t> bits_;
  std::vector<std::uint32_t> summary_;
  std::vector<std::uint32_t> counts_;
  std::vector<std::uint32_t> cursors_;  // next index to look at, per queue
};

}  // namespace voxhap
