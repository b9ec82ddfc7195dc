#include "haptics/collide/tangent_plane_force.h"

#include <algorithm>
#include <array>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/vector_relational.hpp>

#include "haptics/collide/surface_distance.h"
#include "haptics/runtime/frame_helper.h"

namespace voxhap {
namespace {

/// What a run of contacts adds to a pair's wrench, voxmap frame, before the stiff-contact
/// scaling: in contact [0] and damped before contact [1], each capped on its own at the end.
struct WrenchSums {
  glm::dvec3 force[2] = {glm::dvec3(0.0), glm::dvec3(0.0)};
  glm::dvec3 torque[2] = {glm::dvec3(0.0), glm::dvec3(0.0)};
  std::uint32_t acting[2] = {0, 0};
  std::uint32_t contactPoints = 0;
  double maxDepthM = 0.0;
  std::uint32_t missingVoxels = 0;
  glm::ivec3 firstMissingVoxel{0};
  std::uint32_t depthRows = 0;

  /// The sums of the run that follows this one.
  void add(const WrenchSums& next) noexcept {
    for (int kind = 0; kind < 2; ++kind) {
      force[kind] += next.force[kind];
      torque[kind] += next.torque[kind];
      acting[kind] += next.acting[kind];
    }
    contactPoints += next.contactPoints;
    maxDepthM = std::max(maxDepthM, next.maxDepthM);
    if (missingVoxels == 0) firstMissingVoxel = next.firstMissingVoxel;
    missingVoxels += next.missingVoxels;
    depthRows += next.depthRows;
  }
};

/// g / |g|, or zero for zero.
glm::dvec3 unitOfAny(const glm::ivec3& g) noexcept {
  const glm::dvec3 d(g);
  const double length = glm::length(d);
  return length > 0.0 ? d / length : d;
}

/// The fall directions of central differences within ±2, as unitOfAny gives them: the
/// common case, a field's values stepping by one a layer (far and paged neighbours aside).
constexpr int kTabledFall = 2;
constexpr int kTabledFallSpan = 2 * kTabledFall + 1;
constexpr std::size_t kTabledFalls = kTabledFallSpan * kTabledFallSpan * kTabledFallSpan;
const std::array<glm::dvec3, kTabledFalls> kUnitFalls = [] {
  std::array<glm::dvec3, kTabledFalls> table;
  for (int i = 0; i < static_cast<int>(table.size()); ++i) {
    table[static_cast<std::size_t>(i)] =
        unitOfAny(glm::ivec3(i % kTabledFallSpan, i / kTabledFallSpan % kTabledFallSpan,
                             i / (kTabledFallSpan * kTabledFallSpan)) -
                  kTabledFall);
  }
  return table;
}();

/// unitOfAny(g), from the table where it holds g: a square root and three divisions saved.
glm::dvec3 unitOf(const glm::ivec3& g) noexcept {
  const glm::ivec3 at = g + kTabledFall;
  if (glm::any(glm::greaterThanEqual(glm::uvec3(at), glm::uvec3(kTabledFallSpan)))) return unitOfAny(g);
  return kUnitFalls[static_cast<std::size_t>(at.x + kTabledFallSpan * (at.y + kTabledFallSpan * at.z))];
}

/// Unit direction, voxmap frame, in which the field at `shift` falls around `ijk`
/// (far counts as one more than the largest value); zero where it is flat. A neighbour
/// paged out (paged voxmap) counts as the centre and is noted in `out`.
glm::dvec3 fallDirection(const Voxmap& voxmap, const glm::ivec3& ijk, std::uint8_t shift, WrenchSums& out) {
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
    return (values[below] < 0 ? centre : values[below]) - (values[above] < 0 ? centre : values[above]);
  };
  return unitOf(glm::ivec3(fallAlong(1, 2), fallAlong(3, 4), fallAlong(5, 6)));
}

/// The contact normal (toward the voxmap object), by what the point meets: the field it
/// samples names the voxmap object's feature. A vertex there (surface points under
/// geometrical awareness): the point's own normal `n`. A surface (vertex points, or any
/// point without awareness): the surface's normal, the field's fall direction `g` (a
/// corner or edge has no normal of its own worth pushing along, and a surface point on
/// the side of a part resting on a plate would push sideways along its own normal). An
/// edge (edge points): between the two.
glm::dvec3 pushDirectionOf(const Voxmap& voxmap, const PointContact& contact, PointFeature feature,
                           bool aware, std::uint8_t fieldShift, const glm::dvec3& n, WrenchSums& out) {
  if (feature == PointFeature::Surface && aware) return n;
  glm::dvec3 g = fallDirection(voxmap, contact.ijkVoxel, fieldShift, out);
  if (g == glm::dvec3(0.0)) g = n;
  if (feature != PointFeature::Edge || !aware) return g;
  const glm::dvec3 between = n + g;
  const double length = glm::length(between);
  return length > 1e-6 ? between / length : n;
}

/// The pair's motion as every contact of a frame reads it.
struct ContactFrame {
  Pose voxmapToWorld;
  Pose shellToVoxmap;
  glm::dmat3 shellToVoxmapRotation{1.0};
  glm::dvec3 shellComInVoxmap{0.0};
  glm::dvec3 shellComWorld{0.0};
  glm::dvec3 voxmapComWorld{0.0};
  /// the velocity of the shell relative to the voxmap object at a point p of the voxmap
  /// frame: linear + angular × p
  glm::dvec3 linear{0.0};
  glm::dvec3 angular{0.0};
};

ContactFrame contactFrame(const BodyMotion& shellMotion, const BodyMotion& voxmapMotion) noexcept {
  ContactFrame f;
  f.voxmapToWorld = voxmapMotion.poseWorld;
  f.shellToVoxmap = compose(inverse(voxmapMotion.poseWorld), shellMotion.poseWorld);
  f.shellToVoxmapRotation = glm::mat3_cast(f.shellToVoxmap.orientation);
  f.shellComInVoxmap = apply(f.shellToVoxmap, shellMotion.comLocal);
  f.shellComWorld = apply(shellMotion.poseWorld, shellMotion.comLocal);
  f.voxmapComWorld = apply(voxmapMotion.poseWorld, voxmapMotion.comLocal);
  const Pose worldToVoxmap = inverse(voxmapMotion.poseWorld);
  f.angular =
      applyRotation(worldToVoxmap, shellMotion.angularVelocityWorld - voxmapMotion.angularVelocityWorld);
  const glm::dvec3 linearWorld =
      shellMotion.linearVelocityWorld - glm::cross(shellMotion.angularVelocityWorld, f.shellComWorld) -
      voxmapMotion.linearVelocityWorld + glm::cross(voxmapMotion.angularVelocityWorld, f.voxmapComWorld);
  // the velocity field v(x) = linearWorld + ω_rel × x in world, taken to the voxmap frame:
  // x = R p + t gives v = R⁻¹(linearWorld + ω_rel × t) + (R⁻¹ω_rel) × p
  f.linear = applyRotation(worldToVoxmap, linearWorld + glm::cross(shellMotion.angularVelocityWorld -
                                                                       voxmapMotion.angularVelocityWorld,
                                                                   voxmapMotion.poseWorld.position));
  return f;
}

/// The sums of `contacts`, and their depth rows into `sink` from its first row on.
WrenchSums sumContacts(const Pointshell& shell, const Voxmap& voxmap, const ContactParams& params,
                       const ContactFrame& frame, std::span<const PointContact> contacts,
                       const DepthRowSink* sink) noexcept {
  WrenchSums out;
  const VoxelGrid& grid = voxmap.grid();
  const double s = grid.voxelSizeM;
  const auto shifts = fieldShiftsByFeature(params.geometricalAwareness, voxmap.encoding());
  const bool planes = params.surfaceContactM > 0.0 && voxmap.hasSurfacePlanes();
  // the frame and the sums in locals: the rows' writes could alias memory of the caller's,
  // which the compiler would then reload or store again at every contact
  const glm::dmat3 shellToVoxmapRotation = frame.shellToVoxmapRotation;
  const glm::dvec3 shellToVoxmapShift = frame.shellToVoxmap.position;
  const glm::dvec3 shellComInVoxmap = frame.shellComInVoxmap;
  const glm::dvec3 linear = frame.linear;
  const glm::dvec3 angular = frame.angular;
  const Pose voxmapToWorld = frame.voxmapToWorld;
  glm::dvec3 force[2] = {glm::dvec3(0.0), glm::dvec3(0.0)};
  glm::dvec3 torque[2] = {glm::dvec3(0.0), glm::dvec3(0.0)};
  std::uint32_t acting[2] = {0, 0};
  for (const PointContact& c : contacts) {
    const glm::dvec3 p =
        shellToVoxmapRotation * glm::dvec3(shell.positionsLocal[c.point]) + shellToVoxmapShift;
    const bool beforeContact = c.value > params.forceLayer;
    const PlaneWithSides planeWithSides =
        planes ? voxmap.surfacePlaneWithSides(c.ijkVoxel) : PlaneWithSides{};
    const SurfacePlane* plane = planeWithSides.plane;
    // no plane: deep inside (the voxel's tangent plane stands in), or too far out to push
    if (planes && !plane && c.value > kValueFeature) continue;
    glm::dvec3 pushDirection;
    double depth = 0.0;
    OwnPlaneReading own;
    if (plane) own = readOwnPlane(grid, c.ijkVoxel, planeWithSides, p);
    if (plane && !beforeContact) {
      // the own plane bounds φ from below, so the depth from above: a point that can
      // neither push nor limit the step needs no neighbours' planes
      const double depthBoundM = params.surfaceContactM - own.distanceM;
      if (depthBoundM <= 0.0 && (!sink || depthBoundM <= sink->minDepthM)) {
        ++out.contactPoints;
        continue;
      }
    }
    if (plane) {
      const SurfaceDistance phi = surfaceDistance(voxmap, c.ijkVoxel, own);
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
      row.pointWorld = apply(voxmapToWorld, p);
      row.intoVoxmapWorld = applyRotation(voxmapToWorld, pushDirection);
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
  for (int kind = 0; kind < 2; ++kind) {
    out.force[kind] = force[kind];
    out.torque[kind] = torque[kind];
    out.acting[kind] = acting[kind];
  }
  return out;
}

}  // namespace

PairWrench tangentPlaneWrench(const Pointshell& shell, const Voxmap& voxmap, const ContactParams& params,
                              const BodyMotion& shellMotion, const BodyMotion& voxmapMotion,
                              std::span<const PointContact> contacts, const DepthRowSink* sink,
                              FrameHelper* helper) noexcept {
  PairWrench out;
  if (contacts.empty()) return out;
  const ContactFrame frame = contactFrame(shellMotion, voxmapMotion);
  const std::size_t n = contacts.size();
  const std::size_t half = n >= kHalvedContacts ? n / 2 : n;
  // the second half's rows from row `half` on, moved down to follow the first's
  DepthRowSink secondSink;
  if (sink) secondSink = {sink->rows.subspan(std::min(half, sink->rows.size())), sink->minDepthM};
  WrenchSums second;
  auto sumSecond = [&] {
    second = sumContacts(shell, voxmap, params, frame, contacts.subspan(half), sink ? &secondSink : nullptr);
  };
  // a paged voxmap is read by the haptic thread alone
  const bool helped = half < n && helper && !voxmap.isPaged();
  if (helped) helper->run(sumSecond);
  WrenchSums sums = sumContacts(shell, voxmap, params, frame, contacts.first(half), sink);
  if (half < n) {
    if (helped) {
      helper->finish();
    } else {
      sumSecond();
    }
    if (sink && second.depthRows > 0) {
      std::copy_n(secondSink.rows.begin(), second.depthRows, sink->rows.begin() + sums.depthRows);
    }
    sums.add(second);
  }

  glm::dvec3 totalForce(0.0);
  glm::dvec3 totalTorque(0.0);
  for (int kind = 0; kind < 2; ++kind) {
    const std::uint32_t acting = sums.acting[kind];
    const double scale = acting > kStiffContacts ? double(kStiffContacts) / double(acting) : 1.0;
    totalForce += sums.force[kind] * scale;
    totalTorque += sums.torque[kind] * scale;
  }
  out.contactPoints = sums.contactPoints;
  out.pushingPoints = sums.acting[0] + sums.acting[1];
  out.maxDepthM = sums.maxDepthM;
  out.missingVoxels = sums.missingVoxels;
  out.firstMissingVoxel = sums.firstMissingVoxel;
  out.depthRows = sums.depthRows;
  out.forceOnShellWorld = applyRotation(voxmapMotion.poseWorld, totalForce);
  out.torqueOnShellWorld = applyRotation(voxmapMotion.poseWorld, totalTorque);
  out.forceOnVoxmapWorld = -out.forceOnShellWorld;
  out.torqueOnVoxmapWorld =
      -out.torqueOnShellWorld - glm::cross(frame.shellComWorld - frame.voxmapComWorld, out.forceOnShellWorld);
  return out;
}

}  // namespace voxhap
