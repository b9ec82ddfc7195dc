#pragma once
/// MaxTravel and the per-queue quotas of time-critical sampling (paper §5 Eqs. 2 and 3,
/// DESIGN §4.5). If no point moves more than MaxTravel per frame, a point that needs to
/// travel d before it can reach contact need only be tested once every d / MaxTravel
/// frames. Spending the frame's capacity n_cap on the n_mand mandatory points first and on
/// a share of every other queue gives
///
///   (Eq. 2)  MaxTravel = s · (n_cap − n_mand) / Σ_i (n_i / d_i),   at most the upper bound
///   (Eq. 3)  m_i = ceil(n_i · MaxTravel / (d_i · s))
///
/// with d_i the whole voxels a point of queue i must cross before it can reach a voxel of
/// the force layer. The paper writes d_i = i. Our fields hold chessboard distances in whole
/// voxels, and a point anywhere in a voxel one layer beyond the force layer may lie on
/// that layer's boundary: it is 0 voxels from contact, not 1. So queue 1 (value F + 1)
/// is mandatory too and d_i = i − 1; with d_i = i a point of queue 1 tested every other
/// frame at MaxTravel = s/2, or every tenth at s/10, could sit untested in a force-layer
/// voxel (the property test of coherence_test.cpp found it).
///
/// When n_mand ≥ n_cap nothing may move (MaxTravel = 0) and the deadline is missed.
///
/// A point's queue comes from the field it samples, as in the paper. Under geometrical
/// awareness a surface point samples the vertex field, which is far across the middle of
/// a face yet interior (a contact) a voxel past it: such a point can pass from far to
/// contact between two of its tests, once its object's face has sunk through the other's
/// surface voxels. Awareness assumes that this does not happen (vertex and edge contacts
/// keep the surfaces apart, paper §4); when it does, the point's next test finds it, within
/// the travel its queue allowed. Bounding every queue by the surface field as well would
/// make every point within a voxel of the other surface mandatory: half the seated ball
/// of the rotation benchmark. Without awareness the guarantee is exact.
///
/// Several pairs share one capacity: every moving object's MaxTravel is its upper bound
/// times one scale, so that a pair's relative travel per frame is the scale times the sum
/// of its objects' bounds; travelScale() solves Eq. 2 for that scale.
///
/// Eq. 2 as the paper writes it counts n_i · T / d_i tests of queue i, the quota each
/// sweep would take if a queue's members stayed put. They do not: points leave a queue
/// where the sweep tests them and join it anywhere, so the blocks just ahead of a sweep,
/// unvisited for a whole round, hold more of them than the average (1.1 to 1.9 times the
/// quota by queue in the seated 25 mm ball). And a sweep's share is set by the travel of
/// the frame before (swept_queues.h), so the travel a frame allows is what the next frame
/// must test. So each sweep counts what it would take in the next frame for kTravelSteps
/// + 1 travels of this one (SweptQueues::addTestsByTravel), and Eq. 2 takes the largest
/// travel for which those and the mandatory tests fit: from the queues as they stand, no
/// history, no estimate. Everything here is noexcept and allocation-free.

#include <array>
#include <cstddef>
#include <cstdint>

namespace voxhap {

/// The queue of a point whose sampled field value is `value`, for force layer `forceLayer`
/// and largest field value `maxValue`: 0 in contact (1 … forceLayer), value − forceLayer
/// beyond it, and beyond the field's range (far, 0) one queue further out.
inline int queueForValue(std::uint8_t value, std::uint8_t forceLayer, std::uint8_t maxValue) noexcept {
  if (value == 0) return maxValue + 1 - forceLayer;
  return value <= forceLayer ? 0 : value - forceLayer;
}

/// Number of queues for a force layer and largest field value: 0 … maxValue + 1 − forceLayer.
inline int queueCountFor(std::uint8_t forceLayer, std::uint8_t maxValue) noexcept {
  return maxValue + 2 - forceLayer;
}

/// Queues 0 (in contact) and 1 (one layer out, possibly on the force layer's boundary)
/// are tested every frame.
inline constexpr int kMandatoryQueues = 2;

/// d_i: whole voxels a point of queue `i` (≥ kMandatoryQueues) crosses before it can
/// reach the force layer.
inline int voxelsToContact(int i) noexcept {
  return i - 1;
}

/// What Eq. 2 allows this frame, as a fraction of every object's upper bound.
struct TravelBudget {
  double scale = 0.0;           ///< 0 … 1
  bool deadlineMissed = false;  ///< more mandatory tests than the capacity
};

/// Travel scales at which the sweeps count their tests: k / kTravelSteps, k = 0 … kTravelSteps.
inline constexpr int kTravelSteps = 32;
/// Tests beyond the mandatory ones at each of those scales, non-decreasing.
using TestsByTravel = std::array<double, kTravelSteps + 1>;

/// Eq. 2 over all pairs: `capacityTests` point tests fit in a frame, `mandatoryTests` must
/// be done, and `tests[k]` more are taken (in the next frame) at scale k / kTravelSteps.
/// The largest scale whose tests fit, linear between the counted scales (a frame may take
/// up to one step's tests over the capacity).
inline TravelBudget travelScale(double capacityTests, double mandatoryTests,
                                const TestsByTravel& tests) noexcept {
  if (mandatoryTests >= capacityTests) return {0.0, true};
  const double room = capacityTests - mandatoryTests;
  if (tests[kTravelSteps] <= room) return {1.0, false};
  int k = 0;
  while (tests[static_cast<std::size_t>(k + 1)] <= room) ++k;
  const double below = tests[static_cast<std::size_t>(k)];
  const double above = tests[static_cast<std::size_t>(k + 1)];
  const double within = below >= room ? 0.0 : (room - below) / (above - below);
  return {(k + within) / kTravelSteps, false};
}

}  // namespace voxhap
