#pragma once
/// Whether a haptic thread that was granted SCHED_FIFO keeps it (DESIGN §7). The priority
/// keeps a loop's frames on time against the rest of the system; a loop whose frames
/// overrun is late whatever its priority, never sleeps, and under SCHED_FIFO leaves every
/// ordinary thread on its core (its own peer's comms and front end, the other processes)
/// only the kernel's real-time throttling remainder, 5 % by default: six peers under
/// AddressSanitizer on two cores left a controller unable to answer its front end in 5 s.
/// So a loop whose frames have begun late kLateFramesToGiveUp times in a row gives the
/// priority up, and takes it again once its frames have computed in under half a period
/// kQuickFramesToTakeAgain times in a row (time to spare, whoever else runs).
///
/// Only for a thread that was granted SCHED_FIFO; pure decisions, the haptic loop makes the
/// system calls (realtime.h). Never allocates, locks or throws.

#include <cstdint>

namespace voxhap {

class FifoHold {
public:
  /// 50 ms of late frames at 1 kHz.
  static constexpr std::uint32_t kLateFramesToGiveUp = 50;
  /// 1 s of quick frames at 1 kHz.
  static constexpr std::uint32_t kQuickFramesToTakeAgain = 1000;

  enum class Change : std::uint8_t { None, GiveUp, TakeAgain };

  /// After each frame: whether it began late (it found its deadline gone, so did not sleep)
  /// and whether it computed in under half a period. Returns what the thread should do now.
  Change afterFrame(bool beganLate, bool computedQuickly) noexcept {
    if (held_) {
      late_ = beganLate ? late_ + 1 : 0;
      if (late_ < kLateFramesToGiveUp) return Change::None;
      held_ = false;
      late_ = 0;
      ++givenUp_;
      return Change::GiveUp;
    }
    quick_ = computedQuickly ? quick_ + 1 : 0;
    if (quick_ < kQuickFramesToTakeAgain) return Change::None;
    held_ = true;
    quick_ = 0;
    return Change::TakeAgain;
  }

  /// The system refused to give it back: the thread goes on without it, and asks again after
  /// as many quick frames.
  void refused() noexcept { held_ = false; }

  /// Whether the thread holds it now, by these decisions.
  bool held() const noexcept { return held_; }
  /// How often it was given up.
  std::uint64_t givenUp() const noexcept { return givenUp_; }

private:
  bool held_ = true;
  std::uint32_t late_ = 0;
  std::uint32_t quick_ = 0;
  std::uint64_t givenUp_ = 0;
};

}  // namespace voxhap
