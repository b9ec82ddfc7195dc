#include "haptics/sim/simulation.h"

#include <algorithm>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "haptics/collide/tangent_plane_force.h"

namespace voxhap {
namespace {

BodyMotion motionOf(const SimModel& model, const SimState& state, int object) {
  if (object == kStaticEnvironment) return {};
  const auto i = static_cast<std::size_t>(object);
  const RigidBodyState& body = state.bodies[i];
  return {body.pose(model.objects[i].body), model.objects[i].body.comLocal, body.linearVelocityWorld,
          body.angularVelocityWorld};
}

/// Whether the shell's bounding sphere (voxmap frame) reaches the voxmap's grid box.
bool inRange(const MovingObjectModel& shellObject, const Pose& shellToVoxmap, const VoxelGrid& grid) {
  const glm::dvec3 centre = apply(shellToVoxmap, shellObject.shellCentreLocal);
  const glm::dvec3 lo = grid.originLocal;
  const glm::dvec3 hi = lo + glm::dvec3(grid.dimsVoxels()) * grid.voxelSizeM;
  const glm::dvec3 outside = glm::max(glm::dvec3(0.0), glm::max(lo - centre, centre - hi));
  return glm::dot(outside, outside) <= shellObject.shellBoundRadiusM * shellObject.shellBoundRadiusM;
}

/// Holds the step from `before` to `after` to at most `maxTravelM` of any point at most
/// `radiusM` from the centre of mass; velocities shrink by the same factor.
bool limitTravel(const RigidBodyState& before, RigidBodyState& after, double radiusM, double maxTravelM) {
  const double angle = glm::length(rotationVector(after.orientation * glm::conjugate(before.orientation)));
  const double travel = glm::length(after.comWorld - before.comWorld) + angle * radiusM;
  if (!(travel > maxTravelM)) return false;
  const double f = maxTravelM / travel;
  after.comWorld = before.comWorld + (after.comWorld - before.comWorld) * f;
  after.orientation = slerpShortest(before.orientation, after.orientation, f);
  after.linearVelocityWorld *= f;
  after.angularVelocityWorld *= f;
  return true;
}

}  // namespace

SimState makeSimState(const SimModel& model) {
  SimState state;
  std::size_t largest = 0;
  for (const MovingObjectModel& object : model.objects) {
    state.bodies.push_back(restingState(object.body));
    largest = std::max(largest, object.shell.size());
  }
  state.last.resize(model.objects.size());
  state.scratch.resize(largest);
  if (!model.pairs.empty()) state.forceLayer = model.pairs.front().params.forceLayer;
  return state;
}

bool setForceLayer(const SimModel& model, SimState& state, std::uint8_t value) noexcept {
  if (value < 1) return false;
  for (const PairModel& pair : model.pairs) {
    if (value > model.voxmapOf(pair).encoding().maxValue()) return false;
  }
  state.forceLayer = value;
  return true;
}

void stepWithDevices(const SimModel& model, SimState& state, std::span<HapticDevice* const> devices,
                     std::span<HandleInput> handles) noexcept {
  const double t = state.timeS + model.dtS;
  for (std::size_t i = 0; i < devices.size(); ++i) {
    if (devices[i]) handles[i] = {devices[i]->handlePose(t), devices[i]->handleVelocity(t)};
  }
  step(model, state, handles);
  for (std::size_t i = 0; i < devices.size(); ++i) {
    if (devices[i]) devices[i]->setFeedback(state.last[i].feedback);
  }
}

Pose objectPose(const SimModel& model, const SimState& state, std::size_t object) noexcept {
  return state.bodies[object].pose(model.objects[object].body);
}

void step(const SimModel& model, SimState& state, std::span<const HandleInput> handles) noexcept {
  const std::size_t n = model.objects.size();
  for (ObjectFrame& f : state.last) f = ObjectFrame{};

  for (const PairModel& pair : model.pairs) {
    const MovingObjectModel& shellObject = model.objects[static_cast<std::size_t>(pair.shellObject)];
    const Voxmap& voxmap = model.voxmapOf(pair);
    const BodyMotion shellMotion = motionOf(model, state, pair.shellObject);
    const BodyMotion voxmapMotion = motionOf(model, state, pair.voxmapObject);
    const Pose shellToVoxmap = compose(inverse(voxmapMotion.poseWorld), shellMotion.poseWorld);
    if (!inRange(shellObject, shellToVoxmap, voxmap.grid())) {
      ++state.pairsSkipped;
      continue;
    }
    ContactParams params = pair.params;
    params.forceLayer = state.forceLayer;
    const VoxelTransform transform = VoxelTransform::make(shellToVoxmap, voxmap.grid());
    const auto shifts = fieldShiftsByFeature(params.geometricalAwareness, voxmap.encoding());
    const auto points = static_cast<std::uint32_t>(shellObject.shell.size());
    const std::uint32_t found = samplePoints(shellObject.shell, voxmap, transform, shifts,
                                             params.sampledLayer(voxmap.encoding().maxValue()), 0,
                                             points, state.scratch.data());
    const PairWrench w = tangentPlaneWrench(shellObject.shell, voxmap, params, shellMotion, voxmapMotion,
                                            std::span(state.scratch.data(), found));
    ObjectFrame& s = state.last[static_cast<std::size_t>(pair.shellObject)];
    s.contactForceWorld += w.forceOnShellWorld;
    s.contactTorqueWorld += w.torqueOnShellWorld;
    s.contacts += w.contactPoints;
    s.tested += points;
    s.maxDepthM = std::max(s.maxDepthM, w.maxDepthM);
    if (pair.voxmapObject != kStaticEnvironment) {
      ObjectFrame& v = state.last[static_cast<std::size_t>(pair.voxmapObject)];
      v.contactForceWorld += w.forceOnVoxmapWorld;
      v.contactTorqueWorld += w.torqueOnVoxmapWorld;
      v.contacts += w.contactPoints;
      v.maxDepthM = std::max(v.maxDepthM, w.maxDepthM);
    }
  }

  for (std::size_t i = 0; i < n; ++i) {
    const MovingObjectModel& object = model.objects[i];
    ObjectFrame& f = state.last[i];
    RigidBodyState& body = state.bodies[i];
    glm::dvec3 force = f.contactForceWorld + object.body.massKg * model.gravityWorld;
    glm::dvec3 torque = f.contactTorqueWorld;
    CouplingWrench coupling;
    if (object.coupled && i < handles.size()) {
      coupling = couplingWrench(object.gains, handles[i].poseWorld, handles[i].velocity.linearWorld,
                                handles[i].velocity.angularWorld, object.body, body);
      force += coupling.forceWorld;
      torque += coupling.torqueWorld;
      f.feedback = deviceFeedback(coupling, model.deviceLimits);
    }
    const RigidBodyState before = body;
    integrate(object.body, body, force, torque, model.dtS);
    f.travelLimited = limitTravel(before, body, object.shellRadiusM, object.maxTravelM);
    state.travelLimitedFrames += f.travelLimited ? 1 : 0;
  }
  ++state.frame;
  state.timeS = static_cast<double>(state.frame) * model.dtS;
}

}  // namespace voxhap
