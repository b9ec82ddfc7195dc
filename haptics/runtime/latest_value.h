#pragma once
/// A latest-value mailbox (DESIGN §7: a device thread's newest sample for the haptic
/// thread): a seqlock over a small trivially copyable T with a version, so that a reader
/// knows whether the value is new to it.
///
/// Threads. One writer thread calls publish(); any number of reader threads call
/// readNewer(). Both are noexcept, lock-free and allocation-free. The writer never waits.
/// A reader never sees a torn value and never waits for the writer either: when its read
/// overlaps a write it tries again, at most kReadAttempts times, then gives up and keeps
/// what it has (a writer preempted mid-write cannot hold a real-time reader).
///
/// How it works. The sequence counter is odd while a write is in progress; its half is the
/// version, the number of completed writes. The value lives in 64-bit atomic words, so that
/// a read overlapping a write is no data race (and ThreadSanitizer sees every ordering):
///   writer: seq = s + 1 (relaxed); each word stored with release; seq = s + 2 (release).
///   reader: s1 = seq (acquire), even; each word loaded with acquire; s2 = seq (relaxed);
///           the copy is whole when s1 == s2.
/// If a reader loads a word of a later write, that word's release carries the writer's
/// earlier odd store of seq, so the reader's later load of seq reads it or something newer:
/// s2 != s1. If it loads none, the acquire of s1 saw the stores of the write s1 ended and no
/// word older than them. No std::atomic_thread_fence is needed (ThreadSanitizer does not
/// model fences). Meant for a few words: every word is one atomic load and store.

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <type_traits>

namespace voxhap {

template <typename T>
class LatestValue {
  static_assert(std::is_trivially_copyable_v<T>, "the value is copied through atomic words as bytes");

public:
  /// How many times readNewer() tries before it gives up on reads that overlap writes.
  static constexpr int kReadAttempts = 4;

  /// An empty mailbox: version 0, nothing to read yet.
  LatestValue() noexcept = default;
  LatestValue(const LatestValue&) = delete;
  LatestValue& operator=(const LatestValue&) = delete;

  /// Writer only: makes `value` the newest, with the next version.
  void publish(const T& value) noexcept {
    std::array<std::uint64_t, kWords> bytes{};
    std::memcpy(bytes.data(), std::addressof(value), sizeof(T));
    const std::uint64_t s = seq_.load(std::memory_order_relaxed);
    seq_.store(s + 1, std::memory_order_relaxed);
    for (std::size_t i = 0; i < kWords; ++i) words_[i].store(bytes[i], std::memory_order_release);
    seq_.store(s + 2, std::memory_order_release);
  }

  /// Reader: when the newest value's version is above `version`, copies the value into
  /// `out`, sets `version` to its version and returns true. Returns false, with `out` and
  /// `version` untouched, when nothing newer was published, or when every attempt
  /// overlapped a write (the newer value is there for a later call).
  bool readNewer(std::uint64_t& version, T& out) const noexcept {
    for (int attempt = 0; attempt < kReadAttempts; ++attempt) {
      const std::uint64_t s1 = seq_.load(std::memory_order_acquire);
      if (s1 % 2 == 1) continue;
      if (s1 / 2 <= version) return false;
      std::array<std::uint64_t, kWords> bytes;
      for (std::size_t i = 0; i < kWords; ++i) bytes[i] = words_[i].load(std::memory_order_acquire);
      if (seq_.load(std::memory_order_relaxed) != s1) continue;
      std::memcpy(static_cast<void*>(std::addressof(out)), bytes.data(), sizeof(T));
      version = s1 / 2;
      return true;
    }
    return false;
  }

  /// How many values have been published (the newest one's version; 0: none yet).
  std::uint64_t version() const noexcept { return seq_.load(std::memory_order_acquire) / 2; }

private:
  static constexpr std::size_t kWords = (sizeof(T) + sizeof(std::uint64_t) - 1) / sizeof(std::uint64_t);
  static_assert(std::atomic<std::uint64_t>::is_always_lock_free);

  std::atomic<std::uint64_t> seq_{0};
  std::array<std::atomic<std::uint64_t>, kWords> words_{};
};

}  // namespace voxhap
