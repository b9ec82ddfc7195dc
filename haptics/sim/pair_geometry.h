#pragma once
/// Where the two objects of a pair are relative to each other (internal to haptics/sim).

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "haptics/collide/tangent_plane_force.h"
#include "haptics/sim/sim_model.h"
#include "haptics/sim/sim_state.h"

namespace voxhap {

/// The motion of moving object `object` (kStaticEnvironment: at rest at the origin).
inline BodyMotion motionOf(const SimModel& model, const SimState& state, int object) {
  if (object == kStaticEnvironment) return {};
  const auto i = static_cast<std::size_t>(object);
  const RigidBodyState& body = state.bodies[i];
  return {body.pose(model.objects[i].body), model.objects[i].body.comLocal, body.linearVelocityWorld,
          body.angularVelocityWorld};
}

/// The pose of the pair's pointshell object in its voxmap object's frame.
inline Pose shellToVoxmapPose(const SimModel& model, const SimState& state, const PairModel& pair) {
  return compose(inverse(motionOf(model, state, pair.voxmapObject).poseWorld),
                 motionOf(model, state, pair.shellObject).poseWorld);
}

/// Whether the shell's bounding sphere (voxmap frame) reaches the voxmap's grid box.
inline bool inRange(const MovingObjectModel& shellObject, const Pose& shellToVoxmap, const VoxelGrid& grid) {
  const glm::dvec3 centre = apply(shellToVoxmap, shellObject.shellCentreLocal);
  const glm::dvec3 lo = grid.originLocal;
  const glm::dvec3 hi = lo + glm::dvec3(grid.dimsVoxels()) * grid.voxelSizeM;
  const glm::dvec3 outside = glm::max(glm::dvec3(0.0), glm::max(lo - centre, centre - hi));
  return glm::dot(outside, outside) <= shellObject.shellBoundRadiusM * shellObject.shellBoundRadiusM;
}

}  // namespace voxhap
