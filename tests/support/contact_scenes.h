#pragma once
/// Test support for contact: small analytic scenes (sphere over a plate, box over a
/// plate, crossed rods), a runner of free or scripted frames, and exact distances.

#include <string>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "haptics/geometry/mesh_builder.h"
#include "haptics/scene/scene.h"
#include "haptics/sim/local_simulation.h"
#include "haptics/sim/scene_model.h"

namespace voxhap::test {

/// The translation to (x, y, z), m: where a test mesh is placed.
inline glm::dmat4 at(double x, double y, double z) {
  return glm::translate(glm::dmat4(1.0), glm::dvec3(x, y, z));
}

/// An object of one part built by `append(mesh)`.
template <typename Append>
SceneObject meshObject(const std::string& name, ObjectRole role, Append&& append) {
  TriangleMesh mesh;
  append(mesh);
  SceneObject object;
  object.name = name;
  object.settings.role = role;
  object.parts.push_back(makePart(name, glm::vec4(1.0f), std::move(mesh)));
  return object;
}

/// A static plate whose top face is z = 0, 100 × 100 × 10 mm.
inline SceneObject plate() {
  return meshObject("plate", ObjectRole::Static, [](TriangleMesh& m) {
    appendBox(m, glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 0.0, -0.005)),
              glm::dvec3(0.05, 0.05, 0.005));
  });
}

/// Scene-model options for tests of contact physics: time-critical sampling on, with a
/// fixed capacity (deterministic) so large that MaxTravel stays at its upper bound.
inline SceneModelOptions ampleCapacityOptions() {
  SceneModelOptions options;
  options.sim.coherence.capacityTests = 1e9;
  return options;
}

/// Model of `scene` with `moving` free (not coupled) at voxel size `voxelM`, contact by the
/// paper's voxel planes or by exact surface planes.
inline SimModel freeModel(const Scene& scene, const std::vector<std::string>& moving, double voxelM,
                          const glm::dvec3& gravity, bool awareness = true, bool surfaceContact = false) {
  SceneModelOptions options = ampleCapacityOptions();
  options.sim.surfaceContact = surfaceContact;
  options.staticVoxelSizeM = voxelM;
  options.pointSpacingM = voxelM;
  options.sim.gravityWorld = gravity;
  options.sim.geometricalAwareness = awareness;
  SimModel model = buildSceneModel(scene, moving, options);
  for (MovingObjectModel& object : model.objects) object.coupled = false;
  return model;
}

/// Lowest z of `object`'s vertices at `pose`: the exact height of a convex polyhedron
/// over a plane z = 0.
inline double lowestZ(const SceneObject& object, const Pose& pose) {
  double z = 1e300;
  for (const Part& part : object.parts) {
    for (const glm::vec3& p : part.mesh.positionsWorld) z = std::min(z, apply(pose, glm::dvec3(p)).z);
  }
  return z;
}

}  // namespace voxhap::test
