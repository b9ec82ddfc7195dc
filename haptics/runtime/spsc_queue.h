#pragma once
/// A bounded single-producer single-consumer queue of trivially copyable items (DESIGN §7:
/// the comms thread's commands to the haptic thread).
///
/// Threads. One producer thread calls tryPush(), one consumer thread calls tryPop(); either
/// may be the real-time thread. Both are noexcept, lock-free and allocation-free and never
/// wait: a full queue refuses the item (the producer counts or reports the drop), an empty
/// one gives nothing.
///
/// How it works. The slots form a ring of a power-of-two capacity, indexed by two unsigned
/// counters that only grow (their difference stays right when they wrap): tail_, the next
/// slot to write, is stored only
/// by the producer; head_, the next slot to read, only by the consumer. The producer writes
/// the slot, then stores tail_ with release; the consumer's acquire load of tail_ then sees
/// the slot written. Symmetrically, the consumer reads the slot before its release store of
/// head_, so the producer's acquire load of head_ tells it the slot may be overwritten. Each
/// side keeps its last view of the other's counter and reloads it only when the ring looks
/// full (or empty), and each side's counters sit on their own cache line.

#include <atomic>
#include <bit>
#include <cassert>
#include <cstddef>
#include <type_traits>
#include <vector>

#include "haptics/runtime/cache_line.h"

namespace voxhap {

template <typename T>
class SpscQueue {
  static_assert(std::is_trivially_copyable_v<T>, "items are copied in and out of the ring as bytes");
  static_assert(std::is_default_constructible_v<T>, "the ring is built of default-constructed items");

public:
  /// An empty queue with room for `capacity` items, a power of two. Allocates.
  explicit SpscQueue(std::size_t capacity) : slots_(capacity), mask_(capacity - 1) {
    assert(std::has_single_bit(capacity) && "SpscQueue capacity must be a power of two");
  }
  SpscQueue(const SpscQueue&) = delete;
  SpscQueue& operator=(const SpscQueue&) = delete;

  /// How many items fit.
  std::size_t capacity() const noexcept { return slots_.size(); }

  /// Producer only: appends a copy of `item`; false, and nothing written, when full.
  bool tryPush(const T& item) noexcept {
    const std::size_t tail = tail_.load(std::memory_order_relaxed);
    if (tail - producerHead_ == slots_.size()) {
      producerHead_ = head_.load(std::memory_order_acquire);
      if (tail - producerHead_ == slots_.size()) return false;
    }
    slots_[tail & mask_] = item;
    tail_.store(tail + 1, std::memory_order_release);
    return true;
  }

  /// Consumer only: moves the oldest item into `out`; false, and `out` untouched, when empty.
  bool tryPop(T& out) noexcept {
    const std::size_t head = head_.load(std::memory_order_relaxed);
    if (head == consumerTail_) {
      consumerTail_ = tail_.load(std::memory_order_acquire);
      if (head == consumerTail_) return false;
    }
    out = slots_[head & mask_];
    head_.store(head + 1, std::memory_order_release);
    return true;
  }

private:
  std::vector<T> slots_;  // sized once; read and written by both sides, never resized
  std::size_t mask_;
  // the consumer's line: its counter and its view of the producer's
  alignas(kCacheLineBytes) std::atomic<std::size_t> head_{0};
  std::size_t consumerTail_ = 0;
  // the producer's line
  alignas(kCacheLineBytes) std::atomic<std::size_t> tail_{0};
  std::size_t producerHead_ = 0;
};

}  // namespace voxhap
