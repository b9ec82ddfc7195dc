#pragma once
/// A second thread that takes a share of a frame's work (issue 13: a second, pinned worker
/// for point tests where there is a spare core).
///
/// The haptic thread hands it one job at a time (run), does its own share meanwhile and
/// waits for it (finish). Neither call allocates, locks, throws or blocks: the helper
/// spins on an atomic while frames come, so that a job starts within a fraction of a
/// microsecond, and it sleeps (a futex wait) after kIdleBeforeSleep without one; only
/// the first job after such a sleep costs the haptic thread a wake-up system call. It
/// takes a whole core while frames run: it is for machines with one to spare.
///
/// Pinned to the last CPU that the making thread may run on, and that thread (make the
/// helper on the haptic thread) kept off it until the helper is destroyed on it, so that
/// the two never share a core; with only one CPU the constructor refuses (there is no
/// spare core).

#include <atomic>
#include <chrono>
#include <cstdint>
#include <thread>

#include <pthread.h>
#include <sched.h>

#include "haptics/runtime/cache_line.h"

namespace voxhap {

class FrameHelper {
public:
  /// How long the helper spins without a job before it sleeps.
  static constexpr std::chrono::milliseconds kIdleBeforeSleep{50};

  /// Starts the thread and pins it, and keeps the calling thread off its CPU. Throws Error
  /// when the caller may run on a single CPU or the threads cannot be pinned.
  FrameHelper();
  /// Waits for the job in hand, if any, stops and joins the thread; on the thread that made
  /// it, gives that thread its CPUs back.
  ~FrameHelper();
  FrameHelper(const FrameHelper&) = delete;
  FrameHelper& operator=(const FrameHelper&) = delete;

  /// The CPU the helper runs on.
  int cpu() const noexcept { return cpu_; }

  /// Starts `job()` on the helper and returns at once; `job` must live until finish().
  /// One job at a time: call finish() before the next run().
  template <typename Job>
  void run(Job& job) noexcept {
    post(&job, [](void* j) { (*static_cast<Job*>(j))(); });
  }
  /// Returns once the job of the last run() has returned (spinning).
  void finish() noexcept;

private:
  void post(void* job, void (*call)(void*)) noexcept;
  void loop() noexcept;

  int cpu_ = -1;
  pthread_t maker_;
  cpu_set_t makerCpus_;  // before the helper
  void* job_ = nullptr;
  void (*call_)(void*) = nullptr;
  alignas(kCacheLineBytes) std::atomic<std::uint32_t> posted_{0};  // jobs posted; +1 also to stop
  std::atomic<bool> sleeping_{false};
  bool stop_ = false;  // written before the post that stops, read after it
  alignas(kCacheLineBytes) std::atomic<std::uint32_t> done_{0};  // jobs finished
  std::thread thread_;
};

}  // namespace voxhap
