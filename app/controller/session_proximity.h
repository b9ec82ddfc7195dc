#pragma once
/// Proximity of a running session's moving objects to its static scene, for GetProximity
/// (docs/protocol.md): the estimated distance of each vertex of a moving object's meshes,
/// and the static surface voxels near it (paper §3.1: proximity colouring and the
/// "shadow" of nearby static voxels). Built with the session on the loader's thread, then
/// read on the comms thread only; it reads the static voxmap, which is immutable unless
/// paged (then proximity is refused: the pager's residency is the haptic thread's).

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "haptics/core/progress.h"
#include "haptics/dynamics/pose.h"
#include "haptics/scene/object_selection.h"
#include "haptics/sim/scene_model.h"

namespace voxhap::controller {

/// What GetProximity answers for one object at one pose.
struct ProximityResult {
  std::vector<float> vertexDistanceM;             ///< per vertex, in the order of vertexCount's meshes
  std::vector<glm::dvec3> nearStaticVoxelsWorld;  ///< centres of static surface voxels near it, world
  double staticVoxelSizeM = 0.0;
};

class SessionProximity {
public:
  /// The moving objects of `model`, picked from `scene` as `selection` picked them; their
  /// own surface voxmaps at the moving objects' point spacing where the model has none
  /// (through options.voxelizeFn, so its cache).
  SessionProximity(const ObjectSelection& selection, const SimModel& model, const SceneModelOptions& options,
                   const ProgressFn& progress = {});
  ~SessionProximity();

  /// Why proximity cannot be measured in this session, or empty.
  const std::string& unavailable() const { return unavailable_; }
  /// Vertices of moving object `object` (its parts' meshes one after another).
  std::size_t vertexCount(std::size_t object) const { return verticesLocal_[object].size(); }

  /// Distances of object `object`'s vertices at `objectWorld` (its local → world pose) to
  /// the static scene, and the static surface voxels whose centres lie within `withinM`
  /// of it (none when withinM is 0). Requires unavailable() to be empty.
  void measure(std::size_t object, const Pose& objectWorld, double withinM, ProximityResult& out) const;

private:
  const SimModel& model_;
  std::vector<std::vector<glm::vec3>> verticesLocal_;
  std::vector<const Voxmap*> movingVoxmaps_;
  std::vector<std::unique_ptr<Voxmap>> ownVoxmaps_;
  std::string unavailable_;
};

}  // namespace voxhap::controller
