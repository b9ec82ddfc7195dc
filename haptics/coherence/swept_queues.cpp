#include "haptics/coherence/swept_queues.h"

#include <algorithm>
#include <cmath>

namespace voxhap {

SweptQueues::SweptQueues(std::uint32_t memberCount, int queueCount)
    : queues_(memberCount, queueCount), owedBlocks_(static_cast<std::size_t>(queueCount), 0.0) {}

void SweptQueues::clearOwed() noexcept {
  std::fill(owedBlocks_.begin(), owedBlocks_.end(), 0.0);
}

double SweptQueues::owedAfter(int q, double distanceM, double travelM) const noexcept {
  const double blocks = queues_.sweepBlockCount();
  return std::min(blocks, owedBlocks_[static_cast<std::size_t>(q)] + blocks * travelM / distanceM);
}

std::uint32_t SweptQueues::collect(int q, double distanceM, double travelM,
                                   std::span<std::uint32_t> out) noexcept {
  if (!(distanceM > 0.0)) return queues_.takeAll(q, out);
  double& owed = owedBlocks_[static_cast<std::size_t>(q)];
  owed = owedAfter(q, distanceM, travelM);
  if (queues_.count(q) == 0) {
    owed = 0.0;  // nobody waits in an empty queue
    return 0;
  }
  const PointQueues::Sweep sweep = queues_.takeSweep(q, static_cast<std::uint32_t>(std::ceil(owed)), out);
  owed -= static_cast<double>(sweep.coveredBlocks);  // the part of a block covered ahead is credit
  return sweep.taken;
}

void SweptQueues::addTestsByTravel(int q, double distanceM, double fullTravelM,
                                   TestsByTravel& tests) const noexcept {
  if (queues_.count(q) == 0) return;
  std::array<std::uint32_t, kTravelSteps + 1> marks;
  for (std::size_t k = 0; k < marks.size(); ++k) {
    const double travelM = fullTravelM * static_cast<double>(k) / kTravelSteps;
    marks[k] = static_cast<std::uint32_t>(std::ceil(owedAfter(q, distanceM, travelM)));
  }
  std::array<std::uint32_t, kTravelSteps + 1> points;
  queues_.pointsAhead(q, marks, points);
  for (std::size_t k = 0; k < marks.size(); ++k) tests[k] += points[k];
}

}  // namespace voxhap
