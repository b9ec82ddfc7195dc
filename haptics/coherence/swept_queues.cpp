#include "haptics/coherence/swept_queues.h"

#include <algorithm>
#include <cmath>

#include "haptics/coherence/max_travel.h"

namespace voxhap {

SweptQueues::SweptQueues(std::uint32_t memberCount, int queueCount)
    : queues_(memberCount, queueCount), owedIndices_(static_cast<std::size_t>(queueCount), 0.0) {}

void SweptQueues::clearOwed() noexcept {
  std::fill(owedIndices_.begin(), owedIndices_.end(), 0.0);
}

std::uint32_t SweptQueues::collect(int q, double distanceM, double travelM, double lastTravelM,
                                   std::span<std::uint32_t> out) noexcept {
  if (!(distanceM > 0.0)) return queues_.takeAll(q, out);
  const double members = queues_.pointCount();
  double& owed = owedIndices_[static_cast<std::size_t>(q)];
  owed = std::min(members, owed + members * lastTravelM / distanceM);
  const std::uint32_t count = queues_.count(q);
  if (count == 0) {
    owed = 0.0;  // nobody waits in an empty queue
    return 0;
  }
  const PointQueues::Sweep sweep = queues_.takeSweep(q, sweepQuota(count, travelM, distanceM),
                                                     static_cast<std::uint64_t>(std::ceil(owed)), out);
  owed = std::max(0.0, owed - static_cast<double>(sweep.coveredIndices));
  return sweep.taken;
}

}  // namespace voxhap
