#include "app/cache_options.h"

namespace voxhap::cli {

void useVoxelCache(SceneModelOptions& options, const CacheOptions& cache, Console& console) {
  Console* warnings = &console;
  options.voxelizeFn = [cache, warnings](std::span<const SceneObject* const> objects,
                                         const VoxelizeOptions& o, const ProgressFn& progress) {
    CachedVoxelization v = voxelizeCached(objects, o, cache, progress);
    for (const std::string& w : v.warnings) warnings->warning(w);
    return std::move(v.voxelized.voxmap);
  };
  options.pointshellFn = [cache, warnings](const SceneObject& object, const PointshellOptions& o,
                                           const ProgressFn& progress) {
    const SceneObject* one[] = {&object};
    CachedPointshell p = pointshellCached(one, o, cache, progress);
    for (const std::string& w : p.warnings) warnings->warning(w);
    return std::move(p.pointshell);
  };
}

}  // namespace voxhap::cli
