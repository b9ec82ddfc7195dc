#include "haptics/collide/surface_distance.h"

#include <glm/geometric.hpp>

namespace voxhap {

SurfaceDistance surfaceDistance(const Voxmap& voxmap, const glm::ivec3& ijkVoxel, const SurfacePlane& own,
                                const glm::dvec3& pointLocal) noexcept {
  const VoxelGrid& grid = voxmap.grid();
  const double s = grid.voxelSizeM;
  const glm::dvec3 centre = grid.voxelCentre(ijkVoxel);
  const glm::dvec3 ownOutward = own.outwardUnit();
  const double ownVoxels = own.distanceVoxels();
  // the point and the neighbours' centres in voxels from the own centre
  const glm::dvec3 point = (pointLocal - centre) / s;
  SurfaceDistance best{ownPlaneDistanceM(grid, ijkVoxel, own, pointLocal), ownOutward};
  for (int axis = 0; axis < 3; ++axis) {
    glm::ivec3 offset(0);
    offset[axis] = point[axis] < 0.0 ? -1 : 1;
    const SurfacePlane* other = voxmap.surfacePlane(ijkVoxel + offset);
    if (!other) continue;
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
