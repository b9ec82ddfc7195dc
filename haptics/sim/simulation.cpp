#include "haptics/sim/simulation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "haptics/coherence/max_travel.h"
#include "haptics/collide/tangent_plane_force.h"
#include "haptics/sim/pair_geometry.h"

namespace voxhap {
namespace {

/// Holds the step from `before` to `after` to at most `maxTravelM` of any point at most
/// `radiusM` from the centre of mass; velocities shrink by the same factor.
bool limitTravel(const RigidBodyState& before, RigidBodyState& after, double radiusM, double maxTravelM) {
  const double angle = glm::length(rotationVector(after.orientation * glm::conjugate(before.orientation)));
  const double travel = glm::length(after.comWorld - before.comWorld) + angle * radiusM;
  if (!(travel > maxTravelM)) return false;
  const double f = maxTravelM / travel;
  after.comWorld = before.comWorld + (after.comWorld - before.comWorld) * f;
  after.orientation = f > 0.0 ? slerpShortest(before.orientation, after.orientation, f) : before.orientation;
  after.linearVelocityWorld *= f;
  after.angularVelocityWorld *= f;
  return true;
}

}  // namespace

bool setForceLayer(const SimModel& model, SimState& state, SimWorkspace& workspace,
                   std::uint8_t value) noexcept {
  if (!model.forceLayerInRange(value)) return false;
  state.forceLayer = value;
  for (std::size_t p = 0; p < workspace.coherence.size(); ++p)
    workspace.coherence[p].setForceLayer(model.pairs[p].forceLayer(value));
  return true;
}

FrameStatus stepWithDevices(const SimModel& model, SimState& state, SimWorkspace& workspace,
                            std::span<HapticDevice* const> devices, std::span<HandleInput> handles,
                            FrameInputs inputs, FrameOutputs& outputs) noexcept {
  const double t = state.timeS + model.dtS;
  for (std::size_t i = 0; i < devices.size(); ++i) {
    // an object without a device is free, not held where a device last left its handle
    handles[i] = devices[i] ? HandleInput{devices[i]->handlePose(t), devices[i]->handleVelocity(t), true}
                            : HandleInput{{}, {}, false};
  }
  inputs.handles = handles;
  const FrameStatus status = step(model, state, workspace, inputs, outputs);
  for (std::size_t i = 0; i < devices.size(); ++i) {
    if (devices[i]) devices[i]->setFeedback(outputs.objects[i].feedback);
  }
  return status;
}

Pose objectPose(const SimModel& model, const SimState& state, std::size_t object) noexcept {
  return state.bodies[object].pose(model.objects[object].body);
}

namespace {

/// Whether `object` moves only as its remote owner's stream says this frame: a remote body
/// that is not yielding to the depth limits (depth_limit.h).
bool onlyStreamed(int object, std::span<const KinematicInput> kinematic, const DepthLimitScratch& s) {
  if (object == kStaticEnvironment) return true;
  const auto i = static_cast<std::size_t>(object);
  return i < kinematic.size() && kinematic[i].active && !s.deltas[i].yielding;
}

/// Whether nothing here can move `pair`'s bodies but one owner's stream: its owner's peer
/// simulates that pair, and its stream shows the result. Two owners' streams, each played
/// out a delay of its own behind its owner, can carry their parts into each other here: such
/// a pair is tested here like any other, and its parts yield (depth_limit.h).
bool leftToOneOwner(const PairModel& pair, const SimState& state, std::span<const KinematicInput> kinematic,
                    const DepthLimitScratch& s) {
  if (!onlyStreamed(pair.shellObject, kinematic, s) || !onlyStreamed(pair.voxmapObject, kinematic, s))
    return false;
  auto owner = [&state](int object) {
    const auto i = static_cast<std::size_t>(object);
    return i < state.owners.size() ? state.owners[i] : kNoPeer;
  };
  return pair.voxmapObject == kStaticEnvironment || owner(pair.shellObject) == owner(pair.voxmapObject);
}

/// Step 1: which pairs are in range, every object's MaxTravel bound, and Eq. 2 over them.
/// A pair left to one owner (leftToOneOwner) counts as out of range.
void planFrame(const SimModel& model, const SimState& state, std::span<const KinematicInput> kinematic,
               SimWorkspace& ws, CoherenceFrame& plan) {
  const bool coherent = !ws.coherence.empty();
  for (double& bound : ws.travelBoundM) bound = std::numeric_limits<double>::infinity();
  for (std::size_t p = 0; p < model.pairs.size(); ++p) {
    const PairModel& pair = model.pairs[p];
    PairFrame& frame = ws.pairFrames[p];
    const Voxmap& voxmap = model.voxmapOf(pair);
    const Pose shellToVoxmap = shellToVoxmapPose(model, state, pair);
    frame.inRange =
        !leftToOneOwner(pair, state, kinematic, ws.depthScratch) &&
        inRange(model.objects[static_cast<std::size_t>(pair.shellObject)], shellToVoxmap, voxmap.grid());
    if (frame.inRange) frame.transform = VoxelTransform::make(shellToVoxmap, voxmap.grid());
    ws.counters.pairsSkipped += frame.inRange ? 0 : 1;
    const bool far = coherent && (!frame.inRange || ws.coherence[p].onlyCollapsed());
    for (const int i : {pair.shellObject, pair.voxmapObject}) {
      if (i == kStaticEnvironment) continue;
      double& bound = ws.travelBoundM[static_cast<std::size_t>(i)];
      bound = std::min(bound, far ? pair.farTravelM : pair.nearTravelM);
    }
  }
  double mandatory = 0.0;
  TestsByTravel tests{};
  for (std::size_t p = 0; p < model.pairs.size(); ++p) {
    const PairModel& pair = model.pairs[p];
    PairFrame& frame = ws.pairFrames[p];
    frame.relativeTravelBoundM = ws.travelBoundM[static_cast<std::size_t>(pair.shellObject)];
    if (pair.voxmapObject != kStaticEnvironment) {
      frame.relativeTravelBoundM += ws.travelBoundM[static_cast<std::size_t>(pair.voxmapObject)];
    }
    if (coherent && frame.inRange) {
      const CoherenceLoad pairLoad = ws.coherence[p].load(frame.relativeTravelBoundM);
      mandatory += pairLoad.mandatory;
      for (std::size_t k = 0; k < tests.size(); ++k) tests[k] += pairLoad.tests[k];
    }
  }
  const bool missedBefore = ws.lastDeadlineMissed;
  plan = CoherenceFrame{};
  ws.lastDeadlineMissed = false;
  if (!coherent) return;
  plan.capacityTests = model.coherence.capacityTests > 0.0
                           ? model.coherence.capacityTests
                           : model.coherence.testBudgetFraction * model.dtS / ws.testCostS;
  plan.plannedLoad = tests.back();
  const TravelBudget budget = travelScale(plan.capacityTests, mandatory, tests);
  // The first frame with more mandatory tests than capacity stops everything (MaxTravel =
  // 0). If the next is short too, time-criticality is abandoned (paper §5) until it is
  // not: frames test what full MaxTravel needs however long they take, and count as
  // missed. Stopped for good, a part pressed onto more contacts than the capacity could
  // never be pulled free (the seated ball, a tile pressed into a plate).
  plan.travelScale = budget.deadlineMissed && missedBefore ? 1.0 : budget.scale;
  plan.deadlineMissed = budget.deadlineMissed;
  plan.mandatory = static_cast<std::uint32_t>(mandatory);
  ws.lastDeadlineMissed = budget.deadlineMissed;
  ws.counters.missedDeadlines += budget.deadlineMissed ? 1 : 0;
}

/// Step 2 for one pair in range: its contacts, in ws.contacts; returns how many, and
/// adds its tests to `tested` and its lookups of paged-out voxels to `missing`.
std::uint32_t findContacts(const SimModel& model, SimWorkspace& ws, CoherenceFrame& plan, std::size_t p,
                           const ContactParams& params, std::uint32_t& tested, std::uint32_t& missing) {
  const PairModel& pair = model.pairs[p];
  const Pointshell& shell = model.objects[static_cast<std::size_t>(pair.shellObject)].shell;
  const Voxmap& voxmap = model.voxmapOf(pair);
  const std::uint8_t sampledLayer = params.sampledLayer(voxmap.encoding().maxValue());
  const VoxelTransform& transform = ws.pairFrames[p].transform;
  if (ws.coherence.empty()) {
    const auto points = static_cast<std::uint32_t>(shell.size());
    tested += points;
    return samplePoints(shell, voxmap, transform, pair.fieldShifts, sampledLayer, 0, points,
                        ws.contacts.data());
  }
  PairCoherence& coherence = ws.coherence[p];
  const double travelM = plan.travelScale * ws.pairFrames[p].relativeTravelBoundM;
  VoxelPager* pager = ws.pagerOf(pair);
  plan.chunkTests += coherence.updateChunks(shell, voxmap, transform, ws.dueChunks, pager);
  const std::uint32_t due = coherence.collectDue(ws.due);
  tested += due;
  const PairCoherence::Tested t =
      coherence.testDue(shell, voxmap, transform, pair.fieldShifts, sampledLayer,
                        std::span(ws.due.data(), due), ws.contacts.data(), pager, ws.helper.get());
  plan.drifted += t.drifted;
  missing += t.missing;
  coherence.endFrame(travelM);
  return t.contacts;
}

/// Adds `contacts`' points in the force layer (`forceLayer` or below) to `sample`, spread
/// evenly over them when there are more than its room.
void sampleContacts(const Pointshell& shell, const Pose& shellWorld, std::span<const PointContact> contacts,
                    std::uint8_t forceLayer, ContactSample& sample) {
  const std::size_t picks = std::min(ContactSample::kCapacity - sample.count, contacts.size());
  for (std::size_t k = 0; k < picks; ++k) {
    const PointContact& c = contacts[k * contacts.size() / picks];
    if (c.value > forceLayer) continue;
    sample.pointsWorld[sample.count++] =
        glm::vec3(apply(shellWorld, glm::dvec3(shell.positionsLocal[c.point])));
  }
}

/// Paper §5.3: a frame that needed voxels still paged out moves nothing and sends no
/// force; past kMaxSuspensionS of suspension in a row (by the caller's clock) the run stops.
void suspendOrResume(SimWorkspace& ws, bool suspend, std::chrono::steady_clock::time_point now) {
  Suspensions& s = ws.suspensions;
  if (!suspend) {
    s.active = false;
    return;
  }
  if (!s.active) {
    s.active = true;
    s.since = now;
    ++s.count;
  }
  ++s.frames;
  const double seconds = std::chrono::duration<double>(now - s.since).count();
  s.longestS = std::max(s.longestS, seconds);
  if (seconds > kMaxSuspensionS) ws.stopped = true;
}

/// A kinematic body goes where its target says, when the target is a finite pose with a
/// unit orientation; otherwise it stays and the frame says so.
void moveKinematic(const RigidBodyState& target, RigidBodyState& body, FrameStatus& status) {
  if (!isFiniteWithUnitOrientation(target)) {
    status |= kFrameNonFiniteZeroed;
    return;
  }
  body.comWorld = target.comWorld;
  body.orientation = target.orientation;
  body.linearVelocityWorld = target.linearVelocityWorld;
  body.angularVelocityWorld = target.angularVelocityWorld;
}

bool finite(const HandleInput& h) {
  return isFinite(h.poseWorld) && isFinite(h.velocity.linearWorld) && isFinite(h.velocity.angularWorld);
}

}  // namespace

FrameStatus step(const SimModel& model, SimState& state, SimWorkspace& ws, const FrameInputs& inputs,
                 FrameOutputs& outputs) noexcept {
  if (ws.stopped) return kFrameStopped;
  FrameStatus status = 0;
  if (ws.staticPager) ws.staticPager->beginFrame();
  const std::size_t n = model.objects.size();
  for (ObjectFrame& f : outputs.objects) f = ObjectFrame{};
  CoherenceFrame& plan = outputs.coherence;
  // the capacity measured online: a smoothed cost per test, from the caller's timing of
  // frames with enough tests to outweigh a frame's fixed cost
  constexpr std::uint32_t kMeasuredTests = 1000;
  if (inputs.previousStepS > 0.0 && std::isfinite(inputs.previousStepS) && ws.lastTested >= kMeasuredTests) {
    ws.testCostS = 0.9 * ws.testCostS + 0.1 * inputs.previousStepS / ws.lastTested;
  }
  planFrame(model, state, inputs.kinematic, ws, plan);

  std::uint32_t testedInFrame = 0;
  std::uint32_t missing = 0;
  std::size_t rowCount = 0;
  for (std::size_t p = 0; p < model.pairs.size(); ++p) {
    const PairModel& pair = model.pairs[p];
    if (!ws.pairFrames[p].inRange) {
      if (!ws.coherence.empty())
        ws.coherence[p].skipFrame(plan.travelScale * ws.pairFrames[p].relativeTravelBoundM);
      continue;
    }
    ContactParams params = pair.params;
    params.forceLayer = pair.forceLayer(state.forceLayer);
    std::uint32_t tested = 0;
    const std::uint32_t found = findContacts(model, ws, plan, p, params, tested, missing);
    testedInFrame += tested;
    const MovingObjectModel& shellObject = model.objects[static_cast<std::size_t>(pair.shellObject)];
    // rows for the contacts that the step can take past their limit (depth_limit.h)
    const double limitM = depthLimitM(params, model.voxmapOf(pair).grid().voxelSizeM);
    const DepthRowSink sink{std::span(ws.depthScratch.rows).subspan(rowCount),
                            limitM - ws.pairFrames[p].relativeTravelBoundM};
    const BodyMotion shellMotion = motionOf(model, state, pair.shellObject);
    const std::span<const PointContact> contacts(ws.contacts.data(), found);
    const PairWrench w =
        tangentPlaneWrench(shellObject.shell, model.voxmapOf(pair), params, shellMotion,
                           motionOf(model, state, pair.voxmapObject), contacts, &sink, ws.helper.get());
    for (std::size_t r = rowCount; r < rowCount + w.depthRows; ++r) {
      DepthRow& row = ws.depthScratch.rows[r];
      row.limitM = limitM;
      row.shellObject = pair.shellObject;
      row.voxmapObject = pair.voxmapObject;
    }
    rowCount += w.depthRows;
    missing += w.missingVoxels;
    if (w.missingVoxels > 0 && ws.pagerOf(pair)) {
      const glm::ivec3 chunk = w.firstMissingVoxel >> kChunkEdgeLog2;
      ws.pagerOf(pair)->request(chunk - 1, chunk + 1);
    }
    ObjectFrame& s = outputs.objects[static_cast<std::size_t>(pair.shellObject)];
    s.contactForceWorld += w.forceOnShellWorld;
    s.contactTorqueWorld += w.torqueOnShellWorld;
    s.contacts += w.contactPoints;
    s.tested += tested;
    s.maxDepthM = std::max(s.maxDepthM, w.maxDepthM);
    sampleContacts(shellObject.shell, shellMotion.poseWorld, contacts, params.forceLayer, s.contactSample);
    if (pair.voxmapObject != kStaticEnvironment) {
      ObjectFrame& v = outputs.objects[static_cast<std::size_t>(pair.voxmapObject)];
      v.contactForceWorld += w.forceOnVoxmapWorld;
      v.contactTorqueWorld += w.torqueOnVoxmapWorld;
      v.contacts += w.contactPoints;
      v.maxDepthM = std::max(v.maxDepthM, w.maxDepthM);
    }
  }
  plan.tested = testedInFrame;
  ws.lastTested = testedInFrame;
  suspendOrResume(ws, missing > 0, inputs.now);
  if (ws.suspensions.active) {
    status |= kFrameSuspended;
    plan.travelScale = 0.0;
    for (ObjectFrame& f : outputs.objects) f.contactForceWorld = f.contactTorqueWorld = glm::dvec3(0.0);
  }
  if (plan.deadlineMissed) status |= kFrameDeadlineMissed;

  for (std::size_t i = 0; i < n; ++i) {
    const MovingObjectModel& object = model.objects[i];
    ObjectFrame& f = outputs.objects[i];
    RigidBodyState& body = state.bodies[i];
    glm::dvec3 force = f.contactForceWorld + object.body.massKg * model.gravityWorld;
    glm::dvec3 torque = f.contactTorqueWorld;
    if (i < inputs.externalWrenches.size()) {
      const ExternalWrench& external = inputs.externalWrenches[i];
      if (isFinite(external.forceWorld) && isFinite(external.torqueWorld)) {
        force += external.forceWorld;
        torque += external.torqueWorld;
      } else {
        status |= kFrameNonFiniteZeroed;
      }
    }
    if (object.coupled && i < inputs.handles.size() && inputs.handles[i].held) {
      const HandleInput& handle = inputs.handles[i];
      if (finite(handle)) {
        const CouplingGains& gains = i < inputs.couplingGains.size() ? inputs.couplingGains[i] : object.gains;
        const CouplingWrench coupling = couplingWrench(gains, handle.poseWorld, handle.velocity.linearWorld,
                                                       handle.velocity.angularWorld, object.body, body);
        // the body feels what the device renders (negated), never more: a handle that leads
        // far pulls with the device's largest force, not with a spring stretched without bound
        const CouplingWrench felt = deviceFeedback(coupling, model.deviceLimits);
        force -= felt.forceWorld;
        torque -= felt.torqueWorld;
        if (!ws.suspensions.active) f.feedback = felt;
        if (felt.nonFiniteZeroed) status |= kFrameNonFiniteZeroed;
      } else {
        status |= kFrameNonFiniteZeroed;  // a handle that is not a pose holds nothing this frame
      }
    }
    ws.beforeStep[i] = body;
    const bool kinematic = i < inputs.kinematic.size() && inputs.kinematic[i].active;
    ws.depthScratch.deltas[i].kinematic = kinematic;
    if (kinematic) {
      moveKinematic(inputs.kinematic[i].targetWorld, body, status);
    } else {
      integrate(object.body, body, force, torque, model.dtS);
    }
    if (body.skippedSteps != ws.beforeStep[i].skippedSteps) status |= kFrameNonFiniteZeroed;
    // an object without pairs has an infinite bound, which no scale makes finite
    const double bound = ws.travelBoundM[i];
    f.maxTravelM = std::isinf(bound) ? bound : plan.travelScale * bound;
    f.travelLimited = limitTravel(ws.beforeStep[i], body, object.shellRadiusM, f.maxTravelM);
    ws.depthScratch.deltas[i].maxTravelM = f.maxTravelM;
  }
  outputs.depthLimit =
      limitDepths(model.objects, ws.beforeStep, state.bodies, ws.depthScratch, rowCount, model.dtS);
  ws.counters.depthLimitedFrames += outputs.depthLimit.binding > 0 ? 1 : 0;
  for (std::size_t i = 0; i < n; ++i) {
    // what the limits refused (a pair's limit, a row's own or the last pass's scale) is
    // the contacts' push beyond their springs
    const DepthLimitScratch::Delta& refused = ws.depthScratch.deltas[i];
    if (refused.refusedLinear == glm::dvec3(0.0) && refused.refusedAngular == glm::dvec3(0.0)) continue;
    const RigidBodyModel& body = model.objects[i].body;
    const double perH2 = 1.0 / (model.dtS * model.dtS);
    ObjectFrame& f = outputs.objects[i];
    f.contactForceWorld -= body.massKg * perH2 * refused.refusedLinear;
    const glm::dmat3 r = glm::mat3_cast(ws.beforeStep[i].orientation);
    f.contactTorqueWorld -= perH2 * (r * (body.inertiaBody * (glm::transpose(r) * refused.refusedAngular)));
  }
  for (ObjectFrame& f : outputs.objects) {
    f.travelLimited = f.travelLimited || outputs.depthLimit.travelBound;
    ws.counters.travelLimitedFrames += f.travelLimited ? 1 : 0;
  }
  ++state.frame;
  state.timeS = static_cast<double>(state.frame) * model.dtS;
  if (ws.stopped) status |= kFrameStopped;
  return status;
}

}  // namespace voxhap
