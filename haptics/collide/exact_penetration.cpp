#include "haptics/collide/exact_penetration.h"

#include <algorithm>
#include <tuple>

#include <glm/geometric.hpp>

namespace voxhap {
namespace {

/// Ray directions of the inside vote: unit, skewed off the axes so that none runs along
/// the axis-aligned faces and edges CAD models are full of.
const glm::dvec3 kVoteDirections[] = {
    glm::normalize(glm::dvec3(1.0, 0.0123, 0.0071)),
    glm::normalize(glm::dvec3(-0.0093, 1.0, 0.0137)),
    glm::normalize(glm::dvec3(0.0117, -0.0081, 1.0)),
};

}  // namespace

ExactPenetration::ExactPenetration(std::span<const TriangleMesh* const> staticMeshes,
                                   std::span<const glm::vec3> verticesLocal)
    : meshes_(staticMeshes.begin(), staticMeshes.end()),
      scene_(staticMeshes),
      verticesLocal_(verticesLocal.begin(), verticesLocal.end()) {
  auto byXyz = [](const glm::vec3& a, const glm::vec3& b) {
    return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
  };
  std::sort(verticesLocal_.begin(), verticesLocal_.end(), byXyz);
  verticesLocal_.erase(std::unique(verticesLocal_.begin(), verticesLocal_.end()), verticesLocal_.end());
  Bounds bounds;
  for (const TriangleMesh* mesh : meshes_) {
    for (const glm::vec3& p : mesh->positionsWorld) bounds.add(glm::dvec3(p));
  }
  rayLengthM_ = 2.0 * glm::length(bounds.extent()) + 1.0;
}

bool ExactPenetration::inside(const glm::dvec3& pointWorld) {
  int votes = 0;
  for (const glm::dvec3& direction : kVoteDirections) {
    hits_.clear();
    scene_.allCrossings(pointWorld, direction, rayLengthM_, hits_);
    parts_.clear();
    for (const RayCrossing& hit : hits_) parts_.push_back(hit.part);
    std::sort(parts_.begin(), parts_.end());
    // inside the union when inside any part: some part crossed an odd number of times
    bool odd = false;
    for (std::size_t i = 0; i < parts_.size() && !odd;) {
      std::size_t j = i;
      while (j < parts_.size() && parts_[j] == parts_[i]) ++j;
      odd = ((j - i) & 1u) != 0;
      i = j;
    }
    votes += odd ? 1 : 0;
  }
  return votes >= 2;
}

PenetrationSample ExactPenetration::measure(const Pose& objectToWorld, const Voxmap& staticVoxmap) {
  PenetrationSample sample;
  for (const glm::vec3& vertex : verticesLocal_) {
    const glm::dvec3 p = apply(objectToWorld, glm::dvec3(vertex));
    const std::uint8_t value = staticVoxmap.value(staticVoxmap.grid().voxelOf(p), Field::Surface);
    if (value == kValueFar) continue;
    if (value > kValueFeature) {
      if (value > kValueFeature + kClearanceVoxels) continue;
      const double searchM = static_cast<double>(kClearanceVoxels + 2) * staticVoxmap.grid().voxelSizeM;
      if (const auto nearest = scene_.closestPoint(p, searchM)) {
        sample.clearanceM = std::min(sample.clearanceM, nearest->distanceM);
      }
      continue;
    }
    ++sample.candidates;
    if (!inside(p)) {
      if (const auto nearest = scene_.closestPoint(p, 2.0 * staticVoxmap.grid().voxelSizeM)) {
        sample.clearanceM = std::min(sample.clearanceM, nearest->distanceM);
      }
      continue;
    }
    ++sample.inside;
    // most contacts are shallow: a small search radius first, the whole scene if need be
    auto nearest = scene_.closestPoint(p, 4.0 * staticVoxmap.grid().voxelSizeM);
    if (!nearest) nearest = scene_.closestPoint(p, rayLengthM_);
    if (nearest && nearest->distanceM > sample.depthM) {
      sample.depthM = nearest->distanceM;
      sample.deepestWorld = p;
    }
  }
  return sample;
}

}  // namespace voxhap
