#include "haptics/scene/scene.h"

#include <algorithm>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "haptics/geometry/mesh_topology.h"

namespace voxhap {

const char* roleName(ObjectRole role) {
  switch (role) {
    case ObjectRole::Static:
      return "static";
    case ObjectRole::Dynamic:
      return "dynamic";
  }
  return "unknown";
}

void Bounds::add(const glm::dvec3& p) {
  min = glm::min(min, p);
  max = glm::max(max, p);
}

void Bounds::add(const Bounds& b) {
  if (b.empty()) return;
  add(b.min);
  add(b.max);
}

Part makePart(std::string name, glm::vec4 baseColor, TriangleMesh mesh) {
  Part part;
  part.name = std::move(name);
  part.baseColor = baseColor;
  const auto& p = mesh.positionsWorld;
  auto isDegenerate = [&](const glm::uvec3& t) {
    if (t.x == t.y || t.y == t.z || t.z == t.x) return true;
    const glm::dvec3 a(p[t.x]);
    const glm::dvec3 areaVector = glm::cross(glm::dvec3(p[t.y]) - a, glm::dvec3(p[t.z]) - a);
    return areaVector == glm::dvec3(0.0);
  };
  const auto kept = std::remove_if(mesh.triangles.begin(), mesh.triangles.end(), isDegenerate);
  part.degenerateTrianglesDropped = static_cast<std::uint64_t>(mesh.triangles.end() - kept);
  mesh.triangles.erase(kept, mesh.triangles.end());
  part.topology = computeTopology(mesh);
  part.mesh = std::move(mesh);
  return part;
}

std::uint64_t SceneObject::triangleCount() const {
  std::uint64_t count = 0;
  for (const Part& part : parts) count += part.mesh.triangles.size();
  return count;
}

Bounds SceneObject::bounds() const {
  Bounds b;
  for (const Part& part : parts) {
    for (const glm::uvec3& t : part.mesh.triangles) {
      for (int k = 0; k < 3; ++k) b.add(glm::dvec3(part.mesh.positionsWorld[t[k]]));
    }
  }
  return b;
}

bool SceneObject::closed() const {
  return std::all_of(parts.begin(), parts.end(), [](const Part& p) { return p.topology.closed(); });
}

bool SceneObject::consistentlyOriented() const {
  return std::all_of(parts.begin(), parts.end(),
                     [](const Part& p) { return p.topology.consistentlyOriented(); });
}

std::uint64_t Scene::triangleCount() const {
  std::uint64_t count = 0;
  for (const SceneObject& object : objects) count += object.triangleCount();
  return count;
}

std::uint64_t Scene::triangleCount(ObjectRole role) const {
  std::uint64_t count = 0;
  for (const SceneObject& object : objects) {
    if (object.settings.role == role) count += object.triangleCount();
  }
  return count;
}

Bounds Scene::bounds() const {
  Bounds b;
  for (const SceneObject& object : objects) b.add(object.bounds());
  return b;
}

const SceneObject* Scene::find(const std::string& name) const {
  for (const SceneObject& object : objects) {
    if (object.name == name) return &object;
  }
  return nullptr;
}

const SceneGroup* Scene::findGroup(const std::string& name) const {
  for (const SceneGroup& group : groups) {
    if (group.name == name) return &group;
  }
  return nullptr;
}

}  // namespace voxhap
