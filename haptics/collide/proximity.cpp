#include "haptics/collide/proximity.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>

namespace voxhap {

float surfaceDistanceM(const Voxmap& voxmap, const glm::dvec3& pointVoxmap) {
  const std::uint8_t v = voxmap.value(voxmap.grid().voxelOf(pointVoxmap), Field::Surface);
  if (v == kValueFar) return kBeyondRange;
  if (v <= kValueFeature) return 0.0f;
  return static_cast<float>((v - kValueFeature) * voxmap.grid().voxelSizeM);
}

void vertexDistancesM(std::span<const glm::vec3> verticesLocal, const Pose& objectToVoxmap,
                      const Voxmap& voxmap, std::vector<float>& out) {
  out.resize(verticesLocal.size());
  for (std::size_t i = 0; i < verticesLocal.size(); ++i) {
    out[i] = surfaceDistanceM(voxmap, apply(objectToVoxmap, glm::dvec3(verticesLocal[i])));
  }
}

float minimumDistanceM(const Pointshell& shell, const Pose& shellToVoxmap, const Voxmap& voxmap) {
  float least = kBeyondRange;
  for (const glm::vec3& p : shell.positionsLocal) {
    least = std::min(least, surfaceDistanceM(voxmap, apply(shellToVoxmap, glm::dvec3(p))));
  }
  return least;
}

void surfaceVoxelsNear(const Voxmap& staticVoxmap, const Voxmap& movingVoxmap, const Pose& movingToStatic,
                       double distanceM, std::vector<glm::ivec3>& out) {
  out.clear();
  // the moving grid's box, in the static voxmap's voxels
  const VoxelGrid& mg = movingVoxmap.grid();
  const glm::dvec3 size = glm::dvec3(mg.dimsVoxels()) * mg.voxelSizeM;
  glm::dvec3 lo(1e300);
  glm::dvec3 hi(-1e300);
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec3 c = mg.originLocal + size * glm::dvec3(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
    const glm::dvec3 p = apply(movingToStatic, c);
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const VoxelGrid& sg = staticVoxmap.grid();
  const glm::ivec3 from = glm::max(sg.voxelOf(lo), glm::ivec3(0));
  const glm::ivec3 to = glm::min(sg.voxelOf(hi), sg.dimsVoxels() - 1);
  const Pose staticToMoving = inverse(movingToStatic);
  for (int z = from.z; z <= to.z; ++z) {
    for (int y = from.y; y <= to.y; ++y) {
      for (int x = from.x; x <= to.x; ++x) {
        if (staticVoxmap.value({x, y, z}, Field::Surface) != kValueFeature) continue;
        const float d = surfaceDistanceM(movingVoxmap, apply(staticToMoving, sg.voxelCentre({x, y, z})));
        if (d <= distanceM) out.push_back({x, y, z});
      }
    }
  }
}

}  // namespace voxhap
