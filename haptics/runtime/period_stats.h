#pragma once
/// Statistics of durations measured every frame (DESIGN §7): the haptic thread's period
/// (from one frame's start to the next) and the compute time of each frame. A fixed
/// histogram of 1 µs bins up to kRangeNs, an overflow count, the exact minimum, maximum
/// and mean, and the overruns (durations over a threshold). record() is noexcept and
/// allocation-free and the whole object is trivially copyable, so that the haptic thread
/// may publish a copy (or its summary()) in a snapshot; merge() adds another's samples.

#include <array>
#include <cstdint>

namespace voxhap {

/// The figures of a PeriodStats, for a snapshot or a report. Percentiles as percentileNs.
struct PeriodSummary {
  std::uint64_t count = 0;     ///< samples
  std::uint64_t overruns = 0;  ///< samples over the overrun threshold
  std::int64_t minNs = 0;      ///< 0 without samples
  std::int64_t p50Ns = 0;
  std::int64_t p99Ns = 0;
  std::int64_t p999Ns = 0;
  std::int64_t maxNs = 0;
  double meanNs = 0.0;
};

class PeriodStats {
public:
  /// Width of a histogram bin, ns.
  static constexpr std::int64_t kBinNs = 1'000;
  /// Durations at or above this are counted in the overflow, ns.
  static constexpr std::int64_t kRangeNs = 4'000'000;
  static constexpr std::size_t kBins = static_cast<std::size_t>(kRangeNs / kBinNs);

  /// No samples; a duration over `overrunNs` is an overrun.
  explicit PeriodStats(std::int64_t overrunNs) noexcept : overrunNs_(overrunNs) {}

  /// Adds one duration, ns (a negative one, from a clock that stepped back, counts as 0).
  void record(std::int64_t durationNs) noexcept;
  /// Adds every sample of `other`, which must have the same overrun threshold.
  void merge(const PeriodStats& other) noexcept;
  /// Forgets every sample.
  void reset() noexcept { *this = PeriodStats(overrunNs_); }

  std::uint64_t count() const noexcept { return count_; }
  std::uint64_t overruns() const noexcept { return overruns_; }
  /// Samples at or above kRangeNs.
  std::uint64_t overflow() const noexcept { return overflow_; }
  std::int64_t overrunNs() const noexcept { return overrunNs_; }
  /// Exact extremes and mean of the samples, ns (0 without samples).
  std::int64_t minNs() const noexcept { return count_ ? minNs_ : 0; }
  std::int64_t maxNs() const noexcept { return maxNs_; }
  double meanNs() const noexcept;

  /// The duration below or at which a `fraction` (0 … 1) of the samples lie, by the
  /// histogram: the nearest-rank sample v (the ceil(fraction · count)-th smallest, at least
  /// the first) rounded up to its bin's upper edge, but never above the maximum; so within
  /// [v, v + kBinNs]. A rank in the overflow gives the maximum. 0 without samples. Reads
  /// every bin up to the rank's.
  std::int64_t percentileNs(double fraction) const noexcept;
  /// count, overruns, min, p50, p99, p99.9, max and mean in one pass over the bins.
  PeriodSummary summary() const noexcept;

private:
  std::array<std::uint64_t, kBins> bins_{};
  std::uint64_t count_ = 0;
  std::uint64_t overflow_ = 0;
  std::uint64_t overruns_ = 0;
  std::int64_t overrunNs_;
  std::int64_t minNs_ = 0;
  std::int64_t maxNs_ = 0;
  std::int64_t sumNs_ = 0;
};

}  // namespace voxhap
