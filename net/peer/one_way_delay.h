#pragma once
/// The one-way delay to a peer (DESIGN §8), from the round trips that its echoes of our
/// send times measure: half the round trip, filtered (each echo weighs kRoundTripWeight),
/// and reported with hysteresis: the reported delay moves to the filtered one only when
/// that leaves a band of ±max(kHysteresisMs, kHysteresisShare of it). The shared coupling's
/// stiffness follows the reported delay (k₀·(1 − τ/1 s), shared_coupling.h), so it steps by
/// at most a few thousandths of k₀ at a time, and not at every echo.

namespace voxhap::net {

class OneWayDelay {
public:
  static constexpr double kRoundTripWeight = 0.1;
  static constexpr double kHysteresisMs = 2.0;
  static constexpr double kHysteresisShare = 0.1;

  /// Adds one measured round trip, ms (≥ 0; a negative or non-finite one is ignored).
  void addRoundTrip(double roundTripMs) noexcept;
  /// The filtered round trip, ms; < 0: none measured yet.
  double roundTripMs() const noexcept { return filteredMs_; }
  /// The reported one-way delay, ms; < 0: none measured yet.
  double oneWayMs() const noexcept { return reportedMs_; }

private:
  double filteredMs_ = -1.0;
  double reportedMs_ = -1.0;
};

}  // namespace voxhap::net
