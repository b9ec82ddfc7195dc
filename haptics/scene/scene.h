#pragma once
/// The engine's scene: what a glTF file (or a built-in generator) describes,
/// baked into world coordinates and grouped into logical objects.
///
/// A `Scene` is built at load time and read-only afterwards. Positions are in
/// metres in the world frame (node transforms already applied); the voxmap and
/// pointshell of an object are later built in that same frame, which becomes the
/// object's local frame at load time (DESIGN §3).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace voxhap {

/// An indexed triangle mesh in world coordinates (metres).
struct TriangleMesh {
  std::vector<glm::vec3> positionsWorld;  ///< vertex positions, metres, world frame
  std::vector<glm::uvec3> triangles;      ///< counter-clockwise seen from outside
};

/// What the scene file says an object does in the simulation.
enum class ObjectRole : std::uint8_t {
  Static,   ///< fixed in the world; voxelized, never moves
  Dynamic,  ///< may be grabbed and moved by a user
};

/// Name of a role as written in glTF extras and printed by the CLI.
const char* roleName(ObjectRole role);

/// Edge-level topology of a mesh after welding vertices with equal positions.
struct MeshTopology {
  std::uint64_t boundaryEdges = 0;     ///< edges used by exactly one triangle
  std::uint64_t nonManifoldEdges = 0;  ///< edges used by three or more triangles
  std::uint64_t misorientedEdges = 0;  ///< two-triangle edges walked the same way by both
  /// A point on the first boundary or non-manifold edge found, for messages (world, m).
  std::optional<glm::vec3> firstOpenEdgeWorld;

  /// Every edge is shared by exactly two triangles.
  bool closed() const { return boundaryEdges == 0 && nonManifoldEdges == 0; }
  /// Every shared edge is walked in opposite directions by its two triangles.
  bool consistentlyOriented() const { return misorientedEdges == 0; }
};

/// One glTF mesh node: a part of a logical object, with its own colour.
struct Part {
  std::string name;           ///< node name (or "node N" when the node has none)
  glm::vec4 baseColor{1.0f};  ///< linear RGBA, from the material's baseColorFactor
  TriangleMesh mesh;          ///< world frame; degenerate triangles already dropped
  std::uint64_t degenerateTrianglesDropped = 0;
  MeshTopology topology;  ///< of `mesh`, computed by makePart
};

/// Builds a part: drops degenerate triangles (repeated vertex or zero area),
/// counts them, and computes the topology. Every Part is made through here.
Part makePart(std::string name, glm::vec4 baseColor, TriangleMesh mesh);

/// Axis-aligned bounding box, metres, world frame. Empty when min > max.
struct Bounds {
  glm::dvec3 min{1e300};
  glm::dvec3 max{-1e300};

  bool empty() const { return min.x > max.x; }
  void add(const glm::dvec3& p);
  void add(const Bounds& b);
  glm::dvec3 extent() const { return empty() ? glm::dvec3(0.0) : max - min; }
};

/// The largest point offset either way that a scene or a client may give, m.
constexpr double kMaxPointOffsetM = 1.0;

/// Per-object settings read from a node's `extras.voxhap` (DESIGN §5).
struct ObjectSettings {
  ObjectRole role = ObjectRole::Static;
  std::optional<double> densityKgPerM3;  ///< for mass and inertia; engine default if unset
  /// Its points' displacement along their normals, m, negative inward: what seats a part
  /// in a close fit (paper §3.2, mating surfaces). 0 if unset.
  std::optional<double> pointOffsetM;
  /// The force layer of its pairs when it moves (paper §3.2: a mating part's own; a pair
  /// of two such objects takes the smaller); unset: the session's, which the user may vary.
  std::optional<std::uint8_t> forceLayer;
};

/// A logical object: one or more parts that collide as one rigid body.
struct SceneObject {
  std::string name;
  ObjectSettings settings;
  std::vector<Part> parts;
  /// Its parts were grouped by a node's `extras.voxhap` (false: one plain mesh node, or
  /// an object made in code).
  bool namedByExtras = false;

  std::uint64_t triangleCount() const;
  Bounds bounds() const;
  bool closed() const;                ///< every part closed
  bool consistentlyOriented() const;  ///< every part consistently oriented
};

/// A node of the file's hierarchy that holds parts without being an object itself: no
/// mesh of its own, no `extras.voxhap`, and no ancestor with them (a CAD sub-assembly, e.g.
/// a piston with its wrist pin). Moving a group merges the objects under it into one rigid
/// body (object_selection.h).
struct SceneGroup {
  std::string name;  ///< the node's name; unique among the scene's objects and groups
  /// Indices in Scene::objects of the objects with a part under the node, ascending.
  std::vector<std::size_t> objects;
};

/// A whole scene: its objects and what the loader had to say about it.
struct Scene {
  std::string sourceName;  ///< file path or generator name, for messages
  std::vector<SceneObject> objects;
  /// The file's groups, parents before their children; empty for a scene made in code.
  std::vector<SceneGroup> groups;
  std::vector<std::string> warnings;  ///< one line each; nothing the loader skipped is silent

  std::uint64_t triangleCount() const;
  std::uint64_t triangleCount(ObjectRole role) const;
  Bounds bounds() const;
  /// The object with this name, or nullptr.
  const SceneObject* find(const std::string& name) const;
  /// The group with this name, or nullptr.
  const SceneGroup* findGroup(const std::string& name) const;
};

}  // namespace voxhap
