#pragma once
/// Distance-to-contact queues served by sweeps (paper §5 Eq. 3, pair_coherence.h): the
/// members of queue q must be tested again before the pair has moved a distance d_q
/// relative to each other. Each frame the sweep of a queue covers B · T / d_q of the B
/// blocks of its round (point_queues.h) for the relative travel T this frame, whole
/// blocks, the part of a block covered ahead counting towards the next frame. A member
/// that joined at any time is therefore reached before the pair has moved d_q from where
/// it was tested, however the queue fills. Before the frame, each queue counts what it
/// would take at a range of travels, for Eq. 2 (max_travel.h).
///
/// Sized once (allocates); every other call is noexcept and allocation-free.

#include <cstdint>
#include <span>
#include <vector>

#include "haptics/coherence/max_travel.h"
#include "haptics/coherence/point_queues.h"

namespace voxhap {

class SweptQueues {
public:
  SweptQueues(std::uint32_t memberCount, int queueCount);

  PointQueues& queues() noexcept { return queues_; }
  const PointQueues& queues() const noexcept { return queues_; }

  /// Collects members of queue `q` into `out`, for a queue whose members must be tested
  /// before a relative travel of `distanceM` (≤ 0: all of them, every frame) and a travel
  /// of `travelM` this frame. Returns how many.
  std::uint32_t collect(int q, double distanceM, double travelM, std::span<std::uint32_t> out) noexcept;

  /// Adds to `tests[k]` how many members of queue `q` collect() would take at a travel of
  /// k / kTravelSteps · `fullTravelM` this frame (`distanceM` > 0).
  void addTestsByTravel(int q, double distanceM, double fullTravelM, TestsByTravel& tests) const noexcept;

  /// Forgets what the sweeps owe (every member was just tested).
  void clearOwed() noexcept;

private:
  /// What queue `q` owes once a travel of `travelM` this frame is added.
  double owedAfter(int q, double distanceM, double travelM) const noexcept;

  PointQueues queues_;
  std::vector<double> owedBlocks_;  // per queue, blocks its cursor has still to cover (> −1)
};

}  // namespace voxhap
