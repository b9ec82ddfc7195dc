#pragma once
/// What `voxhap simulate`, `voxhap demo` and `voxhap bench extraction` share: the
/// headless 1 kHz frame loop with its statistics and summary (their options:
/// sim_options.h).

#include <cstdint>
#include <functional>
#include <ostream>
#include <span>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/cli/console.h"
#include "haptics/device/scripted_device.h"
#include "haptics/sim/local_simulation.h"
#include "haptics/sim/scene_model.h"

namespace voxhap::cli {

/// Statistics of a run of frames, over every moving object.
struct FrameStats {
  std::vector<double> computeUs;       ///< per frame, the compute time of step, µs
  std::uint64_t framesOverBudget = 0;  ///< frames whose compute time exceeded the frame period
  std::uint32_t maxContacts = 0;       ///< most points in contact in one object-frame
  double sumContacts = 0.0;            ///< over object-frames
  double maxForceN = 0.0;              ///< largest contact force on an object, N
  double sumTested = 0.0;              ///< point tests, over frames
  double sumDrifted = 0.0;             ///< of which skipped the lookup (point drifting)
  double sumChunkTests = 0.0;          ///< chunk-centroid tests, over frames
  double sumTravelScale = 0.0;         ///< MaxTravel over its bound, over frames
  SimCounters counters;                ///< the engine's, at the end of the run
  Suspensions suspensions;             ///< the engine's, at the end of the run

  /// Adds the frame `sim` has just stepped, which took `computeUs` µs.
  void add(const LocalSimulation& sim, double computeUsOfFrame);
  std::uint64_t frames() const { return computeUs.size(); }
  /// Per frame means (0 for no frames).
  double meanContacts() const;
  double meanTested() const;
  double meanDrifted() const;
  double meanChunkTests() const;
  double meanTravelScale() const;
  /// The p-quantile (0 < p ≤ 1, nearest rank) of the compute times, µs; 0 for no frames.
  double computePercentileUs(double p) const;
  double computeMaxUs() const;
};

/// Called after each frame with its index (from 0) and compute time, µs.
using AfterFrameFn = std::function<void(std::uint64_t frame, double computeUs)>;

/// Runs `frames` frames of `sim`: devices[i] (nullptr: free) drives object i; each
/// step is timed alone (whatever `afterFrame` does is not counted), added to `stats`,
/// then `afterFrame` (may be empty) runs. `progress` (may be empty) is told every 100
/// frames and at the end. Throws voxhap::Error when paging stopped the run.
void runFrames(LocalSimulation& sim, std::span<HapticDevice* const> devices, std::uint64_t frames,
               FrameStats& stats, const ProgressFn& progress, const AfterFrameFn& afterFrame = {});

/// The summary keys `voxhap simulate --json` prints: frames, max_contacts, mean_contacts,
/// max_force_n, mean_tested, mean_drifted, mean_chunk_tests, mean_travel_scale, missed_deadlines,
/// frames_over_budget, pairs_skipped, suspensions, suspended_frames, longest_suspension_s,
/// travel_limited_frames, depth_limited_frames, compute_us {p50, p99, max}.
nlohmann::ordered_json frameStatsJson(const FrameStats& stats);

/// The same summary as aligned text lines.
void printFrameStats(std::ostream& out, const FrameStats& stats, bool coherence);

}  // namespace voxhap::cli
