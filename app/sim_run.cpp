#include "app/sim_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include <glm/geometric.hpp>

#include "haptics/core/error.h"

namespace voxhap::cli {

void FrameStats::add(const LocalSimulation& sim, double computeUsOfFrame) {
  computeUs.push_back(computeUsOfFrame);
  framesOverBudget += computeUsOfFrame > sim.model().dtS * 1e6 ? 1 : 0;
  const CoherenceFrame& coherence = sim.outputs.coherence;
  sumTested += coherence.tested;
  sumDrifted += coherence.drifted;
  sumChunkTests += coherence.chunkTests;
  sumTravelScale += coherence.travelScale;
  for (const ObjectFrame& o : sim.outputs.objects) {
    maxContacts = std::max(maxContacts, o.contacts);
    sumContacts += o.contacts;
    maxForceN = std::max(maxForceN, glm::length(o.contactForceWorld));
  }
}

double FrameStats::meanContacts() const {
  return computeUs.empty() ? 0.0 : sumContacts / static_cast<double>(frames());
}
double FrameStats::meanTested() const {
  return computeUs.empty() ? 0.0 : sumTested / static_cast<double>(frames());
}
double FrameStats::meanDrifted() const {
  return computeUs.empty() ? 0.0 : sumDrifted / static_cast<double>(frames());
}
double FrameStats::meanChunkTests() const {
  return computeUs.empty() ? 0.0 : sumChunkTests / static_cast<double>(frames());
}
double FrameStats::meanTravelScale() const {
  return computeUs.empty() ? 0.0 : sumTravelScale / static_cast<double>(frames());
}

double FrameStats::computePercentileUs(double p) const {
  if (computeUs.empty()) return 0.0;
  std::vector<double> values = computeUs;
  const auto rank = static_cast<std::size_t>(std::ceil(p * static_cast<double>(values.size())));
  const std::size_t k = std::clamp<std::size_t>(rank, 1, values.size()) - 1;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  return values[k];
}

double FrameStats::computeMaxUs() const {
  return computeUs.empty() ? 0.0 : *std::max_element(computeUs.begin(), computeUs.end());
}

void runFrames(LocalSimulation& sim, std::span<HapticDevice* const> devices, std::uint64_t frames,
               FrameStats& stats, const ProgressFn& progress, const AfterFrameFn& afterFrame) {
  stats.computeUs.reserve(stats.computeUs.size() + frames);
  for (std::uint64_t f = 0; f < frames; ++f) {
    if (sim.stepWithDevices(devices) & kFrameStopped) {
      throw Error("stopped at " + std::to_string(sim.state.timeS) +
                  " s: the voxels the frame needed were not read "
                  "from the cache file within " +
                  std::to_string(static_cast<int>(kMaxSuspensionS)) +
                  " s (paper §5.3); allow more --voxel-memory or use a faster disk");
    }
    const double us = sim.lastStepS * 1e6;
    stats.add(sim, us);
    if (afterFrame) afterFrame(f, us);
    if (progress && f % 100 == 0) progress(static_cast<double>(f) / static_cast<double>(frames));
  }
  stats.counters = sim.workspace.counters;
  stats.suspensions = sim.workspace.suspensions;
  if (progress) progress(1.0);
}

nlohmann::ordered_json frameStatsJson(const FrameStats& stats) {
  return {{"frames", stats.frames()},
          {"max_contacts", stats.maxContacts},
          {"mean_contacts", stats.meanContacts()},
          {"max_force_n", stats.maxForceN},
          {"mean_tested", stats.meanTested()},
          {"mean_drifted", stats.meanDrifted()},
          {"mean_chunk_tests", stats.meanChunkTests()},
          {"mean_travel_scale", stats.meanTravelScale()},
          {"missed_deadlines", stats.counters.missedDeadlines},
          {"frames_over_budget", stats.framesOverBudget},
          {"pairs_skipped", stats.counters.pairsSkipped},
          {"suspensions", stats.suspensions.count},
          {"suspended_frames", stats.suspensions.frames},
          {"longest_suspension_s", stats.suspensions.longestS},
          {"travel_limited_frames", stats.counters.travelLimitedFrames},
          {"depth_limited_frames", stats.counters.depthLimitedFrames},
          {"compute_us",
           {{"p50", stats.computePercentileUs(0.5)},
            {"p99", stats.computePercentileUs(0.99)},
            {"max", stats.computeMaxUs()}}}};
}

void printFrameStats(std::ostream& out, const FrameStats& stats, bool coherence) {
  out << "frames          " << stats.frames() << "\nmax contacts    " << stats.maxContacts
      << "\nmean contacts   " << stats.meanContacts() << "\nmax force       " << stats.maxForceN
      << " N\nmean tests      " << stats.meanTested() << " per frame ("
      << (coherence ? "time-critical" : "brute force") << "; " << stats.meanDrifted()
      << " of them drifting), " << stats.meanChunkTests() << " chunk tests\nMaxTravel       "
      << stats.meanTravelScale() << " of its bound on average\nmissed deadlines "
      << stats.counters.missedDeadlines << "\nover 1 ms        " << stats.framesOverBudget
      << " frames\ndepth limited   " << stats.counters.depthLimitedFrames << " frames\nsuspensions     "
      << stats.suspensions.count << " (" << stats.suspensions.frames << " frames, longest "
      << stats.suspensions.longestS << " s)\ncompute         p50 " << stats.computePercentileUs(0.5)
      << " us, p99 " << stats.computePercentileUs(0.99) << " us, max " << stats.computeMaxUs() << " us\n";
}

}  // namespace voxhap::cli
