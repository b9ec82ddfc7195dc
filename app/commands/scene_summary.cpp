#include "app/commands/scene_summary.h"

#include <algorithm>
#include <cstdio>
#include <iomanip>

#include "haptics/scene/object_selection.h"

namespace voxhap::cli {
namespace {

nlohmann::ordered_json vec3Json(const glm::dvec3& v) {
  return {v.x, v.y, v.z};
}

nlohmann::ordered_json boundsJson(const Bounds& b) {
  return {{"min", vec3Json(b.min)}, {"max", vec3Json(b.max)}, {"extent", vec3Json(b.extent())}};
}

std::string extentText(const Bounds& b) {
  const glm::dvec3 e = b.extent();
  char text[96];
  std::snprintf(text, sizeof text, "%.3f x %.3f x %.3f", e.x, e.y, e.z);
  return text;
}

std::string pad(const std::string& text, std::size_t width) {
  return text.size() >= width ? text + " " : text + std::string(width - text.size(), ' ');
}

/// What a group holds, from its objects.
struct GroupFigures {
  std::uint64_t parts = 0;
  std::uint64_t triangles = 0;
  Bounds bounds;
};

GroupFigures groupFigures(const Scene& scene, const SceneGroup& group) {
  GroupFigures f;
  for (const std::size_t i : group.objects) {
    const SceneObject& object = scene.objects[i];
    f.parts += object.parts.size();
    f.triangles += object.triangleCount();
    f.bounds.add(object.bounds());
  }
  return f;
}

/// Members of a group named in the text table, at most this many.
constexpr std::size_t kMembersShown = 6;

}  // namespace

nlohmann::ordered_json sceneSummaryJson(const Scene& scene) {
  nlohmann::ordered_json objects = nlohmann::ordered_json::array();
  for (const SceneObject& object : scene.objects) {
    nlohmann::ordered_json parts = nlohmann::ordered_json::array();
    std::uint64_t degenerate = 0;
    for (const Part& part : object.parts) {
      const glm::vec4& c = part.baseColor;
      parts.push_back({{"name", part.name},
                       {"triangles", part.mesh.triangles.size()},
                       {"base_color", {c.r, c.g, c.b, c.a}},
                       {"closed", part.topology.closed()},
                       {"consistently_oriented", part.topology.consistentlyOriented()},
                       {"boundary_edges", part.topology.boundaryEdges},
                       {"non_manifold_edges", part.topology.nonManifoldEdges},
                       {"misoriented_edges", part.topology.misorientedEdges},
                       {"degenerate_triangles_dropped", part.degenerateTrianglesDropped}});
      degenerate += part.degenerateTrianglesDropped;
    }
    nlohmann::ordered_json entry = {{"name", object.name},
                                    {"role", roleName(object.settings.role)},
                                    {"triangles", object.triangleCount()},
                                    {"bounds_m", boundsJson(object.bounds())},
                                    {"closed", object.closed()},
                                    {"consistently_oriented", object.consistentlyOriented()},
                                    {"degenerate_triangles_dropped", degenerate}};
    if (object.settings.densityKgPerM3) entry["density_kg_per_m3"] = *object.settings.densityKgPerM3;
    if (object.settings.pointOffsetM) entry["point_offset_m"] = *object.settings.pointOffsetM;
    if (object.settings.forceLayer) entry["force_layer"] = *object.settings.forceLayer;
    entry["parts"] = parts;
    objects.push_back(entry);
  }
  nlohmann::ordered_json groups = nlohmann::ordered_json::array();
  for (const SceneGroup& group : scene.groups) {
    nlohmann::ordered_json members = nlohmann::ordered_json::array();
    for (const std::size_t i : group.objects) members.push_back(scene.objects[i].name);
    const GroupFigures f = groupFigures(scene, group);
    const std::string problem = groupMoveProblem(scene, group);
    nlohmann::ordered_json entry = {{"name", group.name},
                                    {"objects", members},
                                    {"parts", f.parts},
                                    {"triangles", f.triangles},
                                    {"bounds_m", boundsJson(f.bounds)},
                                    {"movable", problem.empty()}};
    if (!problem.empty()) entry["not_movable_because"] = problem;
    groups.push_back(entry);
  }
  return {{"scene", scene.sourceName},
          {"objects_count", scene.objects.size()},
          {"groups_count", scene.groups.size()},
          {"triangles", scene.triangleCount()},
          {"static_triangles", scene.triangleCount(ObjectRole::Static)},
          {"dynamic_triangles", scene.triangleCount(ObjectRole::Dynamic)},
          {"bounds_m", boundsJson(scene.bounds())},
          {"objects", objects},
          {"groups", groups},
          {"warnings", scene.warnings}};
}

void printSceneSummary(std::ostream& out, const Scene& scene, bool withParts) {
  out << "scene      " << scene.sourceName << "\n";
  out << "objects    " << scene.objects.size() << "\n";
  if (!scene.groups.empty())
    out << "groups     " << scene.groups.size() << " (--move a group: its objects as one)\n";
  out << "triangles  " << scene.triangleCount() << " (static " << scene.triangleCount(ObjectRole::Static)
      << ", dynamic " << scene.triangleCount(ObjectRole::Dynamic) << ")\n";
  out << "extent     " << extentText(scene.bounds()) << " m\n\n";
  out << pad("object", 24) << pad("role", 9) << pad("parts", 7) << pad("triangles", 11)
      << pad("extent (m)", 24) << pad("closed", 8) << "oriented\n";
  for (const SceneObject& object : scene.objects) {
    out << pad(object.name, 24) << pad(roleName(object.settings.role), 9)
        << pad(std::to_string(object.parts.size()), 7) << pad(std::to_string(object.triangleCount()), 11)
        << pad(extentText(object.bounds()), 24) << pad(object.closed() ? "yes" : "NO", 8)
        << (object.consistentlyOriented() ? "yes" : "NO") << "\n";
    if (!withParts) continue;
    for (const Part& part : object.parts) {
      const glm::vec4& c = part.baseColor;
      char color[64];
      std::snprintf(color, sizeof color, "rgba(%.2f %.2f %.2f %.2f)", c.r, c.g, c.b, c.a);
      out << "  " << pad(part.name, 22) << pad(std::to_string(part.mesh.triangles.size()), 11) << color
          << (part.topology.closed() ? "" : "  open")
          << (part.topology.consistentlyOriented() ? "" : "  misoriented") << "\n";
    }
  }
  if (scene.groups.empty()) return;
  out << "\n"
      << pad("group", 24) << pad("objects", 9) << pad("parts", 7) << pad("triangles", 11)
      << pad("extent (m)", 24) << "holds\n";
  for (const SceneGroup& group : scene.groups) {
    const GroupFigures f = groupFigures(scene, group);
    std::string members;
    const std::size_t shown =
        withParts ? group.objects.size() : std::min(group.objects.size(), kMembersShown);
    for (std::size_t k = 0; k < shown; ++k)
      members += (k > 0 ? ", " : "") + scene.objects[group.objects[k]].name;
    if (shown < group.objects.size())
      members += ", ... (" + std::to_string(group.objects.size() - shown) + " more)";
    out << pad(group.name, 24) << pad(std::to_string(group.objects.size()), 9)
        << pad(std::to_string(f.parts), 7) << pad(std::to_string(f.triangles), 11)
        << pad(extentText(f.bounds), 24) << members
        << (groupMoveProblem(scene, group).empty() ? "" : "  (not movable: holds an object named by extras)")
        << "\n";
  }
}

}  // namespace voxhap::cli
