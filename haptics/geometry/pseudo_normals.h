#pragma once
/// Angle-weighted pseudo-normals (Bærentzen and Aanæs, 2005) of closed triangle
/// meshes: the outward normal of the surface feature a closest point lies on. On a
/// face it is the face normal; on an edge, the normalized sum of its two faces'
/// normals; at a vertex, the sum of its faces' normals weighted by their angles there.
/// A pointshell point near a box corner then pushes along the corner's diagonal, not
/// along whichever face happened to be found first, so that symmetric contacts cancel.
///
/// Vertices are welded by exact position, as exporters split them along seams. Built
/// once at load time; const queries from any thread.

#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <tuple>
#include <unordered_map>
#include <vector>

#include <glm/vec3.hpp>

#include "haptics/geometry/embree_scene.h"
#include "haptics/scene/scene.h"

namespace voxhap {

class PseudoNormals {
public:
  /// The meshes are indexed as in the EmbreeScene built from the same span.
  explicit PseudoNormals(std::span<const TriangleMesh* const> meshes);

  /// Unit outward normal at `closest`, found by an EmbreeScene of the same meshes;
  /// a point within `toleranceM` of an edge or vertex takes that feature's normal.
  glm::dvec3 normalAt(const ClosestSurfacePoint& closest, double toleranceM) const;

  /// Normal of the mesh vertex of part `part` at exactly `vertexWorld`, if there is one.
  std::optional<glm::dvec3> vertexNormal(std::size_t part, const glm::vec3& vertexWorld) const;
  /// Normal of the mesh edge of part `part` between exactly `a` and `b`, if there is one.
  std::optional<glm::dvec3> edgeNormal(std::size_t part, const glm::vec3& a, const glm::vec3& b) const;

private:
  using Key = std::tuple<float, float, float>;
  struct PartNormals {
    std::map<Key, std::uint32_t> idOfPosition;                  // welded id of each distinct position
    std::vector<std::uint32_t> weldedOf;                        // per mesh vertex: its welded id
    std::vector<glm::dvec3> vertexNormals;                      // per welded id, unit
    std::unordered_map<std::uint64_t, glm::dvec3> edgeNormals;  // per welded edge, unit
  };
  std::vector<const TriangleMesh*> meshes_;
  std::vector<PartNormals> parts_;
};

}  // namespace voxhap
