#pragma once
/// The haptic thread's frame clock (DESIGN §7): frames begin on absolute deadlines one
/// period apart. waitForFrame() sleeps with clock_nanosleep(CLOCK_MONOTONIC,
/// TIMER_ABSTIME) until shortly before the deadline, then spins to it; sleeping to an
/// absolute time keeps a late wake-up from delaying every later frame. After a stall (the
/// frame begins more than one whole period past its deadline) the next deadline is re-synced
/// to one period after now, instead of running the missed frames back to back, and the
/// periods skipped are counted. The deadline arithmetic is advanceDeadline(), a pure
/// function; the clock is a TimeSource, which tests replace with a fake one.
///
/// Threads: a FrameClock belongs to the thread that waits on it. Nothing here allocates,
/// locks or throws; the wait makes the clock_nanosleep call and reads the vDSO clock.

#include <cstdint>

namespace voxhap {

/// Where deadlines come from: monotonic time and a sleep to an absolute time.
class TimeSource {
public:
  virtual ~TimeSource() = default;
  /// Now, ns on the monotonic clock.
  virtual std::int64_t nowNs() noexcept = 0;
  /// Sleeps until nowNs() reaches `deadlineNs`, or less (the caller checks the time again).
  virtual void sleepUntilNs(std::int64_t deadlineNs) noexcept = 0;
};

/// CLOCK_MONOTONIC through clock_gettime and clock_nanosleep(TIMER_ABSTIME). Stateless.
class MonotonicTime final : public TimeSource {
public:
  std::int64_t nowNs() noexcept override;
  /// Sleeps again after a signal, to the same absolute time.
  void sleepUntilNs(std::int64_t deadlineNs) noexcept override;
};

/// The system's monotonic clock, for every FrameClock that is not under test.
TimeSource& monotonicTime() noexcept;

/// The deadline after a frame that began at `beganNs` for `deadlineNs`.
struct DeadlineAdvance {
  std::int64_t nextDeadlineNs = 0;
  std::uint64_t skippedPeriods = 0;  ///< whole periods with no frame, 0 without a stall
};

/// Next deadline for frames every `periodNs` (> 0), the current one's `deadlineNs` and its
/// start `beganNs`: deadlineNs + periodNs while the frame began at most one whole period
/// late (a frame late by less keeps the grid and the next one may begin at once); after a
/// stall, beganNs + periodNs, with skippedPeriods = the whole periods it was late.
DeadlineAdvance advanceDeadline(std::int64_t deadlineNs, std::int64_t beganNs,
                                std::int64_t periodNs) noexcept;

/// When one frame began, as waitForFrame() returns it.
struct FrameTick {
  std::int64_t beganNs = 0;          ///< by the time source
  std::int64_t deadlineNs = 0;       ///< the deadline it waited for
  std::int64_t sincePreviousNs = 0;  ///< from the previous frame's beganNs (0 for the first)
  std::uint64_t skippedPeriods = 0;  ///< skipped after this frame began (advanceDeadline)
};

class FrameClock {
public:
  /// How long before a deadline the wait stops sleeping and spins, by default, ns.
  static constexpr std::int64_t kDefaultSpinNs = 100'000;

  /// Frames every `periodNs` (> 0), spinning the last `spinNs` (≥ 0) before each deadline,
  /// by `time`, which must outlive the clock. The first waitForFrame() starts the grid.
  explicit FrameClock(std::int64_t periodNs, std::int64_t spinNs = kDefaultSpinNs,
                      TimeSource& time = monotonicTime()) noexcept;

  /// Waits for the next frame's deadline and returns when it began; the first call
  /// returns at once, its time the first deadline.
  FrameTick waitForFrame() noexcept;
  /// The next frame's deadline, ns (meaningful after the first waitForFrame()).
  std::int64_t nextDeadlineNs() const noexcept { return deadlineNs_; }
  /// Periods skipped by every re-sync so far.
  std::uint64_t skippedPeriods() const noexcept { return skippedPeriods_; }
  std::int64_t periodNs() const noexcept { return periodNs_; }

private:
  TimeSource* time_;
  std::int64_t periodNs_;
  std::int64_t spinNs_;
  std::int64_t deadlineNs_ = 0;
  std::int64_t previousBeganNs_ = 0;
  std::uint64_t skippedPeriods_ = 0;
  bool started_ = false;
};

}  // namespace voxhap
