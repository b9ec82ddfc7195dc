#pragma once
/// One 1 kHz frame of the haptic simulation (DESIGN §4.4, §4.5, §4.7):
///   1. Eq. 2 over the pairs in range gives this frame's MaxTravel from the capacity and
///      the distance-to-contact queues (a pair whose bounding sphere misses the voxmap's
///      grid costs no point test);
///   2. every pair in range tests its mandatory points and its Eq. 3 quota of the others
///      (or, with coherence off, every point) and sums tangent-plane forces, applied equal
///      and opposite;
///   3. each coupled object feels its handle through the virtual coupling; each object is
///      integrated as a free rigid body (gravity, coupling, contacts);
///   4. its motion is limited to MaxTravel (at most half a voxel near contact, paper §5;
///      half a chunk when all its pairs are out of range or collapsed, §5.1), which the
///      user feels as viscosity;
///   5. the step is projected onto the contacts' depth limits, so that no contact goes
///      deeper than kDepthLimitVoxels past its tangent plane (depth_limit.h: why parts then
///      never interpenetrate, however hard the handle pulls);
///   6. the coupling wrench is saturated at the device's limits: the body feels exactly
///      what the device renders, negated.
/// A frame that needed voxels of a paged static voxmap that were not yet resident is
/// suspended instead (paper §5.3): nothing moves, the devices get no force, and after
/// kMaxSuspensionS of suspension the run stops (SimState::stopped).
/// All buffers live in SimState, sized by makeSimState: step() never allocates, locks,
/// throws or prints. Deterministic with a fixed capacity and whole voxmaps: same model,
/// state and handles, same bits (a capacity measured online and a pager's timing are not).

#include <chrono>
#include <cstdint>
#include <span>
#include <vector>

#include "haptics/coherence/pair_coherence.h"
#include "haptics/collide/point_sampler.h"
#include "haptics/device/scripted_device.h"
#include "haptics/sim/depth_limit.h"
#include "haptics/sim/sim_model.h"

