#include "haptics/sim/local_simulation.h"

#include <chrono>

namespace voxhap {

LocalSimulation::LocalSimulation(const SimModel& model, std::shared_ptr<VoxelPager> staticPager)
    : LocalSimulation(model, makeSimState(model), std::move(staticPager)) {}

LocalSimulation::LocalSimulation(const SimModel& model, SimState initial,
                                 std::shared_ptr<VoxelPager> staticPager)
    : state(std::move(initial)),
      workspace(makeSimWorkspace(model, state, std::move(staticPager))),
      outputs(makeFrameOutputs(model)),
      model_(&model),
      deviceHandles_(model.objects.size()) {}

FrameStatus LocalSimulation::step(std::span<const HandleInput> handles,
                                  std::span<const ExternalWrench> wrenches,
                                  std::span<const KinematicInput> kinematic) noexcept {
  FrameInputs inputs;
  inputs.handles = handles;
  inputs.externalWrenches = wrenches;
  inputs.kinematic = kinematic;
  return timed(inputs, {});
}

FrameStatus LocalSimulation::stepWithDevices(std::span<HapticDevice* const> devices) noexcept {
  return timed(FrameInputs{}, devices);
}

FrameStatus LocalSimulation::timed(FrameInputs inputs, std::span<HapticDevice* const> devices) noexcept {
  const auto start = std::chrono::steady_clock::now();
  inputs.now = start;
  inputs.previousStepS = lastStepS;
  lastStatus = devices.empty() ? voxhap::step(*model_, state, workspace, inputs, outputs)
                               : voxhap::stepWithDevices(*model_, state, workspace, devices, deviceHandles_,
                                                         inputs, outputs);
  lastStepS = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return lastStatus;
}

}  // namespace voxhap
