#pragma once
/// Time-critical sampling of one pair (paper §5, DESIGN §4.5): which of the pointshell's
/// points to test this frame, and where each goes after its test.
///
/// Every point sits in one distance-to-contact queue (PointQueues, max_travel.h). A frame
///   1. reads the queue counts (Eq. 2 is solved over all pairs by the caller);
///   2. collects the due points: all of the mandatory queues and, from every other queue,
///      a sweep of its cursor;
///   3. tests them, writes the contacts and moves each point to the queue of its new value.
/// Collecting before testing keeps a point that changes queue from being tested twice.
///
/// The sweep of queue i takes at least the Eq. 3 quota m_i = ceil(n_i · T / (d_i · s)),
/// as the paper does, and covers at least pointCount · T' / (d_i · s) indices, T' being
/// the relative travel allowed in the frame before (the motion since the last test). The
/// second is ours: by quota alone a point waits while others join the queue ahead of the
/// cursor, and in a random-motion test one waited 6 frames where its 2 voxels allowed 4
/// and was found in contact untested. By indices, a point joining the queue at any time
/// is reached once the cursor has covered every index, i.e. before the pair has moved
/// d_i · s, however the queue fills and however MaxTravel changes. Where a queue's points
/// crowd into a run of indices, a frame may take more than its quota.
///
/// Out of range (the pointshell wholly outside the voxmap's grid) every point is far: it
/// goes to the far queue when the pair leaves range. A new pair, and one whose force layer
/// changed, has every point mandatory until tested (sortAll() does it at load time).
///
/// Built once per pair (allocates); the frame calls are noexcept and allocation-free.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "haptics/coherence/point_queues.h"
#include "haptics/collide/point_sampler.h"

namespace voxhap {

class PairCoherence {
public:
  /// For a pointshell of `pointCount` points against voxels whose largest value is
  /// `maxValue`, with force layer `forceLayer`.
  PairCoherence(std::uint32_t pointCount, std::uint8_t forceLayer, std::uint8_t maxValue);

  const PointQueues& queues() const noexcept { return queues_; }
  std::uint8_t forceLayer() const noexcept { return forceLayer_; }

  /// Tests every point and puts it in the queue of its value (load time: a whole
  /// pointshell's worth of tests).
  void sortAll(const Pointshell& shell, const Voxmap& voxmap, const VoxelTransform& transform,
               const std::array<std::uint8_t, 3>& fieldShifts) noexcept;
  /// A frame out of range in which the pair may move `relativeTravelM`: every point is far.
  void skipFrame(double relativeTravelM) noexcept;
  /// Makes every point mandatory, to be re-sorted by its next test (a new force layer).
  void setForceLayer(std::uint8_t forceLayer) noexcept;

  /// Step 2: collects the due points into `due` (room for the pointshell) for a relative
  /// travel of at most `relativeTravelM` this frame; returns how many.
  std::uint32_t collectDue(double relativeTravelM, double voxelSizeM, std::span<std::uint32_t> due) noexcept;

  /// Step 3: tests the points collectDue() returned; writes those whose value lies in
  /// [1, sampledLayer] to `contacts` (room for due.size()) and returns how many.
  std::uint32_t testDue(const Pointshell& shell, const Voxmap& voxmap, const VoxelTransform& transform,
                        const std::array<std::uint8_t, 3>& fieldShifts, std::uint8_t sampledLayer,
                        std::span<const std::uint32_t> due, PointContact* contacts) noexcept;

private:
  PointQueues queues_;
  std::uint8_t forceLayer_;
  std::uint8_t maxValue_;
  std::vector<std::uint32_t> dueEndByQueue_;  // collectDue's output: queue q's points end here
  std::vector<double> owedIndices_;           // per queue, indices its cursor has still to cover
  double lastTravelM_ = 0.0;                  // relative travel allowed in the frame before
  bool inRange_ = true;
};

}  // namespace voxhap
