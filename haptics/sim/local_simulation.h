#pragma once
/// One peer's simulation stepped by a caller that owns the clock (commands, benchmarks,
/// tests): the model's state, its workspace and the last frame's outputs together, with
/// the wall clock read around each frame (FrameInputs::now, previousStepS). Not for the
/// haptic thread, which times its frames itself.

#include <memory>
#include <span>
#include <vector>

#include "haptics/sim/simulation.h"

namespace voxhap {

class LocalSimulation {
public:
  /// At rest where the scene file puts every object; `staticPager` as makeSimWorkspace
  /// wants it. `model` must outlive the simulation. Allocates; throws voxhap::Error as
  /// makeSimWorkspace does.
  explicit LocalSimulation(const SimModel& model, std::shared_ptr<VoxelPager> staticPager = nullptr);
  /// From `state` (restored from a snapshot, or set up by a test).
  LocalSimulation(const SimModel& model, SimState state, std::shared_ptr<VoxelPager> staticPager = nullptr);

  /// One frame: `handles` drive the coupled objects, `wrenches` push on them, `kinematic`
  /// moves those a remote peer owns (each empty, or one per object).
  FrameStatus step(std::span<const HandleInput> handles = {}, std::span<const ExternalWrench> wrenches = {},
                   std::span<const KinematicInput> kinematic = {}) noexcept;
  /// One frame driven by `devices` (one per object; nullptr: free), as stepWithDevices.
  FrameStatus stepWithDevices(std::span<HapticDevice* const> devices) noexcept;

  const SimModel& model() const noexcept { return *model_; }
  /// The handles the devices gave in the last stepWithDevices, one per object.
  std::span<const HandleInput> deviceHandles() const noexcept { return deviceHandles_; }
  /// The last frame's outputs for object `i`.
  const ObjectFrame& object(std::size_t i) const noexcept { return outputs.objects[i]; }

  SimState state;
  SimWorkspace workspace;
  FrameOutputs outputs;
  FrameStatus lastStatus = 0;
  double lastStepS = 0.0;  ///< how long the last step() took, s (wall clock)

private:
  FrameStatus timed(FrameInputs inputs, std::span<HapticDevice* const> devices) noexcept;

  const SimModel* model_;
  std::vector<HandleInput> deviceHandles_;
};

}  // namespace voxhap
