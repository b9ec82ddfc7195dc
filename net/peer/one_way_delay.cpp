#include "net/peer/one_way_delay.h"

#include <algorithm>
#include <cmath>

namespace voxhap::net {

void OneWayDelay::addRoundTrip(double roundTripMs) noexcept {
  if (!std::isfinite(roundTripMs) || roundTripMs < 0.0) return;
  filteredMs_ = filteredMs_ < 0.0 ? roundTripMs
                                  : (1.0 - kRoundTripWeight) * filteredMs_ + kRoundTripWeight * roundTripMs;
  const double oneWayMs = 0.5 * filteredMs_;
  const double bandMs = std::max(kHysteresisMs, kHysteresisShare * reportedMs_);
  if (reportedMs_ < 0.0 || std::abs(oneWayMs - reportedMs_) > bandMs) reportedMs_ = oneWayMs;
}

}  // namespace voxhap::net
