#include "haptics/coherence/swept_queues.h"

#include <algorithm>
#include <cmath>

namespace voxhap {

SweptQueues::SweptQueues(std::uint32_t memberCount, int queueCount)
    : queues_(memberCount, queueCount), owedBlocks_(static_cast<std::size_t>(queueCount), 0.0) {}

void SweptQueues::clearOwed() noexcept {
  std::fill(owedBlocks_.begin(), owedBlocks_.end(), 0.0);
}

double SweptQueues::owedAfter(double owedBlocks, double distanceM, double travelM) const noexcept {
  const double blocks = queues_.sweepBlockCount();
  return std::min(blocks, owedBlocks + blocks * travelM / distanceM);
}

std::uint32_t SweptQueues::collect(int q, double distanceM, double lastTravelM,
                                   std::span<std::uint32_t> out) noexcept {
  if (!(distanceM > 0.0)) return queues_.takeAll(q, out);
  double& owed = owedBlocks_[static_cast<std::size_t>(q)];
  owed = owedAfter(owed, distanceM, lastTravelM);
  if (queues_.count(q) == 0) {
    owed = 0.0;  // nobody waits in an empty queue
    return 0;
  }
  const PointQueues::Sweep sweep = queues_.takeSweep(q, static_cast<std::uint32_t>(std::ceil(owed)), out);
  owed -= static_cast<double>(sweep.coveredBlocks);  // the part of a block covered ahead is credit
  return sweep.taken;
}

void SweptQueues::addTestsByTravel(int q, double distanceM, double fullTravelM, double lastTravelM,
                                   TestsByTravel& tests) const noexcept {
  if (queues_.count(q) == 0) return;
  // this frame's sweep (blocks [0, marks[0])), then the next frame's after a travel of
  // k / kTravelSteps · fullTravelM in this one (marks[k + 1])
  const double owedNow = owedAfter(owedBlocks_[static_cast<std::size_t>(q)], distanceM, lastTravelM);
  const double coveredNow = std::ceil(owedNow);
  std::array<std::uint32_t, kTravelSteps + 2> marks;
  marks[0] = static_cast<std::uint32_t>(coveredNow);
  for (std::size_t k = 0; k <= kTravelSteps; ++k) {
    const double travelM = fullTravelM * static_cast<double>(k) / kTravelSteps;
    marks[k + 1] =
        marks[0] + static_cast<std::uint32_t>(std::ceil(owedAfter(owedNow - coveredNow, distanceM, travelM)));
  }
  std::array<std::uint32_t, kTravelSteps + 2> points;
  queues_.pointsAhead(q, marks, points);
  for (std::size_t k = 0; k <= kTravelSteps; ++k) tests[k] += points[k + 1] - points[0];
}

}  // namespace voxhap
