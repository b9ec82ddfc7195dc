#include "haptics/runtime/period_stats.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace voxhap {
namespace {

/// The nearest rank of `fraction` among `count` samples, 1 … count. The small tolerance
/// keeps a product such as 0.999 · 1000 that rounds a hair above 999 at rank 999.
std::uint64_t rankOf(double fraction, std::uint64_t count) {
  const double f = std::clamp(std::isnan(fraction) ? 0.0 : fraction, 0.0, 1.0);
  const double rank = std::ceil(f * static_cast<double>(count) - 1e-9);
  return std::clamp(static_cast<std::uint64_t>(std::max(rank, 1.0)), std::uint64_t{1}, count);
}

/// The upper edge of histogram bin `bin`, ns.
std::int64_t binTopNs(std::size_t bin) {
  return static_cast<std::int64_t>(bin + 1) * PeriodStats::kBinNs;
}

}  // namespace

void PeriodStats::record(std::int64_t durationNs) noexcept {
  const std::int64_t d = std::max<std::int64_t>(durationNs, 0);
  minNs_ = count_ == 0 ? d : std::min(minNs_, d);
  maxNs_ = std::max(maxNs_, d);
  sumNs_ += d;
  ++count_;
  overruns_ += d > overrunNs_ ? 1 : 0;
  if (d >= kRangeNs) {
    ++overflow_;
  } else {
    ++bins_[static_cast<std::size_t>(d / kBinNs)];
  }
}

void PeriodStats::merge(const PeriodStats& other) noexcept {
  assert(other.overrunNs_ == overrunNs_ && "merged PeriodStats count overruns alike");
  if (other.count_ == 0) return;
  for (std::size_t b = 0; b < kBins; ++b) bins_[b] += other.bins_[b];
  minNs_ = count_ == 0 ? other.minNs_ : std::min(minNs_, other.minNs_);
  maxNs_ = std::max(maxNs_, other.maxNs_);
  sumNs_ += other.sumNs_;
  count_ += other.count_;
  overflow_ += other.overflow_;
  overruns_ += other.overruns_;
}

double PeriodStats::meanNs() const noexcept {
  return count_ ? static_cast<double>(sumNs_) / static_cast<double>(count_) : 0.0;
}

std::int64_t PeriodStats::percentileNs(double fraction) const noexcept {
  if (count_ == 0) return 0;
  const std::uint64_t rank = rankOf(fraction, count_);
  std::uint64_t below = 0;
  for (std::size_t b = 0; b < kBins; ++b) {
    below += bins_[b];
    if (below >= rank) return std::min(binTopNs(b), maxNs_);
  }
  return maxNs_;
}

PeriodSummary PeriodStats::summary() const noexcept {
  PeriodSummary s;
  s.count = count_;
  s.overruns = overruns_;
  s.minNs = minNs();
  s.maxNs = maxNs_;
  s.meanNs = meanNs();
  if (count_ == 0) return s;
  // the three ranks in increasing order, each found in the same pass over the bins
  const std::uint64_t ranks[] = {rankOf(0.5, count_), rankOf(0.99, count_), rankOf(0.999, count_)};
  std::int64_t* values[] = {&s.p50Ns, &s.p99Ns, &s.p999Ns};
  std::size_t next = 0;
  std::uint64_t below = 0;
  for (std::size_t b = 0; b < kBins && next < 3; ++b) {
    below += bins_[b];
    while (next < 3 && below >= ranks[next]) {
      *values[next++] = std::min(binTopNs(b), maxNs_);
    }
  }
  while (next < 3) *values[next++] = maxNs_;
  return s;
}

}  // namespace voxhap
