#pragma once
/// What `voxhap voxelize` and `voxhap bench table1` share: which objects of a scene
/// are voxelized as one, and the warnings a voxelization raises.

#include <optional>
#include <string>
#include <vector>

#include "app/cli/console.h"
#include "haptics/scene/scene.h"
#include "haptics/voxel/voxel_cache.h"

namespace voxhap::cli {

/// Name under which the merged static objects are reported.
inline constexpr const char* kStaticObjectsName = "static";

/// "name (role), …" for every object of `scene`, for error messages.
std::string objectList(const Scene& scene);

/// The objects to voxelize as one: the one called `name`, or every static object when
/// `name` is empty. Pointers into `scene`. Throws voxhap::Error naming the scene and
/// listing its objects when there is no such object or no static one.
std::vector<const SceneObject*> objectsToVoxelize(const Scene& scene, const std::optional<std::string>& name);

/// Prints the cache's warnings and, when the inside/outside votes disagreed (holes in
/// the mesh?), how often and where, naming the object as `shownName`.
void warnAboutVoxelization(Console& console, const std::string& shownName, const CachedVoxelization& result);

}  // namespace voxhap::cli
