#pragma once
/// Voxelizing and pointshell building through an on-disk cache (DESIGN §4.6).
///
/// A logical object, or several merged (all static objects of a scene as one static
/// environment), is voxelized once per geometry and parameters: the result is saved
/// in `CacheOptions::directory` under a name made of a 128-bit key, a hash of every
/// triangle position and index of every part (in order), the parameters that change
/// the result and the cache format version. A later call with the same key loads the
/// file instead (cache_file.h: versioned, checksummed, written atomically). A file
/// that is corrupt, truncated, of another format version or made from other data is
/// rebuilt and overwritten, with a warning; a cache folder that cannot be written
/// only costs a warning. Load time only; allocates; thread count never changes a
/// result, so it is not part of the key.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "haptics/core/progress.h"
#include "haptics/pointshell/pointshell.h"
#include "haptics/scene/scene.h"
#include "haptics/voxel/voxel_pager.h"
#include "haptics/voxel/voxelizer.h"

namespace voxhap {

/// Where the cache lives and whether to use it.
struct CacheOptions {
  std::filesystem::path directory;  ///< created when first written to; empty: no cache
  bool enabled = true;              ///< false: always build, never read or write files
};

/// A voxelization and how it was obtained.
struct CachedVoxelization {
  VoxelizedObject voxelized;          ///< the voxmap (object-local frame) and its counts
  bool cacheHit = false;              ///< read from the cache rather than built
  double voxelizeS = 0.0;             ///< seconds spent building (features + voxelize); 0 on a hit
  double loadS = 0.0;                 ///< seconds spent reading the cache file; 0 on a miss
  double saveS = 0.0;                 ///< seconds spent writing the cache file; 0 on a hit or when disabled
  std::filesystem::path cacheFile;    ///< the file read or written; empty when the cache is disabled
  std::vector<std::string> warnings;  ///< one line each, e.g. a corrupt cache file that was rebuilt
};

/// A pointshell and how it was obtained.
struct CachedPointshell {
  Pointshell pointshell;              ///< object-local frame
  bool cacheHit = false;              ///< read from the cache rather than built
  double buildS = 0.0;                ///< seconds spent building (features + pointshell); 0 on a hit
  double loadS = 0.0;                 ///< seconds spent reading the cache file; 0 on a miss
  double saveS = 0.0;                 ///< seconds spent writing the cache file; 0 on a hit or when disabled
  std::filesystem::path cacheFile;    ///< the file read or written; empty when the cache is disabled
  std::vector<std::string> warnings;  ///< one line each, e.g. a corrupt cache file that was rebuilt
};

/// Voxelizes the parts of `objects` (object-local frame = the scene's world frame) as one
/// voxmap: quasi-planar features per part (in parallel over parts), then voxelize().
/// Loads the result from the cache instead when it holds it. Throws voxhap::Error as
/// voxelize() does; cache trouble is never an error, only a warning.
CachedVoxelization voxelizeCached(std::span<const SceneObject* const> objects, const VoxelizeOptions& options,
                                  const CacheOptions& cache, const ProgressFn& progress = {});

/// A static voxmap within a memory budget (paper §5.3, DESIGN §4.6).
struct BudgetedVoxmap {
  Voxmap voxmap;                      ///< whole, or paged (its words come from `pager`)
  std::shared_ptr<VoxelPager> pager;  ///< null when the whole voxmap fits the budget
  std::uint64_t wordBytes = 0;        ///< the voxel words the cache file holds
  std::vector<std::string> warnings;
};

/// As voxelizeCached, but keeps at most `budgetBytes` of the voxmap in memory: when the
/// whole voxmap is larger, its tables are loaded and its voxel words are paged from the
/// cache file (built and saved first if the cache lacks it; its checksum is checked
/// once). Throws voxhap::Error when the cache is off or cannot be written, or when the
/// budget cannot hold the voxmap's tables and one chunk.
BudgetedVoxmap voxelizeWithinBudget(std::span<const SceneObject* const> objects,
                                    const VoxelizeOptions& options, const CacheOptions& cache,
                                    std::uint64_t budgetBytes, const ProgressFn& progress = {});

/// Builds the pointshell of the parts of `objects` (features at the point spacing, then
/// buildPointshell()), or loads it from the cache. Throws voxhap::Error as
/// buildPointshell() does.
CachedPointshell pointshellCached(std::span<const SceneObject* const> objects,
                                  const PointshellOptions& options, const CacheOptions& cache,
                                  const ProgressFn& progress = {});

}  // namespace voxhap
