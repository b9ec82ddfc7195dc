#pragma once
/// A point's distance from a voxmap object's exact surface, from the surface planes
/// (surface_plane.h) of the voxel it lies in and of the three voxels beside that one on
/// the point's side along each axis (contact finer than a voxel, DESIGN §4.4).
///
/// One voxel's plane alone, extrapolated up to 0.87 voxel from its centre, lies under the
/// true distance near a convex edge or corner: a seated ball's points over a socket's
/// rim read 0.99 mm deep there while 0.5 mm clear, and its rows lock any turn (stop 22).
/// Where the distance is convex every tangent plane lies under it, so the highest of the
/// neighbours' planes at the point is the closest bound from below. A neighbour's plane
/// is taken only where the two voxels' planes agree with convexity between their centres
/// (each lies under the other's value at the other's centre; with no slack, so that the
/// quantization cannot admit a pair across a concave fold): near a concave edge or inside a
/// socket a plane may lie above the truth, and the point's own plane stands alone there.
/// Which pairs agree is decided with the planes (PlaneWithSides), so that no lookup is made
/// for a neighbour that cannot count: the seated ball's contacts in its socket, 0.5 % of
/// whose neighbours did, took 37–49 % of the time they had taken.
///
/// Measured (surface_distance_test.cpp, 1 mm voxels): outside a box within 1.5 voxels of its
/// edges and corners, the own plane lies up to 0.41 voxel under the truth, these planes 0.068
/// voxel. The four voxels beside on the diagonals too gave the same, at twice the frame cost
/// of the seated ball's 9,600 contacts.

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "haptics/voxel/voxmap.h"

namespace voxhap {

struct SurfaceDistance {
  double distanceM = 0.0;       ///< φ(p): positive outside, m
  glm::dvec3 outwardUnit{0.0};  ///< the normal of the plane that gave it, voxmap frame
};

/// A point of a voxel as the voxel's own plane reads it: where surfaceDistance starts.
struct OwnPlaneReading {
  glm::dvec3 pointVoxels{0.0};   ///< the point from the voxel's centre, voxels
  glm::dvec3 outwardUnit{0.0};   ///< n_c of the own plane
  double distanceVoxels = 0.0;   ///< φ_c of the own plane, voxels
  double distanceM = 0.0;        ///< φ(p) by the own plane alone, m: surfaceDistance never gives less
  std::uint8_t convexSides = 0;  ///< the neighbours whose planes may give more (PlaneWithSides)
};

/// `pointLocal` (voxmap frame, m), a point of voxel `ijkVoxel`, read by that voxel's plane `own`.
inline OwnPlaneReading readOwnPlane(const VoxelGrid& grid, const glm::ivec3& ijkVoxel,
                                    const PlaneWithSides& own, const glm::dvec3& pointLocal) noexcept {
  OwnPlaneReading r;
  r.pointVoxels = (pointLocal - grid.voxelCentre(ijkVoxel)) / grid.voxelSizeM;
  r.outwardUnit = own.plane->outwardUnit();
  r.distanceVoxels = own.plane->distanceVoxels();
  r.convexSides = own.convexSides;
  r.distanceM = (r.distanceVoxels + glm::dot(r.pointVoxels, r.outwardUnit)) * grid.voxelSizeM;
  return r;
}

/// φ at a point of voxel `ijkVoxel` that its own plane reads as `own` (readOwnPlane).
SurfaceDistance surfaceDistance(const Voxmap& voxmap, const glm::ivec3& ijkVoxel,
                                const OwnPlaneReading& own) noexcept;

}  // namespace voxhap
