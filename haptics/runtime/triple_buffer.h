#pragma once
/// A triple buffer (DESIGN §7): the haptic thread publishes each frame's snapshot (poses,
/// contacts, statistics) and the comms thread takes the newest complete one at its own rate.
///
/// Threads. One writer thread fills writeBuffer() and calls publish(); one reader thread
/// calls update() and reads readBuffer(). Neither ever waits for the other; all four calls
/// are noexcept, lock-free and allocation-free (T's copies are made once, at construction).
///
/// How it works. Of three buffers the writer owns one and the reader owns one; the third,
/// the middle, is held by an atomic index with a "fresh" bit. publish() swaps the writer's
/// buffer into the middle, marked fresh, and takes the old middle to write next (a snapshot
/// the reader never took is dropped: the newest wins). update() swaps the reader's buffer
/// into the middle when the middle is fresh, and takes the fresh one. Both swaps are one
/// exchange with acq_rel: its release hands over what the side wrote (or finished reading)
/// in the buffer it gives, its acquire sees what the other side did in the one it takes.
/// The reader sees whole snapshots only, each newer than the last.

#include <array>
#include <atomic>
#include <cstdint>

#include "haptics/runtime/cache_line.h"

namespace voxhap {

template <typename T>
class TripleBuffer {
public:
  /// Three copies of `initial`: a snapshot with its vectors already sized for the run, so
  /// that a writer that overwrites them in place never allocates. The reader holds
  /// `initial` until the first update(). Allocates as T's copy does.
  explicit TripleBuffer(const T& initial) : slots_{Slot{initial}, Slot{initial}, Slot{initial}} {}
  TripleBuffer(const TripleBuffer&) = delete;
  TripleBuffer& operator=(const TripleBuffer&) = delete;

  /// Writer only: the buffer for the next snapshot. It holds an older snapshot (or
  /// `initial`), not the last published one: write every field.
  T& writeBuffer() noexcept { return slots_[writeIndex_].value; }

  /// Writer only: makes writeBuffer() the newest snapshot; writeBuffer() is another one then.
  void publish() noexcept {
    writeIndex_ = middle_.exchange(writeIndex_ | kFresh, std::memory_order_acq_rel) & kIndexMask;
  }

  /// Reader only: takes the newest snapshot when one was published since the last call;
  /// returns whether it did (readBuffer() changed).
  bool update() noexcept {
    if ((middle_.load(std::memory_order_relaxed) & kFresh) == 0) return false;
    readIndex_ = middle_.exchange(readIndex_, std::memory_order_acq_rel) & kIndexMask;
    return true;
  }

  /// Reader only: the snapshot taken by the last update() that returned true.
  const T& readBuffer() const noexcept { return slots_[readIndex_].value; }

private:
  // each buffer on its own cache lines, so the two sides' writes never share one
  struct alignas(kCacheLineBytes) Slot {
    T value;
  };
  static constexpr std::uint32_t kIndexMask = 3;
  static constexpr std::uint32_t kFresh = 4;

  std::array<Slot, 3> slots_;
  alignas(kCacheLineBytes) std::uint32_t writeIndex_ = 0;  // the writer's
  alignas(kCacheLineBytes) std::uint32_t readIndex_ = 1;   // the reader's
  alignas(kCacheLineBytes) std::atomic<std::uint32_t> middle_{2};
};

}  // namespace voxhap
