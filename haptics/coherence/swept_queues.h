#pragma once
/// Distance-to-contact queues served by sweeps (paper §5 Eq. 3, pair_coherence.h): the
/// members of queue q must be tested again before the pair has moved a distance d_q
/// relative to each other. Each frame the sweep of a queue takes at least the paper's
/// quota, ceil(n_q · T / d_q) for a relative travel T this frame, and covers at least
/// memberCount · T' / d_q indices for the travel T' allowed in the frame before, so that a
/// member that joined at any time is reached before the pair has moved d_q, however the
/// queue fills.
///
/// Sized once (allocates); every other call is noexcept and allocation-free.

#include <cstdint>
#include <span>
#include <vector>

#include "haptics/coherence/point_queues.h"

namespace voxhap {

class SweptQueues {
public:
  SweptQueues(std::uint32_t memberCount, int queueCount);

  PointQueues& queues() noexcept { return queues_; }
  const PointQueues& queues() const noexcept { return queues_; }

  /// Collects members of queue `q` into `out`, for a queue whose members must be tested
  /// before a relative travel of `distanceM` (≤ 0: all of them, every frame), a travel of
  /// `travelM` this frame and `lastTravelM` in the frame before. Returns how many.
  std::uint32_t collect(int q, double distanceM, double travelM, double lastTravelM,
                        std::span<std::uint32_t> out) noexcept;

  /// Forgets what the sweeps owe (every member was just tested).
  void clearOwed() noexcept;

private:
  PointQueues queues_;
  std::vector<double> owedIndices_;  // per queue, indices its cursor has still to cover
};

}  // namespace voxhap
