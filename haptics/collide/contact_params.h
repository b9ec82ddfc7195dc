#pragma once
/// Parameters of the point-voxel contact model (DESIGN §4.4, paper §3.2, §4).

#include <cstdint>

#include "haptics/voxel/voxel_encoding.h"

namespace voxhap {

/// The force layer of DESIGN §4.4: the second free-space layer, the least that keeps
/// exact surfaces from interpenetrating (paper §3.2).
inline constexpr std::uint8_t kDefaultForceLayer = distanceValue(2);

/// The force layer of contact by surface planes at up to a voxel (ContactParams::
/// surfaceContactM): the first free layer holds every point within a voxel of the surface.
inline constexpr std::uint8_t kSurfaceContactForceLayer = distanceValue(1);
/// Contact by surface planes begins this many point spacings from the surface: an edge or
/// corner at right angles, which may meet the other's surface between its points, reaches
/// a point within half a spacing of it before it can pass between them.
inline constexpr double kSurfaceContactSpacings = 0.75;

/// Above this many points pushing, the per-point stiffness and damping are scaled down
/// so that the total stays at kStiffContacts · per-point stiffness (the original VPS caps
/// at ~10). Every pushing point counts in full, however shallow: the cap bounds the
/// stiffness, the sum of k over pushing points, not the force (counting points by depth
/// let 1,500 shallow contacts of the actuator add up to 375 times the bound, and it shook
/// at the frame rate). Four: a box on a plate under
/// geometrical awareness stands on its four corner points with the pair's whole stiffness.
inline constexpr int kStiffContacts = 4;

/// How point tests read the voxmap and turn contacts into forces.
struct ContactParams {
  /// Voxels with a value in [1, forceLayer] are in contact; larger values give clearance
  /// (collision offsetting). At most the encoding's largest value.
  std::uint8_t forceLayer = kDefaultForceLayer;
  /// Geometrical awareness (paper §4): surface points sample the vertex field, vertex
  /// points the surface field, edge points the edge field. Off: every point samples the
  /// surface field.
  bool geometricalAwareness = true;
  /// Stiffness of one point in contact, N/m; the total is capped at kStiffContacts times this.
  double pointStiffnessNPerM = 0.0;
  /// Damping of one point in contact along its normal, N·s/m (capped like the stiffness).
  double pointDampingNsPerM = 0.0;
  /// Pre-contact damping: points in the free layer just outside the force layer
  /// (value forceLayer + 1) that approach feel the damper alone, no spring, so that
  /// contact begins gently. Their damping is capped on its own like the contacts'. Off by
  /// default: it adds a viscous feel before contact and tests ~2x the points near it.
  /// The sampler then reads up to sampledLayer().
  bool preContactDamping = false;
  /// Contact finer than a voxel: > 0 when the voxmap's surface planes (surface_planes.h)
  /// measure the contacts, a point then pushing once it lies closer than this to the voxmap
  /// object's exact surface, m; 0: the paper's tangent planes through the voxels' centres.
  /// Every point then samples the surface field (awareness off), and the force layer only
  /// bounds which voxels are read: it must reach the voxels that hold points this close.
  double surfaceContactM = 0.0;

  /// The largest value a point test must report: the force layer, or the layer beyond it
  /// when pre-contact damping is on (never beyond the encoding's `maxValue`).
  std::uint8_t sampledLayer(std::uint8_t maxValue) const {
    const int layer = forceLayer + (preContactDamping ? 1 : 0);
    return static_cast<std::uint8_t>(layer < maxValue ? layer : maxValue);
  }
};

}  // namespace voxhap
