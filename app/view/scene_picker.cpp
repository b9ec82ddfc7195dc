#include "app/view/scene_picker.h"

#include <limits>

#include "haptics/core/error.h"

namespace voxhap::view {

ScenePicker::ScenePicker(const Scene& scene) {
  for (const SceneObject& object : scene.objects) {
    std::vector<const TriangleMesh*> meshes;
    for (const Part& part : object.parts) meshes.push_back(&part.mesh);
    objects_.push_back(std::make_unique<EmbreeScene>(meshes));
  }
}

std::optional<Pick> ScenePicker::pick(const glm::dvec3& originWorld, const glm::dvec3& directionWorld,
                                      std::span<const Pose> posesWorld) const {
  if (posesWorld.size() != objects_.size()) throw Error("pick: one pose per scene object is needed");
  const double length = glm::length(directionWorld);
  if (!(length > 0.0)) return std::nullopt;
  const glm::dvec3 direction = directionWorld / length;
  std::optional<Pick> first;
  std::vector<RayCrossing> crossings;
  for (std::size_t i = 0; i < objects_.size(); ++i) {
    // the ray in the object's placement coordinates
    const Pose& pose = posesWorld[i];
    const glm::dquat toLocal = glm::conjugate(pose.orientation);
    crossings.clear();
    objects_[i]->allCrossings(toLocal * (originWorld - pose.position), toLocal * direction,
                              std::numeric_limits<double>::infinity(), crossings);
    for (const RayCrossing& c : crossings) {
      if (!first || c.t < first->distanceM) first = Pick{i, originWorld + c.t * direction, c.t};
    }
  }
  return first;
}

}  // namespace voxhap::view
