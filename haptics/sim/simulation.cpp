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
  after.orientation = f > 0.0 ? slerpShortest(before.orientation, after.orientation, f) : before.orientation;
  after.linearVelocityWorld *= f;
  after.angularVelocityWorld *= f;
  return true;
}

}  // namespace

SimState makeSimState(const SimModel& model) {
  SimState state;
  std::size_t largest = 0;
  std::size_t mostChunks = 0;
  for (const MovingObjectModel& object : model.objects) {
    state.bodies.push_back(restingState(object.body));
    largest = std::max(largest, object.shell.size());
    mostChunks = std::max(mostChunks, object.shell.chunkCount());
  }
  state.last.resize(model.objects.size());
  state.beforeStep.resize(model.objects.size());
  std::size_t rowCapacity = 0;
  for (const PairModel& pair : model.pairs) rowCapacity += model.objects[static_cast<std::size_t>(pair.shellObject)].shell.size();
  state.depthScratch = DepthLimitScratch(rowCapacity, model.pairs.size(), model.objects.size());
  state.travelBoundM.resize(model.objects.size());
  state.scratch.resize(largest);
  state.due.resize(largest);
  state.dueChunks.resize(mostChunks);
  state.pairFrames.resize(model.pairs.size());
  if (!model.pairs.empty()) state.forceLayer = model.pairs.front().params.forceLayer;
  if (!model.coherence.enabled) return state;
  for (std::size_t p = 0; p < model.pairs.size(); ++p) {
    const PairModel& pair = model.pairs[p];
    const MovingObjectModel& shellObject = model.objects[static_cast<std::size_t>(pair.shellObject)];
    const Voxmap& voxmap = model.voxmapOf(pair);
    PairCoherence& coherence =
        state.coherence.emplace_back(shellObject.shell, voxmap.grid().voxelSizeM, state.forceLayer,
                                     voxmap.encoding().maxValue(), model.coherence.pointDrifting);
    const Pose shellToVoxmap = compose(inverse(motionOf(model, state, pair.voxmapObject).poseWorld),
                                       motionOf(model, state, pair.shellObject).poseWorld);
    if (inRange(shellObject, shellToVoxmap, voxmap.grid())) {
      coherence.sortAll(shellObject.shell, voxmap, VoxelTransform::make(shellToVoxmap, voxmap.grid()),
                        pair.fieldShifts, model.pagerOf(pair));
    } else {
      coherence.skipFrame(0.0);
    }
  }
  return state;
}

