#pragma once
/// Tangent-plane forces (DESIGN §4.4, paper §2.1 Fig. 1b) from the contacts that
/// point sampling found, for one pointshell object against one voxmap object.
///
/// For a contact point p (voxmap frame) with unit normal n (the pointshell object's
/// outward normal, so it points toward the voxmap object) in a voxel of centre c and
/// value v, the depth is d = (p − c)·u + (F − v)·s: how far p has crossed the plane
/// through c normal to u, plus a voxel per layer it lies beyond the force layer F; a point
/// with d > 0 pushes the pointshell object with k·d + b·v_u along −u (v_u: approach speed
/// along u; never negative: contacts do not pull). Depth and force share u, so each
/// point's force is the gradient of k·d²/2 within a voxel (conservative).
///
/// DESIGN §4.4 takes u = n for every point. We take u by the features that meet (the
/// field sampled names the voxmap object's): n for a surface point meeting a vertex
/// (geometrical awareness); the voxmap surface's normal g, the unit direction in which
/// the sampled field falls (central differences of the six neighbours), for a vertex point
/// and for any point without awareness (all meet a surface); between n and g where edge
/// meets edge. Without awareness, u = n let the side-face points of a bar resting on a
/// plate push it sideways (3.8 mN on an 80 mm bar, 1.7 % of its weight) until it slid off. With u = n a
/// box standing on its corners, whose normals are diagonal, was pushed sideways by
/// whichever corner sat deepest and slid off a frictionless plate; and a diagonal u gains
/// up to 0.42·s of depth at every voxel crossing, which rocked it over. With u = g for a
/// face-parallel surface d is continuous across voxels.
///
/// Contact finer than a voxel (ContactParams::surfaceContactM = L > 0, beyond the paper):
/// the surface planes give the point's distance from the voxmap object's exact surface,
/// φ = φ_c + (p − c)·n_c for the plane of its voxel or of a surrounding one
/// (surface_distance.h), and u = −n_c of that plane; the depth is d = L − φ,
/// so that a point pushes once it comes closer than L, along the surface's exact normal
/// (edges and corners included: no quantized fall direction). A contact without a plane
/// pushes as above if it lies in an interior or surface voxel (deep inside, past the
/// planes' reach), and not at all in a free voxel.
///
/// Contacts beyond the force layer (value F + 1, sampled for pre-contact damping) only
/// damp: b·v_u along −u while they approach, nothing otherwise.
///
/// When more than kStiffContacts points push, k and b are scaled by kStiffContacts /
/// count, so that the total stiffness stays bounded however many points touch. Force and
/// torque are summed in the voxmap frame, turned to world, and applied equal and opposite
/// to the two objects. From kHalvedContacts contacts on they are summed in two halves,
/// the first's sums then the second's added, whether a frame helper sums the second half
/// meanwhile or not: the same bits whatever the thread count.

#include <cstddef>
#include <cstdint>
#include <span>

#include <glm/vec3.hpp>

#include "haptics/collide/contact_params.h"
#include "haptics/collide/point_sampler.h"

namespace voxhap {

class FrameHelper;

/// A pair's contacts are summed in two halves from this many on (tangentPlaneWrench).
inline constexpr std::size_t kHalvedContacts = 1024;

/// Pose and velocity of one object of a pair, world frame.
struct BodyMotion {
  Pose poseWorld;                        ///< local → world
  glm::dvec3 comLocal{0.0};              ///< centre of mass, object-local frame, m
  glm::dvec3 linearVelocityWorld{0.0};   ///< of the centre of mass, m/s
  glm::dvec3 angularVelocityWorld{0.0};  ///< rad/s
};

/// One contact as a limit on motion (sim/depth_limit.h): the shell point at `pointWorld`
/// lies `depthM` deep along `intoVoxmapWorld`, the unit direction in which it would sink
/// further into the voxmap object (the negated push direction). World frame, frame start.
struct DepthRow {
  glm::dvec3 pointWorld{0.0};       ///< m
  glm::dvec3 intoVoxmapWorld{0.0};  ///< unit
  double depthM = 0.0;              ///< tangent-plane depth d, m (may be negative)
  double limitM = 0.0;        ///< the deepest mean depth its pair's rows may reach, m (set by the caller)
  double floorM = 0.0;        ///< d₀: the sink's minDepthM, below which a row weighs nothing, m
  int shellObject = 0;        ///< moving object index of the pointshell (set by the caller)
  int voxmapObject = 0;       ///< moving object index of the voxmap, or −1: static (set by the caller)
  bool surfacePlane = false;  ///< measured by a surface plane (ContactParams::surfaceContactM)
  bool limited = false;       ///< given a limit of its own this frame (depth_limit.h)
};

/// Where tangentPlaneWrench writes the contacts that may limit this frame's motion: every
/// contact in the force layer with depth above `minDepthM`, up to `rows.size()` of them.
struct DepthRowSink {
  std::span<DepthRow> rows;
  double minDepthM = 0.0;  ///< m
};

/// Contact wrench on both objects of a pair, world frame; torques about each object's
/// centre of mass.
struct PairWrench {
  glm::dvec3 forceOnShellWorld{0.0};    ///< N
  glm::dvec3 torqueOnShellWorld{0.0};   ///< N·m
  glm::dvec3 forceOnVoxmapWorld{0.0};   ///< N, = −forceOnShellWorld
  glm::dvec3 torqueOnVoxmapWorld{0.0};  ///< N·m
  std::uint32_t contactPoints = 0;      ///< contacts at or inside the force layer
  std::uint32_t pushingPoints = 0;      ///< contacts pushing (depth > 0, or damping before contact)
  double maxDepthM = 0.0;               ///< largest depth d, m
  std::uint32_t missingVoxels = 0;      ///< neighbour lookups of a paged voxmap that found it paged out
  glm::ivec3 firstMissingVoxel{0};      ///< the first of them
  std::uint32_t depthRows = 0;          ///< rows written to the DepthRowSink
};

/// Sums the tangent-plane forces of `contacts` (from samplePoints with the same
/// `params`) of `shell` (its object moving as `shellMotion`) in `voxmap` (its object
/// moving as `voxmapMotion`). With a `sink`, the contacts deep enough to limit the step
/// are written to it too (their object indices and limit left to the caller), in contact
/// order; the second half's rows are written from the sink's row contacts.size() / 2 on
/// and moved down, so a sink with fewer rows than contacts may keep fewer of them. With a
/// `helper` (frame_helper.h) and an unpaged voxmap, the helper sums the second half.
PairWrench tangentPlaneWrench(const Pointshell& shell, const Voxmap& voxmap, const ContactParams& params,
                              const BodyMotion& shellMotion, const BodyMotion& voxmapMotion,
                              std::span<const PointContact> contacts, const DepthRowSink* sink = nullptr,
                              FrameHelper* helper = nullptr) noexcept;

}  // namespace voxhap
