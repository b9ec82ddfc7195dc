#pragma once
/// Small procedural scenes for the benchmarks that need analytic ground truth (scaling,
/// error), and the statistics they share. World frame, metres, z up; every plate's top
/// face is the plane z = 0.

#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "haptics/dynamics/pose.h"
#include "haptics/scene/scene.h"

namespace voxhap::cli {

/// A static box plate of half size `halfXyM` × `halfXyM` whose top face is z = 0,
/// `thicknessM` thick.
SceneObject plateObject(const std::string& name, double halfXyM, double thicknessM);

/// A dynamic axis-aligned box of half extents `halfM` centred on `centreWorld`.
SceneObject boxObject(const std::string& name, const glm::dvec3& centreWorld, const glm::dvec3& halfM,
                      ObjectRole role = ObjectRole::Dynamic);

/// A dynamic geodesic sphere (2048 triangles, vertices on the sphere) centred on `centreWorld`.
SceneObject sphereObject(const std::string& name, const glm::dvec3& centreWorld, double radiusM);

/// `object`'s triangles moved rigidly by `pose` (local → world), all parts as one mesh.
TriangleMesh posedMesh(const SceneObject& object, const Pose& pose);

/// The value at quantile `p` in [0, 1] (nearest rank); 0 for no values.
double percentile(std::vector<double> values, double p);

}  // namespace voxhap::cli
