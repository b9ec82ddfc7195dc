#include "app/cache_options.h"

#include "app/scene_source.h"

namespace voxhap::cli {

const OptionSpec kCacheDirOption{"cache-dir", 0, "DIR", "voxel cache folder (default ~/.cache/voxhap/voxels)"};
const OptionSpec kNoCacheOption{"no-cache", 0, "", "build voxels afresh; neither read nor write the cache"};

CacheOptions voxelCacheOptions(const ParsedArgs& args) {
  return {args.value(kCacheDirOption.longName).value_or((userCacheDir() / "voxels").string()),
          !args.has(kNoCacheOption.longName)};
}

}  // namespace voxhap::cli