namespace voxhap {

/// The handle of one coupled object this frame.
struct HandleInput {
  Pose poseWorld;            ///< target local → world pose of the object
  HandleVelocity velocity;   ///< world frame
};

/// What happened to one moving object in the last frame.
struct ObjectFrame {
  glm::dvec3 contactForceWorld{0.0};   ///< sum over its pairs, N
  glm::dvec3 contactTorqueWorld{0.0};  ///< about its centre of mass, N·m
  CouplingWrench feedback;             ///< to its device (zero when not coupled)
  std::uint32_t contacts = 0;          ///< its points (or points against it) in the force layer
  std::uint32_t tested = 0;            ///< point tests in the pairs where it is the pointshell
  double maxDepthM = 0.0;              ///< deepest tangent-plane depth of its contacts, m
  double maxTravelM = 0.0;             ///< MaxTravel this frame, m (infinite: no pair)
  bool travelLimited = false;          ///< MaxTravel held it back
};

/// Time-critical sampling in one frame, over all pairs.
struct CoherenceFrame {
  std::uint32_t tested = 0;       ///< point tests
  std::uint32_t drifted = 0;      ///< of the point tests, those that skipped the lookup (drifting)
  std::uint32_t chunkTests = 0;   ///< chunk-centroid tests
  std::uint32_t mandatory = 0;    ///< points and chunks tested whatever the travel
  double capacityTests = 0.0;     ///< n_cap used by Eq. 2
  double travelScale = 1.0;       ///< every object's MaxTravel over its upper bound
  double plannedLoad = 0.0;       ///< Eq. 2's free-space tests at full travel, with the sweeps' excess
  bool deadlineMissed = false;    ///< more mandatory tests than capacity (see planFrame)
};

/// The longest a run of frames may stay suspended waiting for paged voxels, s (paper §5.3).
inline constexpr double kMaxSuspensionS = 2.0;

/// Frames suspended because voxels they needed were still paged out (paper §5.3): nothing
/// moves and the devices feel no force until the pager has read them.
struct Suspensions {
  bool active = false;             ///< the frame just stepped was suspended
  std::chrono::steady_clock::time_point since;  ///< when the current suspension began
  std::uint64_t count = 0;         ///< suspensions (runs of suspended frames)
  std::uint64_t frames = 0;        ///< suspended frames in all
  double longestS = 0.0;           ///< longest suspension so far, s (wall clock)
};

/// Per pair, between the two passes of a frame.
struct PairFrame {
  VoxelTransform transform;
  bool inRange = false;
  double relativeTravelBoundM = 0.0;  ///< its two objects' MaxTravel bounds this frame, summed
};

/// Everything that changes per frame.
struct SimState {
  std::uint64_t frame = 0;
  double timeS = 0.0;
  std::vector<RigidBodyState> bodies;  ///< per moving object
  std::vector<ObjectFrame> last;       ///< per moving object, the frame just stepped
  std::uint64_t pairsSkipped = 0;      ///< pair-frames out of range, in all
  std::uint64_t travelLimitedFrames = 0;  ///< object-frames that MaxTravel held back
  /// The contacts' depth limits this frame (depth_limit.h), and the frames they bound.
  DepthLimitFrame depthLimit;
  std::uint64_t depthLimitedFrames = 0;
  DepthLimitScratch depthScratch;        ///< room for every pair's contacts as depth rows
  std::vector<RigidBodyState> beforeStep;  ///< per moving object, its state at frame start
  std::vector<PointContact> scratch;   ///< room for the largest pointshell's contacts
  std::vector<PairFrame> pairFrames;   ///< per pair
  std::vector<double> travelBoundM;    ///< per moving object, its MaxTravel bound this frame, m
  /// Per pair, its queues; empty when coherence is off.
  std::vector<PairCoherence> coherence;
  std::vector<std::uint32_t> due;      ///< room for the largest pointshell's indices
  std::vector<std::uint32_t> dueChunks;  ///< room for the largest pointshell's chunks
  CoherenceFrame coherent;             ///< the frame just stepped
  /// Frames with more mandatory tests than capacity: the first of a run stops every object,
  /// the rest run at full MaxTravel however long they take.
  std::uint64_t missedDeadlines = 0;
  /// Online estimate of the time one point test (with its share of forces) takes, s.
  double testCostS = 20e-9;
  /// Free-space tests the sweeps take over those Eq. 3 asks for, smoothed (≥ 1; from
  /// the tests themselves, so a fixed capacity stays bit-reproducible).
  double sweepExcess = 1.0;
  Suspensions suspensions;
  /// A suspension outlasted kMaxSuspensionS: the run is over and step() does nothing more.
  bool stopped = false;
  /// The force layer in use (collision offsetting, paper §3.2), adjustable between frames
  /// with setForceLayer; starts at the model's.
  std::uint8_t forceLayer = kDefaultForceLayer;
};

/// Moves the force layer of every pair to `value` (1 … the voxmaps' largest value) from
/// the next frame on: a larger value keeps the objects further apart. Returns false and
/// changes nothing when the value is out of range.
bool setForceLayer(const SimModel& model, SimState& state, std::uint8_t value) noexcept;

/// A state with every object at rest where the scene file puts it.
SimState makeSimState(const SimModel& model);

/// Advances `state` by one frame. `handles[i]` drives object i when it is coupled (entries
/// of uncoupled objects are ignored); size = number of objects.
void step(const SimModel& model, SimState& state, std::span<const HandleInput> handles) noexcept;

/// One frame driven by devices: reads `devices[i]` (nullptr: object i is free) at the
/// frame's end time into `handles` (same size, caller-owned), steps, and writes each
/// device its feedback.
void stepWithDevices(const SimModel& model, SimState& state, std::span<HapticDevice* const> devices,
                     std::span<HandleInput> handles) noexcept;

/// The world pose of object `object` (local → world).
Pose objectPose(const SimModel& model, const SimState& state, std::size_t object) noexcept;

}  // namespace voxhap
