#pragma once
/// Geometry of a voxel grid in an object's local frame: where voxel (0,0,0) sits,
/// how big a voxel is, how many hyperchunks the grid spans.

#include <cmath>

#include <glm/vec3.hpp>

#include "haptics/voxel/tree_shape.h"

namespace voxhap {

struct VoxelGrid {
  glm::dvec3 originLocal{0.0};  ///< corner of voxel (0,0,0), object's local frame, m
  double voxelSizeM = 0.0;      ///< edge length of a voxel, m
  glm::ivec3 dimsHyper{0};      ///< grid size in hyperchunks along x, y, z

  glm::ivec3 dimsVoxels() const { return dimsHyper * kHyperEdgeVoxels; }
  glm::ivec3 dimsChunks() const { return dimsHyper * kHyperEdgeChunks; }

  /// The voxel containing `pointLocal` (may lie outside the grid).
  glm::ivec3 voxelOf(const glm::dvec3& pointLocal) const {
    const glm::dvec3 u = (pointLocal - originLocal) / voxelSizeM;
    return {static_cast<int>(std::floor(u.x)), static_cast<int>(std::floor(u.y)),
            static_cast<int>(std::floor(u.z))};
  }
  /// Centre of voxel `ijkVoxel`, local frame, m.
  glm::dvec3 voxelCentre(const glm::ivec3& ijkVoxel) const {
    return originLocal + (glm::dvec3(ijkVoxel) + 0.5) * voxelSizeM;
  }
  bool containsVoxel(const glm::ivec3& ijkVoxel) const {
    const glm::ivec3 d = dimsVoxels();
    return ijkVoxel.x >= 0 && ijkVoxel.y >= 0 && ijkVoxel.z >= 0 && ijkVoxel.x < d.x && ijkVoxel.y < d.y &&
           ijkVoxel.z < d.z;
  }
};

}  // namespace voxhap
