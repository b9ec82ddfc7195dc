#include "haptics/runtime/frame_clock.h"

#include <cassert>
#include <cerrno>
#include <ctime>

namespace voxhap {
namespace {

constexpr std::int64_t kNsPerS = 1'000'000'000;

}  // namespace

std::int64_t MonotonicTime::nowNs() noexcept {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return static_cast<std::int64_t>(t.tv_sec) * kNsPerS + t.tv_nsec;
}

void MonotonicTime::sleepUntilNs(std::int64_t deadlineNs) noexcept {
  timespec t{};
  t.tv_sec = static_cast<time_t>(deadlineNs / kNsPerS);
  t.tv_nsec = static_cast<long>(deadlineNs % kNsPerS);
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &t, nullptr) == EINTR) {
  }
}

TimeSource& monotonicTime() noexcept {
  static MonotonicTime time;
  return time;
}

DeadlineAdvance advanceDeadline(std::int64_t deadlineNs, std::int64_t beganNs,
                                std::int64_t periodNs) noexcept {
  const std::int64_t lateNs = beganNs - deadlineNs;
  if (lateNs <= periodNs) return {deadlineNs + periodNs, 0};
  return {beganNs + periodNs, static_cast<std::uint64_t>(lateNs / periodNs)};
}

FrameClock::FrameClock(std::int64_t periodNs, std::int64_t spinNs, TimeSource& time) noexcept
    : time_(&time), periodNs_(periodNs), spinNs_(spinNs) {
  assert(periodNs > 0 && spinNs >= 0);
}

FrameTick FrameClock::waitForFrame() noexcept {
  std::int64_t now = time_->nowNs();
  if (!started_) {
    started_ = true;
    deadlineNs_ = now;
    previousBeganNs_ = now;
  }
  while (now < deadlineNs_ - spinNs_) {
    time_->sleepUntilNs(deadlineNs_ - spinNs_);
    now = time_->nowNs();
  }
  while (now < deadlineNs_) now = time_->nowNs();
  const DeadlineAdvance next = advanceDeadline(deadlineNs_, now, periodNs_);
  const FrameTick tick{now, deadlineNs_, now - previousBeganNs_, next.skippedPeriods};
  deadlineNs_ = next.nextDeadlineNs;
  previousBeganNs_ = now;
  skippedPeriods_ += next.skippedPeriods;
  return tick;
}

}  // namespace voxhap
