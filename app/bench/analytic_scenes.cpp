#include "app/bench/analytic_scenes.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "haptics/geometry/mesh_builder.h"

namespace voxhap::cli {
namespace {

constexpr int kSphereSubdivisions = 4;  // 8·4^4 = 2048 triangles

SceneObject oneMeshObject(const std::string& name, ObjectRole role, TriangleMesh mesh) {
  SceneObject object;
  object.name = name;
  object.settings.role = role;
  object.parts.push_back(makePart(name, glm::vec4(1.0f), std::move(mesh)));
  return object;
}

}  // namespace

SceneObject plateObject(const std::string& name, double halfXyM, double thicknessM) {
  TriangleMesh mesh;
  appendBox(mesh, glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 0.0, -0.5 * thicknessM)),
            glm::dvec3(halfXyM, halfXyM, 0.5 * thicknessM));
  return oneMeshObject(name, ObjectRole::Static, std::move(mesh));
}

SceneObject boxObject(const std::string& name, const glm::dvec3& centreWorld, const glm::dvec3& halfM,
                      ObjectRole role) {
  TriangleMesh mesh;
  appendBox(mesh, glm::translate(glm::dmat4(1.0), centreWorld), halfM);
  return oneMeshObject(name, role, std::move(mesh));
}

SceneObject sphereObject(const std::string& name, const glm::dvec3& centreWorld, double radiusM) {
  TriangleMesh mesh;
  appendGeodesicSphere(mesh, glm::translate(glm::dmat4(1.0), centreWorld), radiusM, kSphereSubdivisions);
  return oneMeshObject(name, ObjectRole::Dynamic, std::move(mesh));
}

TriangleMesh posedMesh(const SceneObject& object, const Pose& pose) {
  TriangleMesh out;
  for (const Part& part : object.parts) {
    const auto base = static_cast<std::uint32_t>(out.positionsWorld.size());
    for (const glm::vec3& p : part.mesh.positionsWorld)
      out.positionsWorld.push_back(glm::vec3(apply(pose, glm::dvec3(p))));
    for (const glm::uvec3& t : part.mesh.triangles) out.triangles.push_back(t + glm::uvec3(base));
  }
  return out;
}

double percentile(std::vector<double> values, double p) {
  if (values.empty()) return 0.0;
  const double rank = std::ceil(std::clamp(p, 0.0, 1.0) * static_cast<double>(values.size()));
  const std::size_t k = rank < 1.0 ? 0 : static_cast<std::size_t>(rank) - 1;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  return values[k];
}

}  // namespace voxhap::cli
