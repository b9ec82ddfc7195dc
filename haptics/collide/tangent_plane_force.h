#pragma once
/// Tangent-plane forces (DESIGN §4.4, paper §2.1 Fig. 1b) from the contacts that
/// point sampling found, for one pointshell object against one voxmap object.
///
/// For a contact point p (voxmap frame) with unit normal n (the pointshell object's
/// outward normal, so it points toward the voxmap object) in voxel of centre c and value
/// v, the depth is d = (p − c)·g + (F − v)·s: how far p has crossed the plane through c
/// normal to g, plus a voxel per layer it lies beyond the force layer F. DESIGN §4.4
/// takes g = n; we take g = the unit direction in which the sampled field falls (central
/// differences of its six neighbours; n where they are all equal). Then d is continuous
/// where the point crosses from voxel to voxel (a layer deeper adds s exactly as the
/// plane term loses it), whereas with g = n a corner point with a diagonal normal gains
/// or loses up to 0.58·s at every crossing, and those force steps pump energy into a
/// box resting on its corners until it rocks over. A point with d > 0 pushes with
/// k·d + b·v_u along −u on the pointshell object (v_u: approach speed along u; the sum is
/// kept ≥ 0, contacts never pull), where u is the contact normal of the features that
/// meet: n for a surface point (it meets a vertex), g for a vertex point (it meets a
/// surface; with u = n a box standing on its corners, whose corner normals are diagonal,
/// is pushed sideways by whatever corner sits deepest and slides off), between n and g
/// for an edge point (also without geometrical awareness: the labels stay). Pushing points count by
/// min(1, d/s); when the count exceeds kStiffContacts, k and b are scaled by
/// kStiffContacts / count, so that the total stiffness stays bounded. Force and torque are summed in the voxmap frame, turned to
/// world, and applied equal and opposite to the two objects.

#include <cstdint>
#include <span>

#include <glm/vec3.hpp>

#include "haptics/collide/contact_params.h"
#include "haptics/collide/point_sampler.h"

namespace voxhap {

/// Pose and velocity of one object of a pair, world frame.
struct BodyMotion {
  Pose poseWorld;                       ///< local → world
  glm::dvec3 comLocal{0.0};             ///< centre of mass, object-local frame, m
  glm::dvec3 linearVelocityWorld{0.0};  ///< of the centre of mass, m/s
  glm::dvec3 angularVelocityWorld{0.0};  ///< rad/s
};

/// Contact wrench on both objects of a pair, world frame; torques about each object's
/// centre of mass.
struct PairWrench {
  glm::dvec3 forceOnShellWorld{0.0};     ///< N
  glm::dvec3 torqueOnShellWorld{0.0};    ///< N·m
  glm::dvec3 forceOnVoxmapWorld{0.0};    ///< N, = −forceOnShellWorld
  glm::dvec3 torqueOnVoxmapWorld{0.0};   ///< N·m
  std::uint32_t pushingPoints = 0;       ///< contacts with depth > 0
  double maxDepthM = 0.0;                ///< largest depth d, m
};

/// Sums the tangent-plane forces of `contacts` (from samplePoints with the same
/// `params`) of `shell` (its object moving as `shellMotion`) in `voxmap` (its object
/// moving as `voxmapMotion`).
PairWrench tangentPlaneWrench(const Pointshell& shell, const Voxmap& voxmap, const ContactParams& params,
                              const BodyMotion& shellMotion, const BodyMotion& voxmapMotion,
                              std::span<const PointContact> contacts) noexcept;

}  // namespace voxhap