bool setForceLayer(const SimModel& model, SimState& state, std::uint8_t value) noexcept {
  if (value < 1) return false;
  for (const PairModel& pair : model.pairs) {
    if (value > model.voxmapOf(pair).encoding().maxValue()) return false;
  }
  state.forceLayer = value;
  for (PairCoherence& c : state.coherence) c.setForceLayer(value);
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

namespace {

/// Step 1: which pairs are in range, every object's MaxTravel bound, and Eq. 2 over them.
void planFrame(const SimModel& model, SimState& state) {
  const bool coherent = !state.coherence.empty();
  for (double& bound : state.travelBoundM) bound = std::numeric_limits<double>::infinity();
  for (std::size_t p = 0; p < model.pairs.size(); ++p) {
    const PairModel& pair = model.pairs[p];
    PairFrame& frame = state.pairFrames[p];
    const Voxmap& voxmap = model.voxmapOf(pair);
    const Pose shellToVoxmap = compose(inverse(motionOf(model, state, pair.voxmapObject).poseWorld),
                                       motionOf(model, state, pair.shellObject).poseWorld);
    frame.inRange = inRange(model.objects[static_cast<std::size_t>(pair.shellObject)], shellToVoxmap, voxmap.grid());
    if (frame.inRange) frame.transform = VoxelTransform::make(shellToVoxmap, voxmap.grid());
    state.pairsSkipped += frame.inRange ? 0 : 1;
    const bool far = coherent && (!frame.inRange || state.coherence[p].onlyCollapsed());
    for (const int i : {pair.shellObject, pair.voxmapObject}) {
      if (i == kStaticEnvironment) continue;
      double& bound = state.travelBoundM[static_cast<std::size_t>(i)];
      bound = std::min(bound, far ? pair.farTravelM : pair.nearTravelM);
    }
  }
  double mandatory = 0.0;
  double load = 0.0;
  for (std::size_t p = 0; p < model.pairs.size(); ++p) {
    const PairModel& pair = model.pairs[p];
    PairFrame& frame = state.pairFrames[p];
    frame.relativeTravelBoundM = state.travelBoundM[static_cast<std::size_t>(pair.shellObject)];
    if (pair.voxmapObject != kStaticEnvironment) {
      frame.relativeTravelBoundM += state.travelBoundM[static_cast<std::size_t>(pair.voxmapObject)];
    }
    if (coherent && frame.inRange) {
      const CoherenceLoad pairLoad = state.coherence[p].load();
      mandatory += pairLoad.mandatory;
      load += pairLoad.testsPerM * frame.relativeTravelBoundM;
    }
  }
  CoherenceFrame& plan = state.coherent;
  const bool missedBefore = plan.deadlineMissed;
  plan = CoherenceFrame{};
  if (!coherent) return;
  plan.capacityTests = model.coherence.capacityTests > 0.0
                           ? model.coherence.capacityTests
                           : model.coherence.testBudgetFraction * model.dtS / state.testCostS;
  // the sweeps may take more than Eq. 3's quotas where a queue's points crowd into a run of
  // indices (pair_coherence.h): plan with the excess measured so far
  plan.plannedLoad = load * state.sweepExcess;
  const TravelBudget budget = travelScale(plan.capacityTests, mandatory, plan.plannedLoad);
  // The first frame with more mandatory tests than capacity stops everything (MaxTravel =
  // 0). If the next is short too, time-criticality is abandoned (paper §5) until it is
  // not: frames test what full MaxTravel needs however long they take, and count as
  // missed. Stopped for good, a part pressed onto more contacts than the capacity could
  // never be pulled free (the seated ball, a tile pressed into a plate).
  plan.travelScale = budget.deadlineMissed && missedBefore ? 1.0 : budget.scale;
  plan.deadlineMissed = budget.deadlineMissed;
  plan.mandatory = static_cast<std::uint32_t>(mandatory);
  state.missedDeadlines += budget.deadlineMissed ? 1 : 0;
}

/// Step 2 for one pair in range: its contacts, in state.scratch; returns how many, and
/// adds its tests to `tested` and its lookups of paged-out voxels to `missing`.
std::uint32_t findContacts(const SimModel& model, SimState& state, std::size_t p, std::uint32_t& tested,
                           std::uint32_t& missing) {
  const PairModel& pair = model.pairs[p];
  const Pointshell& shell = model.objects[static_cast<std::size_t>(pair.shellObject)].shell;
  const Voxmap& voxmap = model.voxmapOf(pair);
  ContactParams params = pair.params;
  params.forceLayer = state.forceLayer;
  const std::uint8_t sampledLayer = params.sampledLayer(voxmap.encoding().maxValue());
  const VoxelTransform& transform = state.pairFrames[p].transform;
  if (state.coherence.empty()) {
    const auto points = static_cast<std::uint32_t>(shell.size());
    tested += points;
    return samplePoints(shell, voxmap, transform, pair.fieldShifts, sampledLayer, 0, points, state.scratch.data());
  }
  PairCoherence& coherence = state.coherence[p];
  const double travelM = state.coherent.travelScale * state.pairFrames[p].relativeTravelBoundM;
  VoxelPager* pager = model.pagerOf(pair);
  state.coherent.chunkTests += coherence.updateChunks(shell, voxmap, transform, travelM, state.dueChunks, pager);
  const std::uint32_t due = coherence.collectDue(travelM, state.due);
  tested += due;
  const PairCoherence::Tested t = coherence.testDue(shell, voxmap, transform, pair.fieldShifts, sampledLayer,
                                                   std::span(state.due.data(), due), state.scratch.data(), pager);
  state.coherent.drifted += t.drifted;
  missing += t.missing;
  coherence.endFrame(travelM);
  return t.contacts;
}

/// Paper §5.3: a frame that needed voxels still paged out moves nothing and sends no
/// force; past kMaxSuspensionS of suspension in a row the run stops.
void suspendOrResume(SimState& state, bool suspend, std::chrono::steady_clock::time_point now) {
  Suspensions& s = state.suspensions;
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
  if (seconds > kMaxSuspensionS) state.stopped = true;
}

}  // namespace

void step(const SimModel& model, SimState& state, std::span<const HandleInput> handles) noexcept {
  if (state.stopped) return;
  if (model.staticPager) model.staticPager->beginFrame();
  const std::size_t n = model.objects.size();
  for (ObjectFrame& f : state.last) f = ObjectFrame{};
  planFrame(model, state);

  const auto started = std::chrono::steady_clock::now();
  std::uint32_t testedInFrame = 0;
  std::uint32_t missing = 0;
  std::size_t rowCount = 0;
  for (std::size_t p = 0; p < model.pairs.size(); ++p) {
    const PairModel& pair = model.pairs[p];
    if (!state.pairFrames[p].inRange) {
      if (!state.coherence.empty()) {
        state.coherence[p].skipFrame(state.coherent.travelScale * state.pairFrames[p].relativeTravelBoundM);
      }
      continue;
    }
    std::uint32_t tested = 0;
    const std::uint32_t found = findContacts(model, state, p, tested, missing);
    testedInFrame += tested;
    ContactParams params = pair.params;
    params.forceLayer = state.forceLayer;
    const MovingObjectModel& shellObject = model.objects[static_cast<std::size_t>(pair.shellObject)];
    // rows for the contacts that the step can take past their limit (depth_limit.h)
    const double limitM = kDepthLimitVoxels * model.voxmapOf(pair).grid().voxelSizeM;
    const DepthRowSink sink{std::span(state.depthScratch.rows).subspan(rowCount),
                            limitM - state.pairFrames[p].relativeTravelBoundM};
    const PairWrench w = tangentPlaneWrench(shellObject.shell, model.voxmapOf(pair), params,
                                            motionOf(model, state, pair.shellObject),
                                            motionOf(model, state, pair.voxmapObject),
                                            std::span(state.scratch.data(), found), &sink);
    for (std::size_t r = rowCount; r < rowCount + w.depthRows; ++r) {
      DepthRow& row = state.depthScratch.rows[r];
      row.limitM = limitM;
      row.shellObject = pair.shellObject;
      row.voxmapObject = pair.voxmapObject;
    }
    rowCount += w.depthRows;
    missing += w.missingVoxels;
    if (w.missingVoxels > 0 && model.pagerOf(pair)) {
      const glm::ivec3 chunk = w.firstMissingVoxel >> kChunkEdgeLog2;
      model.pagerOf(pair)->request(chunk - 1, chunk + 1);
    }
    ObjectFrame& s = state.last[static_cast<std::size_t>(pair.shellObject)];
    s.contactForceWorld += w.forceOnShellWorld;
    s.contactTorqueWorld += w.torqueOnShellWorld;
    s.contacts += w.contactPoints;
    s.tested += tested;
    s.maxDepthM = std::max(s.maxDepthM, w.maxDepthM);
    if (pair.voxmapObject != kStaticEnvironment) {
      ObjectFrame& v = state.last[static_cast<std::size_t>(pair.voxmapObject)];
      v.contactForceWorld += w.forceOnVoxmapWorld;
      v.contactTorqueWorld += w.torqueOnVoxmapWorld;
      v.contacts += w.contactPoints;
      v.maxDepthM = std::max(v.maxDepthM, w.maxDepthM);
    }
  }
  state.coherent.tested = testedInFrame;
  // what the sweeps took beyond the mandatory tests, over what Eq. 3 asked (enough of
  // them to be a fair sample): a smoothed ratio, at least one
  const CoherenceFrame& plan = state.coherent;
  const double asked = plan.travelScale * plan.plannedLoad / state.sweepExcess;
  const double taken = static_cast<double>(testedInFrame + plan.chunkTests) - static_cast<double>(plan.mandatory);
  if (asked >= 100.0 && !plan.deadlineMissed) {
    state.sweepExcess = std::max(1.0, 0.95 * state.sweepExcess + 0.05 * taken / asked);
  }
  suspendOrResume(state, missing > 0, std::chrono::steady_clock::now());
  if (state.suspensions.active) {
    state.coherent.travelScale = 0.0;
    for (ObjectFrame& f : state.last) f.contactForceWorld = f.contactTorqueWorld = glm::dvec3(0.0);
  }
  // the capacity measured online: a smoothed cost per test, from frames with enough tests
  // to outweigh the fixed cost of a pair
  constexpr std::uint32_t kMeasuredTests = 1000;
  if (testedInFrame >= kMeasuredTests) {
    const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - started;
    state.testCostS = 0.9 * state.testCostS + 0.1 * elapsed.count() / testedInFrame;
  }

  for (std::size_t i = 0; i < n; ++i) {
    const MovingObjectModel& object = model.objects[i];
    ObjectFrame& f = state.last[i];
    RigidBodyState& body = state.bodies[i];
    glm::dvec3 force = f.contactForceWorld + object.body.massKg * model.gravityWorld;
    glm::dvec3 torque = f.contactTorqueWorld;
    if (object.coupled && i < handles.size()) {
      const CouplingWrench coupling = couplingWrench(object.gains, handles[i].poseWorld, handles[i].velocity.linearWorld,
                                                     handles[i].velocity.angularWorld, object.body, body);
      // the body feels what the device renders (negated), never more: a handle that leads
      // far pulls with the device's largest force, not with a spring stretched without bound
      const CouplingWrench felt = deviceFeedback(coupling, model.deviceLimits);
      force -= felt.forceWorld;
      torque -= felt.torqueWorld;
      if (!state.suspensions.active) f.feedback = felt;
    }
    state.beforeStep[i] = body;
    integrate(object.body, body, force, torque, model.dtS);
    // an object without pairs has an infinite bound, which no scale makes finite
    const double bound = state.travelBoundM[i];
    f.maxTravelM = std::isinf(bound) ? bound : state.coherent.travelScale * bound;
    f.travelLimited = limitTravel(state.beforeStep[i], body, object.shellRadiusM, f.maxTravelM);
    state.travelLimitedFrames += f.travelLimited ? 1 : 0;
  }
  state.depthLimit = limitDepths(model.objects, state.beforeStep, state.bodies, state.depthScratch, rowCount, model.dtS);
  state.depthLimitedFrames += state.depthLimit.binding > 0 ? 1 : 0;
  for (std::size_t i = 0; i < n && state.depthLimit.binding > 0; ++i) {
    // what the limits refused is the contacts' push beyond their springs
    const DepthLimitScratch::Delta& refused = state.depthScratch.deltas[i];
    const RigidBodyModel& body = model.objects[i].body;
    const double perH2 = 1.0 / (model.dtS * model.dtS);
    ObjectFrame& f = state.last[i];
    f.contactForceWorld -= body.massKg * perH2 * refused.refusedLinear;
    const glm::dmat3 r = glm::mat3_cast(state.beforeStep[i].orientation);
    f.contactTorqueWorld -= perH2 * (r * (body.inertiaBody * (glm::transpose(r) * refused.refusedAngular)));
    // the projection moves points of the body by no more than it refused, but lever arms
    // could carry a far point past MaxTravel: hold it to MaxTravel again (a scaled step
    // still keeps every depth limit, depth_limit.h)
    f.travelLimited = limitTravel(state.beforeStep[i], state.bodies[i], model.objects[i].shellRadiusM, f.maxTravelM) ||
                      f.travelLimited;
  }
  ++state.frame;
  state.timeS = static_cast<double>(state.frame) * model.dtS;
}

}  // namespace voxhap
