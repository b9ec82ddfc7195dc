#pragma once
/// MaxTravel and the per-queue quotas of time-critical sampling (paper §5 Eqs. 2 and 3,
/// DESIGN §4.5). A point i voxels from contact cannot reach contact before it has moved
/// i·s; if no point moves more than MaxTravel per frame, testing a point of queue i once
/// every i·s / MaxTravel frames is enough. Spending the frame's capacity n_cap on the
/// n_mand points in contact first and on a share of every other queue gives
///
///   (Eq. 2)  MaxTravel = s · (n_cap − n_mand) / Σ_i (n_i / i),   at most `upperBoundM`
///   (Eq. 3)  m_i = ceil(n_i · MaxTravel / (i · s))
///
/// When n_mand ≥ n_cap nothing may move (MaxTravel = 0) and the deadline is missed.
/// Everything here is noexcept and allocation-free.

#include <cmath>
#include <cstdint>
#include <span>

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

/// What Eq. 2 allows this frame.
struct TravelBudget {
  double maxTravelM = 0.0;      ///< most any point may move this frame, m
  bool deadlineMissed = false;  ///< more points in contact than the capacity
};

/// Eq. 2: `queueCounts[i]` points in queue i (index 0, the mandatory queue, is read as
/// n_mand), `capacityTests` point tests fit in a frame, voxel size `voxelSizeM`.
inline TravelBudget maxTravel(double capacityTests, std::span<const std::uint32_t> queueCounts, double voxelSizeM,
                              double upperBoundM) noexcept {
  const double mandatory = queueCounts.empty() ? 0.0 : static_cast<double>(queueCounts[0]);
  if (mandatory >= capacityTests) return {0.0, true};
  double load = 0.0;  // Σ n_i / i
  for (std::size_t i = 1; i < queueCounts.size(); ++i) load += static_cast<double>(queueCounts[i]) / static_cast<double>(i);
  if (load == 0.0) return {upperBoundM, false};
  const double travel = voxelSizeM * (capacityTests - mandatory) / load;
  return {travel < upperBoundM ? travel : upperBoundM, false};
}

/// Eq. 3: how many of the `count` points of queue `i` (≥ 1) to test this frame.
inline std::uint32_t queueQuota(std::uint32_t count, int i, double maxTravelM, double voxelSizeM) noexcept {
  const double share = std::ceil(static_cast<double>(count) * maxTravelM / (static_cast<double>(i) * voxelSizeM));
  return share >= static_cast<double>(count) ? count : static_cast<std::uint32_t>(share);
}

}  // namespace voxhap
