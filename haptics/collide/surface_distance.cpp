#include "haptics/collide/surface_distance.h"

#include <array>

#include <glm/geometric.hpp>

namespace voxhap {

SurfaceDistance surfaceDistance(const Voxmap& voxmap, const glm::ivec3& ijkVoxel,
                                const OwnPlaneReading& own) noexcept {
  const double s = voxmap.grid().voxelSizeM;
  // the point and the neighbours' centres in voxels from the own centre
  const glm::dvec3& point = own.pointVoxels;
  const glm::dvec3& ownOutward = own.outwardUnit;
  const double ownVoxels = own.distanceVoxels;
  SurfaceDistance best{own.distanceM, ownOutward};
  const glm::ivec3 side(point.x < 0.0 ? -1 : 1, point.y < 0.0 ? -1 : 1, point.z < 0.0 ? -1 : 1);
  const std::array<const SurfacePlane*, 3> beside = voxmap.surfacePlanesBeside(ijkVoxel, side);
  for (int axis = 0; axis < 3; ++axis) {
    const SurfacePlane* other = beside[static_cast<std::size_t>(axis)];
    if (!other) continue;
    glm::ivec3 offset(0);
    offset[axis] = side[axis];
    const glm::dvec3 otherOutward = other->outwardUnit();
    const double otherVoxels = other->distanceVoxels();
    const glm::dvec3 apart(offset);
    const bool convex = otherVoxels - glm::dot(apart, otherOutward) <= ownVoxels &&
                        ownVoxels + glm::dot(apart, ownOutward) <= otherVoxels;
    if (!convex) continue;
    const double atPointM = (otherVoxels + glm::dot(point - apart, otherOutward)) * s;
    if (atPointM > best.distanceM) best = {atPointM, otherOutward};
  }
  return best;
}

}  // namespace voxhap
