#include "haptics/collide/surface_distance.h"

#include <array>

#include <glm/geometric.hpp>

namespace voxhap {

SurfaceDistance surfaceDistance(const Voxmap& voxmap, const glm::ivec3& ijkVoxel,
                                const OwnPlaneReading& own) noexcept {
  const double s = voxmap.grid().voxelSizeM;
  // the point and the neighbours' centres in voxels from the own centre
  const glm::dvec3& point = own.pointVoxels;
  SurfaceDistance best{own.distanceM, own.outwardUnit};
  const glm::ivec3 side(point.x < 0.0 ? -1 : 1, point.y < 0.0 ? -1 : 1, point.z < 0.0 ? -1 : 1);
  std::uint8_t wanted = 0;
  for (int axis = 0; axis < 3; ++axis) wanted |= SurfacePlane::sideBit(axis, side[axis]);
  wanted &= own.convexSides;
  // near a concave surface (a socket's) no neighbour is convex with the own plane: no lookup
  if (!wanted) return best;
  const std::array<const SurfacePlane*, 3> beside = voxmap.surfacePlanesBeside(ijkVoxel, side);
  for (int axis = 0; axis < 3; ++axis) {
    const SurfacePlane* other = beside[static_cast<std::size_t>(axis)];
    if (!other || !(wanted & SurfacePlane::sideBit(axis, side[axis]))) continue;
    glm::dvec3 apart(0.0);
    apart[axis] = side[axis];
    const double atPointM = (other->distanceVoxels() + glm::dot(point - apart, other->outwardUnit())) * s;
    if (atPointM > best.distanceM) best = {atPointM, other->outwardUnit()};
  }
  return best;
}

}  // namespace voxhap
