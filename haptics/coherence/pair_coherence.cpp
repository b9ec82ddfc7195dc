#include "haptics/coherence/pair_coherence.h"

#include <algorithm>
#include <cmath>

#include "haptics/coherence/max_travel.h"

namespace voxhap {

// Room for the queues of the lowest force layer, so that setForceLayer never allocates.
PairCoherence::PairCoherence(std::uint32_t pointCount, std::uint8_t forceLayer, std::uint8_t maxValue)
    : queues_(pointCount, queueCountFor(1, maxValue)),
      forceLayer_(forceLayer),
      maxValue_(maxValue),
      dueEndByQueue_(static_cast<std::size_t>(queueCountFor(1, maxValue)), 0),
      owedIndices_(static_cast<std::size_t>(queueCountFor(1, maxValue)), 0.0) {
  queues_.assignAll(1);
}

void PairCoherence::sortAll(const Pointshell& shell, const Voxmap& voxmap, const VoxelTransform& transform,
                            const std::array<std::uint8_t, 3>& fieldShifts) noexcept {
  queues_.assignAll(1);
  for (std::uint32_t point = 0; point < queues_.pointCount(); ++point) {
    const PointSample sample = samplePointAt(shell, voxmap, transform, fieldShifts, point);
    queues_.move(point, 1, queueForValue(sample.value, forceLayer_, maxValue_));
  }
  std::fill(owedIndices_.begin(), owedIndices_.end(), 0.0);
  lastTravelM_ = 0.0;
  inRange_ = true;
}

void PairCoherence::skipFrame(double relativeTravelM) noexcept {
  if (inRange_) queues_.assignAll(queueForValue(kValueFar, forceLayer_, maxValue_));
  inRange_ = false;
  std::fill(owedIndices_.begin(), owedIndices_.end(), 0.0);  // every point is known far now
  lastTravelM_ = relativeTravelM;
}

void PairCoherence::setForceLayer(std::uint8_t forceLayer) noexcept {
  forceLayer_ = forceLayer;
  queues_.assignAll(1);
}

std::uint32_t PairCoherence::collectDue(double relativeTravelM, double voxelSizeM,
                                        std::span<std::uint32_t> due) noexcept {
  inRange_ = true;
  const double pointCount = queues_.pointCount();
  std::uint32_t n = 0;
  const int queueCount = queueCountFor(forceLayer_, maxValue_);
  for (int q = 0; q < queueCount; ++q) {
    const auto qi = static_cast<std::size_t>(q);
    if (q < kMandatoryQueues) {
      n += queues_.takeAll(q, due.subspan(n));
    } else {
      double& owed = owedIndices_[qi];
      owed = std::min(pointCount, owed + pointCount * lastTravelM_ / (voxelsToContact(q) * voxelSizeM));
      const std::uint32_t count = queues_.count(q);
      if (count > 0) {
        const PointQueues::Sweep sweep = queues_.takeSweep(q, queueQuota(count, q, relativeTravelM, voxelSizeM),
                                                          static_cast<std::uint64_t>(std::ceil(owed)), due.subspan(n));
        n += sweep.taken;
        owed = std::max(0.0, owed - static_cast<double>(sweep.coveredIndices));
      } else {
        owed = 0.0;  // nobody waits in an empty queue
      }
    }
    dueEndByQueue_[qi] = n;
  }
  lastTravelM_ = relativeTravelM;
  return n;
}
std::uint32_t PairCoherence::testDue(const Pointshell& shell, const Voxmap& voxmap, const VoxelTransform& transform,
                                     const std::array<std::uint8_t, 3>& fieldShifts, std::uint8_t sampledLayer,
                                     std::span<const std::uint32_t> due, PointContact* contacts) noexcept {
  std::uint32_t found = 0;
  std::uint32_t at = 0;
  const int queueCount = queueCountFor(forceLayer_, maxValue_);
  for (int q = 0; q < queueCount; ++q) {
    const std::uint32_t end = dueEndByQueue_[static_cast<std::size_t>(q)];
    for (; at < end && at < due.size(); ++at) {
      const std::uint32_t point = due[at];
      const PointSample sample = samplePointAt(shell, voxmap, transform, fieldShifts, point);
      // value − 1 wraps far (0) to 255, so one compare keeps [1, sampledLayer]
      if (static_cast<std::uint8_t>(sample.value - 1u) < sampledLayer) {
        contacts[found++] = {point, sample.ijkVoxel, sample.value};
      }
      queues_.move(point, q, queueForValue(sample.value, forceLayer_, maxValue_));
    }
  }
  return found;
}

}  // namespace voxhap
