#pragma once
/// Mass, centre of mass and inertia of a rigid object from its closed triangle meshes
/// (DESIGN §4.7), computed once at load time.
///
/// The object's local frame is the world frame at load time (scene.h), so everything
/// here is in that frame. Exact for the polyhedron the triangles bound (not for the
/// CAD surface they approximate): a tessellated sphere has a little less volume than
/// the sphere.

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "haptics/scene/scene.h"

namespace voxhap {

/// Density used when an object's extras give none: steel, kg/m³.
inline constexpr double kDefaultDensityKgPerM3 = 7850.0;

/// Rigid-body mass properties of a solid of uniform density.
struct MassProperties {
  double massKg = 0.0;       ///< kg, > 0
  double volumeM3 = 0.0;     ///< m³, > 0
  glm::dvec3 comLocal{0.0};  ///< centre of mass, object-local frame, m
  /// Inertia tensor about the centre of mass along the local axes, kg·m²; symmetric
  /// positive definite (products of inertia carry their minus sign: I_xy = −∫xy dm).
  glm::dmat3 inertiaAboutComKgM2{0.0};
};

/// The object's density from its settings, or kDefaultDensityKgPerM3, kg/m³.
double objectDensityKgPerM3(const SceneObject& object);

/// Mass properties of `object` at uniform `densityKgPerM3`, from the closed triangle
/// meshes of all its parts (their volumes add; parts must not overlap). Throws
/// voxhap::Error naming the object (and part) when the density is not a positive
/// finite number, when a part is open or not consistently oriented, or when a part's
/// or the object's volume is not positive (an inside-out mesh). Deterministic.
MassProperties computeMassProperties(const SceneObject& object, double densityKgPerM3);

}  // namespace voxhap
