#include "app/voxelize_objects.h"

#include "app/cli/number_format.h"
#include "haptics/core/error.h"

namespace voxhap::cli {

std::string objectList(const Scene& scene) {
  std::string list;
  for (const SceneObject& o : scene.objects) {
    list += (list.empty() ? "" : ", ") + o.name + " (" + roleName(o.settings.role) + ")";
  }
  return list;
}

std::vector<const SceneObject*> objectsToVoxelize(const Scene& scene,
                                                  const std::optional<std::string>& name) {
  std::vector<const SceneObject*> objects;
  if (name) {
    const SceneObject* object = scene.find(*name);
    if (!object) {
      throw Error(scene.sourceName + ": no object named '" + *name + "' (objects: " + objectList(scene) +
                  ")");
    }
    objects.push_back(object);
    return objects;
  }
  for (const SceneObject& o : scene.objects) {
    if (o.settings.role == ObjectRole::Static) objects.push_back(&o);
  }
  if (objects.empty()) {
    throw Error(scene.sourceName +
                ": no static objects; pick one with --object (objects: " + objectList(scene) + ")");
  }
  return objects;
}

void warnAboutVoxelization(Console& console, const std::string& shownName, const CachedVoxelization& result) {
  for (const std::string& warning : result.warnings) console.warning(warning);
  const VoxelizeStats& stats = result.voxelized.stats;
  if (stats.voteDisagreements > 0 && stats.firstDisagreementLocal) {
    const glm::dvec3 p = *stats.firstDisagreementLocal;
    console.warning(shownName + ": inside/outside votes disagree at " + withCommas(stats.voteDisagreements) +
                    " voxels (holes in the mesh?), e.g. near (" + fixed(p.x, 4) + ", " + fixed(p.y, 4) +
                    ", " + fixed(p.z, 4) + ") m");
  }
}

}  // namespace voxhap::cli
