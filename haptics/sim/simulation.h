#pragma once
/// One 1 kHz frame of the haptic simulation (DESIGN §4.4, §4.5, §4.7):
///   1. Eq. 2 over the pairs in range gives this frame's MaxTravel from the capacity and
///      the distance-to-contact queues (a pair whose bounding sphere misses the voxmap's
///      grid costs no point test);
///   2. every pair in range tests its mandatory points and its Eq. 3 quota of the others
///      (or, with coherence off, every point) and sums tangent-plane forces, applied equal
///      and opposite;
///   3. each coupled object feels its handle through the virtual coupling; each object is
///      integrated as a free rigid body (gravity, coupling, external wrenches, contacts);
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
/// kMaxSuspensionS of suspension by the caller's clock the run stops (kFrameStopped).
/// step() reads no clock, never allocates, locks, throws or prints: its buffers live in
/// the workspace and the outputs, sized at load time. Deterministic with a fixed capacity
/// and whole voxmaps: same model, state and inputs, same bits, on any machine that runs
/// IEEE doubles without contraction (-ffp-contract=off); a capacity measured online and a
/// pager's timing are not.

#include <span>

#include "haptics/device/scripted_device.h"
#include "haptics/sim/frame_io.h"
#include "haptics/sim/sim_model.h"
#include "haptics/sim/sim_state.h"
#include "haptics/sim/sim_workspace.h"

namespace voxhap {

/// Moves the force layer of every pair to `value` (1 … the voxmaps' largest value) from
/// the next frame on: a larger value keeps the objects further apart. Returns false and
/// changes nothing when the value is out of range.
bool setForceLayer(const SimModel& model, SimState& state, SimWorkspace& workspace,
                   std::uint8_t value) noexcept;

/// Advances `state` by one frame of `inputs`, writing `outputs` (sized by
/// makeFrameOutputs) and returning what went wrong.
FrameStatus step(const SimModel& model, SimState& state, SimWorkspace& workspace, const FrameInputs& inputs,
                 FrameOutputs& outputs) noexcept;

/// One frame driven by devices: reads `devices[i]` (nullptr: object i is free) at the
/// frame's end time into `handles` (one per object, caller-owned), steps with them and
/// the rest of `inputs`, and writes each device its feedback.
FrameStatus stepWithDevices(const SimModel& model, SimState& state, SimWorkspace& workspace,
                            std::span<HapticDevice* const> devices, std::span<HandleInput> handles,
                            FrameInputs inputs, FrameOutputs& outputs) noexcept;

/// The world pose of object `object` (local → world).
Pose objectPose(const SimModel& model, const SimState& state, std::size_t object) noexcept;

}  // namespace voxhap
