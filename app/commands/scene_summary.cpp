#include "app/commands/scene_summary.h"

#include <cstdio>
#include <iomanip>

namespace voxhap::cli {
namespace {

nlohmann::ordered_json vec3Json(const glm::dvec3& v) { return {v.x, v.y, v.z}; }

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
    entry["parts"] = parts;
    objects.push_back(entry);
  }
  return {{"scene", scene.sourceName},
          {"objects_count", scene.objects.size()},
          {"triangles", scene.triangleCount()},
          {"static_triangles", scene.triangleCount(ObjectRole::Static)},
          {"dynamic_triangles", scene.triangleCount(ObjectRole::Dynamic)},
          {"bounds_m", boundsJson(scene.bounds())},
          {"objects", objects},
          {"warnings", scene.warnings}};
}

void printSceneSummary(std::ostream& out, const Scene& scene, bool withParts) {
  out << "scene      " << scene.sourceName << "\n";
  out << "objects    " << scene.objects.size() << "\n";
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
          << (part.topology.closed() ? "" : "  open") << (part.topology.consistentlyOriented() ? "" : "  misoriented")
          << "\n";
    }
  }
}

}  // namespace voxhap::cli
