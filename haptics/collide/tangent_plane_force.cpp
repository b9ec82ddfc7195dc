#include "haptics/collide/tangent_plane_force.h"

#include <algorithm>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "haptics/collide/surface_distance.h"

namespace voxhap {
namespace {

/// Unit direction, voxmap frame, in which the field at `shift` falls around `ijk`
/// (far counts as one more than the largest value); zero where it is flat. A neighbour
/// paged out (paged voxmap) counts as the centre and is noted in `out`.
glm::dvec3 fallDirection(const Voxmap& voxmap, const glm::ivec3& ijk, std::uint8_t shift, PairWrench& out) {
  const VoxelEncoding& e = voxmap.encoding();
  const std::array<VoxelWord, 7> words = voxmap.wordsAround(ijk);
  std::array<int, 7> values;  // −1: paged out
  for (std::size_t n = 0; n < values.size(); ++n) {
    if (words[n] == Voxmap::kMissingWord) {
      if (out.missingVoxels++ == 0) out.firstMissingVoxel = ijk + Voxmap::kAroundSteps[n];
      values[n] = -1;
      continue;
    }
    const auto value = static_cast<int>((words[n] >> shift) & e.fieldMask());
    values[n] = value == kValueFar ? e.maxValue() + 1 : value;
  }
  const int centre = values[0];
  // whole vectors, not one component at a time: a vector written by component and read
  // whole stalled on store forwarding (perf, contactWrenches)
  auto fallAlong = [&](std::size_t below, std::size_t above) {
    return double((values[below] < 0 ? centre : values[below]) -
                  (values[above] < 0 ? centre : values[above]));
  };
  const glm::dvec3 g(fallAlong(1, 2), fallAlong(3, 4), fallAlong(5, 6));
  const double length = glm::length(g);
  return length > 0.0 ? g / length : g;
}

/// The contact normal (toward the voxmap object), by what the point meets: the field it
/// samples names the voxmap object's feature. A vertex there (surface points under
/// geometrical awareness): the point's own normal `n`. A surface (vertex points, or any
/// point without awareness): the surface's normal, the field's fall direction `g` (a
/// corner or edge has no normal of its own worth pushing along, and a surface point on
/// the side of a part resting on a plate would push sideways along its own normal). An
/// edge (edge points): between the two.
glm::dvec3 pushDirectionOf(const Voxmap& voxmap, const PointContact& contact, PointFeature feature,
                           bool aware, std::uint8_t fieldShift, const glm::dvec3& n, PairWrench& out) {
  if (feature == PointFeature::Surface && aware) return n;
  glm::dvec3 g = fallDirection(voxmap, contact.ijkVoxel, fieldShift, out);
  if (g == glm::dvec3(0.0)) g = n;
  if (feature != PointFeature::Edge || !aware) return g;
  const glm::dvec3 between = n + g;
  const double length = glm::length(between);
  return length > 1e-6 ? between / length : n;
}

}  // namespace

PairWrench tangentPlaneWrench(const Pointshell& shell, const Voxmap& voxmap, const ContactParams& params,
                              const BodyMotion& shellMotion, const BodyMotion& voxmapMotion,
                              std::span<const PointContact> contacts, const DepthRowSink* sink) noexcept {
  PairWrench out;
  if (contacts.empty()) return out;
  const Pose shellToVoxmap = compose(inverse(voxmapMotion.poseWorld), shellMotion.poseWorld);
  const glm::dmat3 shellToVoxmapRotation = glm::mat3_cast(shellToVoxmap.orientation);
  const glm::dvec3 shellComInVoxmap = apply(shellToVoxmap, shellMotion.comLocal);
  const glm::dvec3 shellComWorld = apply(shellMotion.poseWorld, shellMotion.comLocal);
  const glm::dvec3 voxmapComWorld = apply(voxmapMotion.poseWorld, voxmapMotion.comLocal);
  // velocity of the shell relative to the voxmap object at a point p of the voxmap frame:
  // linear + angular × p, both constant over the frame's contacts
  const Pose worldToVoxmap = inverse(voxmapMotion.poseWorld);
  const glm::dvec3 angular =
      applyRotation(worldToVoxmap, shellMotion.angularVelocityWorld - voxmapMotion.angularVelocityWorld);
  const glm::dvec3 linearWorld =
      shellMotion.linearVelocityWorld - glm::cross(shellMotion.angularVelocityWorld, shellComWorld) -
      voxmapMotion.linearVelocityWorld + glm::cross(voxmapMotion.angularVelocityWorld, voxmapComWorld);
  // the velocity field v(x) = linearWorld + ω_rel × x in world, taken to the voxmap frame:
  // x = R p + t gives v = R⁻¹(linearWorld + ω_rel × t) + (R⁻¹ω_rel) × p
  const glm::dvec3 linear = applyRotation(
      worldToVoxmap,
      linearWorld + glm::cross(shellMotion.angularVelocityWorld - voxmapMotion.angularVelocityWorld,
                               voxmapMotion.poseWorld.position));
  const VoxelGrid& grid = voxmap.grid();
  const double s = grid.voxelSizeM;
  const auto shifts = fieldShiftsByFeature(params.geometricalAwareness, voxmap.encoding());
  const bool planes = params.surfaceContactM > 0.0 && voxmap.hasSurfacePlanes();

  // unscaled sums (voxmap frame), in contact [0] and damped before contact [1]; each is
  // capped on its own at the end
  glm::dvec3 force[2] = {glm::dvec3(0.0), glm::dvec3(0.0)};
  glm::dvec3 torque[2] = {glm::dvec3(0.0), glm::dvec3(0.0)};
  std::uint32_t acting[2] = {0, 0};
  for (const PointContact& c : contacts) {
    const glm::dvec3 p =
        shellToVoxmapRotation * glm::dvec3(shell.positionsLocal[c.point]) + shellToVoxmap.position;
    const bool beforeContact = c.value > params.forceLayer;
    const SurfacePlane* plane = planes ? voxmap.surfacePlane(c.ijkVoxel) : nullptr;
    // no plane: deep inside (the voxel's tangent plane stands in), or too far out to push
    if (planes && !plane && c.value > kValueFeature) continue;
    glm::dvec3 pushDirection;
    double depth = 0.0;
    if (plane && !beforeContact) {
      // the own plane bounds φ from below, so the depth from above: a point that can
      // neither push nor limit the step needs no neighbours' planes
      const double depthBoundM = params.surfaceContactM - ownPlaneDistanceM(grid, c.ijkVoxel, *plane, p);
      if (depthBoundM <= 0.0 && (!sink || depthBoundM <= sink->minDepthM)) {
        ++out.contactPoints;
        continue;
      }
    }
    if (plane) {
      const SurfaceDistance phi = surfaceDistance(voxmap, c.ijkVoxel, *plane, p);
      pushDirection = -phi.outwardUnit;
      if (!beforeContact) depth = params.surfaceContactM - phi.distanceM;
    } else {
      const glm::dvec3 n = shellToVoxmapRotation * glm::dvec3(shell.normalsLocal[c.point]);
      const PointFeature feature = shell.features[c.point];
      pushDirection = pushDirectionOf(voxmap, c, feature, params.geometricalAwareness,
                                      shifts[static_cast<std::size_t>(feature)], n, out);
      if (!beforeContact)
        depth = glm::dot(p - grid.voxelCentre(c.ijkVoxel), pushDirection) +
                static_cast<double>(params.forceLayer - c.value) * s;
    }
    out.contactPoints += beforeContact ? 0 : 1;
    if (sink && !beforeContact && depth > sink->minDepthM && out.depthRows < sink->rows.size()) {
      DepthRow& row = sink->rows[out.depthRows++];
      row.pointWorld = apply(voxmapMotion.poseWorld, p);
      row.intoVoxmapWorld = applyRotation(voxmapMotion.poseWorld, pushDirection);
      row.depthM = depth;
      row.floorM = sink->minDepthM;
      row.surfacePlane = plane != nullptr;
    }
    if (!beforeContact && depth <= 0.0) continue;
    const double approach = glm::dot(linear + glm::cross(angular, p), pushDirection);
    const double push =
        std::max(0.0, params.pointStiffnessNPerM * depth + params.pointDampingNsPerM * approach);
    if (push == 0.0) continue;
    out.maxDepthM = std::max(out.maxDepthM, depth);
    const glm::dvec3 f = -push * pushDirection;
    const int kind = beforeContact ? 1 : 0;
    ++acting[kind];
    force[kind] += f;
    torque[kind] += glm::cross(p - shellComInVoxmap, f);
  }
  glm::dvec3 totalForce(0.0);
  glm::dvec3 totalTorque(0.0);
  for (int kind = 0; kind < 2; ++kind) {
    const double scale = acting[kind] > kStiffContacts ? double(kStiffContacts) / double(acting[kind]) : 1.0;
    totalForce += force[kind] * scale;
    totalTorque += torque[kind] * scale;
  }
  out.pushingPoints = acting[0] + acting[1];
  out.forceOnShellWorld = applyRotation(voxmapMotion.poseWorld, totalForce);
  out.torqueOnShellWorld = applyRotation(voxmapMotion.poseWorld, totalTorque);
  out.forceOnVoxmapWorld = -out.forceOnShellWorld;
  out.torqueOnVoxmapWorld =
      -out.torqueOnShellWorld - glm::cross(shellComWorld - voxmapComWorld, out.forceOnShellWorld);
  return out;
}

}  // namespace voxhap
