#pragma once
/// Picking a part by clicking it: the first object a ray from the eye meets, through
/// Embree, with the moving objects where they are now. One Embree scene per object, in
/// its scene-placement coordinates, built once; a moving object's pose is applied to the
/// ray, not to its triangles. Per click, never per frame.

#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "haptics/dynamics/pose.h"
#include "haptics/geometry/embree_scene.h"
#include "haptics/scene/scene.h"

namespace voxhap::view {

/// What a ray met first.
struct Pick {
  std::size_t object = 0;   ///< index in the scene's objects
  glm::dvec3 pointWorld{};  ///< where, m
  double distanceM = 0.0;   ///< from the ray's origin
};

class ScenePicker {
public:
  /// Builds the queries for every object of `scene` (kept by reference: it must outlive
  /// the picker). Throws voxhap::Error when Embree fails.
  explicit ScenePicker(const Scene& scene);

  /// The first object met by the ray from `originWorld` along `directionWorld` (need not be
  /// unit), each object at `posesWorld[i]` (one per scene object: identity for one where
  /// the file puts it); none when the ray meets nothing.
  std::optional<Pick> pick(const glm::dvec3& originWorld, const glm::dvec3& directionWorld,
                           std::span<const Pose> posesWorld) const;

private:
  std::vector<std::unique_ptr<EmbreeScene>> objects_;  ///< per scene object
};

}  // namespace voxhap::view
