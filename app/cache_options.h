#pragma once
/// The voxel cache as the command line sets it: `--cache-dir DIR` and `--no-cache`,
/// shared by every command that voxelizes.

#include "app/cli/args.h"
#include "app/cli/console.h"
#include "haptics/sim/scene_model.h"
#include "haptics/voxel/voxel_cache.h"

namespace voxhap::cli {

/// `--cache-dir DIR`: where voxmaps and pointshells are cached.
extern const OptionSpec kCacheDirOption;
/// `--no-cache`: build afresh, read and write nothing.
extern const OptionSpec kNoCacheOption;

/// The cache those options ask for; by default userCacheDir()/voxels.
CacheOptions voxelCacheOptions(const ParsedArgs& args);

/// Makes `options` build its voxmaps and pointshells through `cache`, passing the cache's
/// warnings to `console` (which must outlive the options).
void useVoxelCache(SceneModelOptions& options, const CacheOptions& cache, Console& console);

}  // namespace voxhap::cli
