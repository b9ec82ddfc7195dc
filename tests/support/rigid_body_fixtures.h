#pragma once
/// Test support for the dynamics: closed box objects and rigid-body models of a given mass.

#include <string>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat4x4.hpp>

#include "haptics/dynamics/mass_properties.h"
#include "haptics/dynamics/rigid_body.h"
#include "haptics/geometry/mesh_builder.h"
#include "haptics/scene/scene.h"

namespace voxhap::test {

/// An object of one part: a box with half extents `halfExtentsM` placed by `localToWorld`.
inline SceneObject boxObject(const glm::dvec3& halfExtentsM, const glm::dmat4& localToWorld = glm::dmat4(1.0),
                             const std::string& name = "box") {
  TriangleMesh mesh;
  appendBox(mesh, localToWorld, halfExtentsM);
  SceneObject object;
  object.name = name;
  object.parts.push_back(makePart(name + " part", glm::vec4(1.0f), std::move(mesh)));
  return object;
}

/// A flat box (10 × 5 × 2 cm) centred at (0.3, −0.2, 0.1) m, away from its local origin,
/// with the density that gives it `massKg`: three distinct principal moments and a centre
/// of mass that is not the local origin.
inline RigidBodyModel offsetBoxModel(double massKg) {
  const SceneObject box =
      boxObject(glm::dvec3(0.05, 0.025, 0.01), glm::translate(glm::dmat4(1.0), glm::dvec3(0.3, -0.2, 0.1)));
  const double volumeM3 = computeMassProperties(box, 1.0).volumeM3;
  return makeRigidBodyModel(computeMassProperties(box, massKg / volumeM3), box.name);
}

}  // namespace voxhap::test
