#include "haptics/geometry/pseudo_normals.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace voxhap {
namespace {

std::uint64_t edgeKey(std::uint32_t a, std::uint32_t b) {
  return (std::uint64_t{std::min(a, b)} << 32) | std::max(a, b);
}

glm::dvec3 unitOr(const glm::dvec3& v, const glm::dvec3& fallback) {
  const double length = glm::length(v);
  return length > 0.0 ? v / length : fallback;
}

/// Angle at `p` between the directions to `q` and `r`, rad.
double angleAt(const glm::dvec3& p, const glm::dvec3& q, const glm::dvec3& r) {
  const glm::dvec3 u = q - p;
  const glm::dvec3 v = r - p;
  return std::atan2(glm::length(glm::cross(u, v)), glm::dot(u, v));
}

}  // namespace

PseudoNormals::PseudoNormals(std::span<const TriangleMesh* const> meshes)
    : meshes_(meshes.begin(), meshes.end()) {
  for (const TriangleMesh* mesh : meshes) {
    PartNormals part;
    auto& ids = part.idOfPosition;
    part.weldedOf.reserve(mesh->positionsWorld.size());
    for (const glm::vec3& p : mesh->positionsWorld) {
      const auto [it, added] =
          ids.emplace(std::make_tuple(p.x, p.y, p.z), static_cast<std::uint32_t>(ids.size()));
      part.weldedOf.push_back(it->second);
    }
    part.vertexNormals.assign(ids.size(), glm::dvec3(0.0));
    for (const glm::uvec3& t : mesh->triangles) {
      const glm::dvec3 x[3] = {glm::dvec3(mesh->positionsWorld[t.x]), glm::dvec3(mesh->positionsWorld[t.y]),
                               glm::dvec3(mesh->positionsWorld[t.z])};
      const glm::dvec3 n = unitOr(glm::cross(x[1] - x[0], x[2] - x[0]), glm::dvec3(0.0));
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t id = part.weldedOf[t[k]];
        const std::uint32_t next = part.weldedOf[t[(k + 1) % 3]];
        part.vertexNormals[id] += angleAt(x[k], x[(k + 1) % 3], x[(k + 2) % 3]) * n;
        part.edgeNormals[edgeKey(id, next)] += n;
      }
    }
    for (glm::dvec3& n : part.vertexNormals) n = unitOr(n, glm::dvec3(0.0, 0.0, 1.0));
    for (auto& [key, n] : part.edgeNormals) n = unitOr(n, glm::dvec3(0.0, 0.0, 1.0));
    parts_.push_back(std::move(part));
  }
}

std::optional<glm::dvec3> PseudoNormals::vertexNormal(std::size_t part, const glm::vec3& vertexWorld) const {
  const auto& ids = parts_[part].idOfPosition;
  const auto it = ids.find(Key(vertexWorld.x, vertexWorld.y, vertexWorld.z));
  if (it == ids.end()) return std::nullopt;
  return parts_[part].vertexNormals[it->second];
}

std::optional<glm::dvec3> PseudoNormals::edgeNormal(std::size_t part, const glm::vec3& a,
                                                    const glm::vec3& b) const {
  const auto& ids = parts_[part].idOfPosition;
  const auto ia = ids.find(Key(a.x, a.y, a.z));
  const auto ib = ids.find(Key(b.x, b.y, b.z));
  if (ia == ids.end() || ib == ids.end()) return std::nullopt;
  const auto it = parts_[part].edgeNormals.find(edgeKey(ia->second, ib->second));
  if (it == parts_[part].edgeNormals.end()) return std::nullopt;
  return it->second;
}

glm::dvec3 PseudoNormals::normalAt(const ClosestSurfacePoint& closest, double toleranceM) const {
  const TriangleMesh& mesh = *meshes_[closest.part];
  const PartNormals& part = parts_[closest.part];
  const glm::uvec3& t = mesh.triangles[closest.triangle];
  int near[3];
  int count = 0;
  for (int k = 0; k < 3; ++k) {
    const glm::dvec3 a(mesh.positionsWorld[t[k]]);
    if (glm::length(closest.point - a) <= toleranceM) return part.vertexNormals[part.weldedOf[t[k]]];
    // distance from the closest point to the edge k → k+1
    const glm::dvec3 b(mesh.positionsWorld[t[(k + 1) % 3]]);
    const glm::dvec3 ab = b - a;
    const double along = std::clamp(glm::dot(closest.point - a, ab) / glm::dot(ab, ab), 0.0, 1.0);
    if (glm::length(closest.point - (a + along * ab)) <= toleranceM) near[count++] = k;
  }
  if (count > 0) {
    const int k = near[0];
    const auto it = part.edgeNormals.find(edgeKey(part.weldedOf[t[k]], part.weldedOf[t[(k + 1) % 3]]));
    if (it != part.edgeNormals.end()) return it->second;
  }
  return closest.faceNormal;
}

}  // namespace voxhap
