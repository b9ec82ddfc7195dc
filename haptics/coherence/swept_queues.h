#pragma once
/// Distance-to-contact queues served by sweeps (paper §5 Eq. 3, pair_coherence.h): the
/// members of queue q must be tested again before the pair has moved a distance d_q
/// relative to each other. Each frame the sweep of a queue covers B · T' / d_q of the B
/// blocks of its round (point_queues.h) for the relative travel T' allowed in the frame
/// before, whole blocks, the part of a block covered ahead counting towards the next
/// frame. A member that joins in frame j, tested at relative position o_j, is reached by
/// the first frame m whose start lies further than d_q from there: the frames j + 1 … m
/// cover B · (T_j + … + T_{m−1}) / d_q = B · (o_m − o_j) / d_q > B blocks at least,
/// however the queue fills. So the travel a frame allows sets the next frame's sweeps,
/// and each queue counts beforehand what they would take at a range of travels, for
/// Eq. 2 (max_travel.h).
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
  /// before a relative travel of `distanceM` (≤ 0: all of them, every frame), after a
  /// travel of `lastTravelM` in the frame before. Returns how many.
  std::uint32_t collect(int q, double distanceM, double lastTravelM, std::span<std::uint32_t> out) noexcept;

  /// Adds to `tests[k]` how many members of queue `q` collect() would take in the next
  /// frame if this one, after `lastTravelM` in the frame before, allows a travel of
  /// k / kTravelSteps · `fullTravelM` (`distanceM` > 0; as the queue stands now).
  void addTestsByTravel(int q, double distanceM, double fullTravelM, double lastTravelM,
                        TestsByTravel& tests) const noexcept;

  /// Forgets what the sweeps owe (every member was just tested).
  void clearOwed() noexcept;

private:
  /// Blocks owed once a travel of `travelM` is added to `owedBlocks`.
  double owedAfter(double owedBlocks, double distanceM, double travelM) const noexcept;

  PointQueues queues_;
  std::vector<double> owedBlocks_;  // per queue, blocks its cursor has still to cover (> −1)
};

}  // namespace voxhap
