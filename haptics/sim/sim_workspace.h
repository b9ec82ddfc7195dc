#pragma once
/// Everything a peer's frames need beside the replicated SimState, never sent (DESIGN
/// §7): time-critical sampling's queues and capacity estimate, the paging suspension's
/// clock, the scratch the frame works in, the running counts, and the residency of a
/// paged static voxmap (its pager, which other reader threads join with addReader()).
/// Sized at load time by makeSimWorkspace, so that step() never allocates.

#include <chrono>
#include <cstdint>
#include <memory>
#include <vector>

#include "haptics/coherence/pair_coherence.h"
#include "haptics/collide/point_sampler.h"
#include "haptics/runtime/frame_helper.h"
#include "haptics/sim/depth_limit.h"
#include "haptics/sim/sim_model.h"
#include "haptics/sim/sim_state.h"
#include "haptics/voxel/voxel_pager.h"

namespace voxhap {

/// The longest a run of frames may stay suspended waiting for paged voxels, s (paper §5.3).
inline constexpr double kMaxSuspensionS = 2.0;

/// Frames suspended because voxels they needed were still paged out (paper §5.3): nothing
/// moves and the devices feel no force until the pager has read them.
struct Suspensions {
  bool active = false;                          ///< the frame just stepped was suspended
  std::chrono::steady_clock::time_point since;  ///< when the current suspension began
  std::uint64_t count = 0;                      ///< suspensions (runs of suspended frames)
  std::uint64_t frames = 0;                     ///< suspended frames in all
  double longestS = 0.0;                        ///< longest suspension so far, s (caller's clock)
};

/// Per pair, between the two passes of a frame.
struct PairFrame {
  VoxelTransform transform;
  bool inRange = false;
  double relativeTravelBoundM = 0.0;  ///< its two objects' MaxTravel bounds this frame, summed
};

/// Running counts over every frame stepped.
struct SimCounters {
  std::uint64_t pairsSkipped = 0;         ///< pair-frames out of range or only streamed
  std::uint64_t travelLimitedFrames = 0;  ///< object-frames that MaxTravel held back
  std::uint64_t depthLimitedFrames = 0;   ///< frames in which a depth limit bound
  /// Frames with more mandatory tests than capacity: the first of a run stops every object,
  /// the rest run at full MaxTravel however long they take.
  std::uint64_t missedDeadlines = 0;
};

struct SimWorkspace {
  /// Per pair, its queues; empty when coherence is off.
  std::vector<PairCoherence> coherence;
  /// Online estimate of the time one point test (with its share of the frame) takes, s.
  double testCostS = 20e-9;
  bool lastDeadlineMissed = false;  ///< the previous frame had more mandatory tests than capacity
  std::uint32_t lastTested = 0;     ///< point tests of the previous frame
  Suspensions suspensions;
  /// A suspension outlasted kMaxSuspensionS: the run is over and step() does nothing more.
  bool stopped = false;
  SimCounters counters;
  /// Pages the static voxmap's words when they exceed the voxel memory budget (paper
  /// §5.3); null when it is whole. It writes the model's paged voxmap, so the model must
  /// outlive it; threads other than the haptic thread read that voxmap through
  /// staticPager->addReader().
  std::shared_ptr<VoxelPager> staticPager;
  /// A second thread, pinned to a spare core, that tests half the due points of a pair's
  /// large frames (frame_helper.h); null: the haptic thread tests them all. The same
  /// results either way.
  std::shared_ptr<FrameHelper> helper;

  // scratch of one frame
  std::vector<PairFrame> pairFrames;       ///< per pair
  std::vector<double> travelBoundM;        ///< per moving object, its MaxTravel bound this frame, m
  std::vector<RigidBodyState> beforeStep;  ///< per moving object, its state at frame start
  std::vector<PointContact> contacts;      ///< room for the largest pointshell's contacts
  std::vector<std::uint32_t> due;          ///< room for the largest pointshell's indices
  std::vector<std::uint32_t> dueChunks;    ///< room for the largest pointshell's chunks
  DepthLimitScratch depthScratch;          ///< room for every pair's contacts as depth rows

  /// The pager of the pair's voxmap, or null when it is whole.
  VoxelPager* pagerOf(const PairModel& pair) const {
    return pair.voxmapObject == kStaticEnvironment ? staticPager.get() : nullptr;
  }
};

/// A workspace for frames of `model` from `state` (its queues sorted for the state's
/// poses), paging the static voxmap with `staticPager` (null when it is whole; from
/// buildScene). Load time: allocates.
SimWorkspace makeSimWorkspace(const SimModel& model, const SimState& state,
                              std::shared_ptr<VoxelPager> staticPager = nullptr);

}  // namespace voxhap
