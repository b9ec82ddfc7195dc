#pragma once
/// Building voxmaps and pointshells through the voxel cache, shared by every command that
/// voxelizes (the cache's folder and whether it is used come from the command line:
/// voxelCacheOptions, sim_options.h).

#include "app/cli/console.h"
#include "haptics/sim/scene_model.h"
#include "haptics/voxel/voxel_cache.h"

namespace voxhap::cli {

/// Makes `options` build its voxmaps and pointshells through `cache`, passing the cache's
/// warnings to `console` (which must outlive the options).
void useVoxelCache(SceneModelOptions& options, const CacheOptions& cache, Console& console);

}  // namespace voxhap::cli
