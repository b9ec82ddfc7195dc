#include "haptics/scene/object_selection.h"

#include <algorithm>

#include "haptics/core/error.h"

namespace voxhap {
namespace {

std::string quoted(const std::string& name) {
  return "'" + name + "'";
}

/// Members of a group named in a list of what can be moved, at most this many.
constexpr std::size_t kMembersNamed = 4;

}  // namespace

std::string groupMoveProblem(const Scene& scene, const SceneGroup& group) {
  for (const std::size_t i : group.objects) {
    const SceneObject& object = scene.objects[i];
    if (object.namedByExtras) {
      return "group " + quoted(group.name) + " holds object " + quoted(object.name) +
             ", which a node's extras.voxhap make an object of its own; move " + quoted(object.name) +
             ", or put the extras on node " + quoted(group.name) + " to make the group one object";
    }
  }
  return "";
}

std::string movableNames(const Scene& scene) {
  std::string objects;
  for (const SceneObject& o : scene.objects) objects += (objects.empty() ? "" : ", ") + o.name;
  std::string groups;
  for (const SceneGroup& g : scene.groups) {
    if (!groupMoveProblem(scene, g).empty()) continue;
    std::string members;
    for (std::size_t k = 0; k < g.objects.size() && k < kMembersNamed; ++k) {
      members += (k > 0 ? ", " : "") + scene.objects[g.objects[k]].name;
    }
    if (g.objects.size() > kMembersNamed) members += ", ...";
    groups += (groups.empty() ? "" : ", ") + g.name + " (" + members + ")";
  }
  return "objects: " + objects + (groups.empty() ? "" : "; groups: " + groups);
}

ObjectSelection selectObjects(const Scene& scene, std::span<const std::string> names) {
  ObjectSelection selection;
  // per object of the scene, the name that holds it (names.size(): none yet)
  std::vector<std::size_t> heldBy(scene.objects.size(), names.size());
  for (std::size_t n = 0; n < names.size(); ++n) {
    const std::string& name = names[n];
    if (std::find(names.begin(), names.begin() + static_cast<std::ptrdiff_t>(n), name) !=
        names.begin() + static_cast<std::ptrdiff_t>(n)) {
      throw Error(scene.sourceName + ": " + quoted(name) + " is moved twice");
    }
    std::vector<std::size_t> held;
    const SceneObject* object = scene.find(name);
    const SceneGroup* group = object ? nullptr : scene.findGroup(name);
    if (object) {
      held.push_back(static_cast<std::size_t>(object - scene.objects.data()));
    } else if (group) {
      const std::string problem = groupMoveProblem(scene, *group);
      if (!problem.empty()) throw Error(scene.sourceName + ": " + problem);
      held = group->objects;
    } else {
      throw Error(scene.sourceName + ": no object or group named " + quoted(name) + " (" +
                  movableNames(scene) + ")");
    }
    for (const std::size_t i : held) {
      if (heldBy[i] != names.size()) {
        throw Error(scene.sourceName + ": " + quoted(names[heldBy[i]]) + " and " + quoted(name) +
                    " both hold object " + quoted(scene.objects[i].name) + "; move one of them");
      }
      heldBy[i] = n;
    }
    if (object) {
      selection.picked.push_back(object);
      continue;
    }
    auto merged = std::make_unique<SceneObject>();
    merged->name = group->name;
    merged->settings.role = ObjectRole::Dynamic;
    for (const std::size_t i : held) {
      const std::vector<Part>& parts = scene.objects[i].parts;
      merged->parts.insert(merged->parts.end(), parts.begin(), parts.end());
    }
    selection.picked.push_back(merged.get());
    selection.merged.push_back(std::move(merged));
  }
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    if (heldBy[i] == names.size()) selection.rest.push_back(&scene.objects[i]);
  }
  return selection;
}

std::vector<std::string> dynamicObjectNames(const Scene& scene) {
  std::vector<std::string> names;
  for (const SceneObject& o : scene.objects) {
    if (o.settings.role == ObjectRole::Dynamic) names.push_back(o.name);
  }
  return names;
}

}  // namespace voxhap
