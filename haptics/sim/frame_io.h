#pragma once
/// What one frame takes and gives (DESIGN §7): FrameInputs from the caller's devices,
/// peers and clock; FrameOutputs for its devices, peers and statistics; FrameStatus,
/// a bitmask of what went wrong. The caller owns both and sizes them at load time
/// (makeFrameOutputs), so that step() never allocates.

#include <array>
#include <chrono>
#include <cstdint>
#include <span>
#include <vector>

#include "haptics/device/scripted_device.h"
#include "haptics/dynamics/virtual_coupling.h"
#include "haptics/sim/depth_limit.h"
#include "haptics/sim/sim_model.h"

namespace voxhap {

/// The handle of one coupled object this frame.
struct HandleInput {
  Pose poseWorld;           ///< target local → world pose of the object
  HandleVelocity velocity;  ///< world frame
  bool held = true;         ///< false: nothing holds the object this frame (no coupling wrench)
};

/// An object that a remote peer owns (type-1, DESIGN §8): its owner integrates it, and
/// this peer moves it as a kinematic body to where the owner's stream puts it. It feels
/// no force here (its contacts still push the local objects). Its step is held to its
/// MaxTravel like any other, so that no contact is skipped, and the depth limits do not
/// move it, so that every peer shows it where its owner has it; only a local part trapped
/// between it and a third, or pushed by it faster than its MaxTravel lets it give way, or
/// another owner's remote part that the two streams carry into it, makes it yield
/// (depth_limit.h): it then lags its stream until it is free, and its owner's peer, which
/// simulates the same contact, stops it one delay later.
struct KinematicInput {
  bool active = false;
  RigidBodyState targetWorld;  ///< where the stream puts it at the frame's end
};

/// A wrench from outside the simulation on one moving object, world frame: the type-2
/// coupling to remote copies of a shared object (DESIGN §8), a user's push.
struct ExternalWrench {
  glm::dvec3 forceWorld{0.0};   ///< N, at the centre of mass
  glm::dvec3 torqueWorld{0.0};  ///< N·m, about the centre of mass
};

struct FrameInputs {
  /// handles[i] drives object i when it is coupled (entries of uncoupled objects are
  /// ignored); empty, or one per object.
  std::span<const HandleInput> handles;
  /// Per object, added to its gravity, coupling and contacts; empty, or one per object.
  std::span<const ExternalWrench> externalWrenches;
  /// Per object, the gains of its coupling in place of the model's (a user's softer
  /// setting, scaledCouplingGains); empty: the model's.
  std::span<const CouplingGains> couplingGains;
  /// Per object, whether a remote peer moves it this frame; empty, or one per object.
  std::span<const KinematicInput> kinematic;
  /// When this frame began by the caller's clock: a paged voxmap's suspension is timed
  /// by it (paper §5.3). The frame itself reads no clock.
  std::chrono::steady_clock::time_point now{};
  /// How long the previous step() took by the caller's clock, s (≤ 0: not measured):
  /// with CoherenceOptions::capacityTests 0, the capacity is measured from it online.
  double previousStepS = 0.0;
};

/// Some of an object's contact points, for display: all of them while they fit, else a
/// sample spread evenly over each pair's (the first pairs' when the room runs out).
struct ContactSample {
  static constexpr std::size_t kCapacity = 64;
  std::array<glm::vec3, kCapacity> pointsWorld;  ///< m, at the frame's start
  std::uint32_t count = 0;

  std::span<const glm::vec3> points() const { return {pointsWorld.data(), count}; }
};

/// What happened to one moving object in the frame.
struct ObjectFrame {
  glm::dvec3 contactForceWorld{0.0};   ///< sum over its pairs, N
  glm::dvec3 contactTorqueWorld{0.0};  ///< about its centre of mass, N·m
  CouplingWrench feedback;             ///< to its device (zero when not coupled)
  std::uint32_t contacts = 0;          ///< its points (or points against it) in the force layer
  std::uint32_t tested = 0;            ///< point tests in the pairs where it is the pointshell
  double maxDepthM = 0.0;              ///< deepest tangent-plane depth of its contacts, m
  double maxTravelM = 0.0;             ///< MaxTravel this frame, m (infinite: no pair)
  bool travelLimited = false;          ///< MaxTravel held it back
  ContactSample contactSample;         ///< of its points in the force layer, where it is the pointshell
};

/// Time-critical sampling in one frame, over all pairs.
struct CoherenceFrame {
  std::uint32_t tested = 0;      ///< point tests
  std::uint32_t drifted = 0;     ///< of the point tests, those that skipped the lookup (drifting)
  std::uint32_t chunkTests = 0;  ///< chunk-centroid tests
  std::uint32_t mandatory = 0;   ///< points and chunks tested whatever the travel
  double capacityTests = 0.0;    ///< n_cap used by Eq. 2
  double travelScale = 1.0;      ///< every object's MaxTravel over its upper bound
  double plannedLoad = 0.0;      ///< Eq. 2's free-space tests at full travel
  bool deadlineMissed = false;   ///< more mandatory tests than capacity (see planFrame)
};

struct FrameOutputs {
  std::vector<ObjectFrame> objects;  ///< per moving object
  CoherenceFrame coherence;
  DepthLimitFrame depthLimit;  ///< the contacts' depth limits (depth_limit.h)
};

/// Outputs with room for every object of `model`.
inline FrameOutputs makeFrameOutputs(const SimModel& model) {
  FrameOutputs outputs;
  outputs.objects.resize(model.objects.size());
  return outputs;
}

/// What went wrong in a frame, as bits (0: nothing).
using FrameStatus = std::uint32_t;
/// Nothing went wrong.
inline constexpr FrameStatus kFrameOk = 0;
/// More mandatory point tests than capacity (simulation.cpp, planFrame).
inline constexpr FrameStatus kFrameDeadlineMissed = 1u << 0;
/// Voxels it needed were paged out: nothing moved, no force was sent (paper §5.3).
inline constexpr FrameStatus kFrameSuspended = 1u << 1;
/// A non-finite input (handle, external wrench) was replaced by none, or a body skipped
/// its step because its forces were not finite (RigidBodyState::skippedSteps).
inline constexpr FrameStatus kFrameNonFiniteZeroed = 1u << 2;
/// A suspension outlasted kMaxSuspensionS: the run is over, and the frame did nothing.
inline constexpr FrameStatus kFrameStopped = 1u << 3;

}  // namespace voxhap
