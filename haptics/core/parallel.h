#pragma once
/// A minimal parallel-for for load-time work (voxelizing, building pointshells).
/// Items are handed out through an atomic counter; callers make each item's result
/// independent of the thread that computed it, so output is deterministic.
/// Never used in the 1 kHz frame.

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "haptics/core/progress.h"

namespace voxhap {

/// Threads to use when the caller asks for 0 ("all cores").
inline int defaultThreadCount() {
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

/// Calls `body(i)` for i in [0, count) on up to `threads` threads (0: all cores).
/// `progress`, if set, is called from the calling thread only, with the fraction of
/// items finished. Rethrows the first exception a body threw, after all threads stopped.
template <typename Body>
void parallelFor(std::size_t count, int threads, Body&& body, const ProgressFn& progress = {}) {
  const int n = static_cast<int>(
      std::min<std::size_t>(count, static_cast<std::size_t>(threads > 0 ? threads : defaultThreadCount())));
  std::atomic<std::size_t> next{0};
  std::atomic<std::size_t> finished{0};
  std::exception_ptr failure;
  std::mutex failureMutex;
  auto work = [&](bool reports) {
    try {
      for (std::size_t i = next++; i < count; i = next++) {
        body(i);
        const std::size_t f = ++finished;
        if (reports && progress) progress(static_cast<double>(f) / static_cast<double>(count));
      }
    } catch (...) {
      std::lock_guard lock(failureMutex);
      if (!failure) failure = std::current_exception();
      next = count;
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < n; ++t) pool.emplace_back(work, false);
  work(true);
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace voxhap
