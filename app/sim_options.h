#pragma once
/// The simulation options `voxhap` commands share, defined once as typed fields: resolution
/// and sampling (--voxel-size, --point-spacing, --point-offset, --point-layer,
/// --no-awareness, --pre-contact-damping, --paper-contact), time-critical sampling (--capacity,
/// --brute-force, --no-drifting, --frame-helper), paging (--voxel-memory), the device (--device-profile),
/// the run (--duration), the exact checks' probes (--probe-spacing) and the voxel cache
/// (--cache-dir, --no-cache). Each command adds the ones it takes to its CLI::App; their
/// values are parsed and checked while the command line is (option_values.h).

#include <cstdint>
#include <initializer_list>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "app/cli/console.h"
#include "haptics/dynamics/virtual_coupling.h"
#include "haptics/runtime/frame_helper.h"
#include "haptics/sim/scene_model.h"
#include "haptics/voxel/voxel_cache.h"

namespace CLI {
class App;
}  // namespace CLI

namespace voxhap::cli {

/// The shared options as given; empty or false when not.
struct SimOptions {
  std::optional<double> voxelSizeM;     ///< --voxel-size: of the static voxmap, m (> 0)
  std::optional<double> pointSpacingM;  ///< --point-spacing: of the moving objects' points, m (> 0)
  std::optional<double> pointOffsetM;   ///< --point-offset: along each point's normal, m; < 0 inward
  std::optional<int> pointLayer;        ///< --point-layer: free-space layer of the points, voxels
  std::map<std::string, std::uint8_t> forceLayerOf;  ///< --force-layer-of OBJECT=N, by object
  bool noAwareness = false;                          ///< --no-awareness: no geometrical awareness
  bool preContactDamping = false;                    ///< --pre-contact-damping
  bool paperContact = false;              ///< --paper-contact: the paper's voxel planes, not surface planes
  bool bruteForce = false;                ///< --brute-force: every point every frame
  bool noDrifting = false;                ///< --no-drifting: no point drifting
  bool frameHelper = false;               ///< --frame-helper: a second thread shares large frames
  std::optional<std::uint64_t> capacity;  ///< --capacity: point tests per frame (≥ 1)
  std::optional<std::uint64_t> voxelMemoryBytes;  ///< --voxel-memory: for the static voxels, bytes
  std::optional<DeviceLimits> deviceLimits;       ///< --device-profile NAME: that profile's limits
  std::optional<double> durationS;                ///< --duration: simulated time, s (≥ 0)
  std::optional<double> probeSpacingM;            ///< --probe-spacing: of the exact checks' probes, m (> 0)
  std::optional<std::string> cacheDir;            ///< --cache-dir: the voxel cache folder
  bool noCache = false;                           ///< --no-cache: neither read nor write the cache
};

/// One option of SimOptions (Cache: --cache-dir and --no-cache).
enum class SimOption {
  VoxelSize,
  PointSpacing,
  PointOffset,
  ForceLayerOf,
  PointLayer,
  NoAwareness,
  PreContactDamping,
  PaperContact,
  Capacity,
  VoxelMemory,
  BruteForce,
  NoDrifting,
  FrameHelper,
  DeviceProfile,
  Duration,
  ProbeSpacing,
  Cache,
};

/// Adds the options `which` to `command`, in that order (--help lists them so), bound to
/// `options`, which must outlive `command`. Each comes with a general help line; a command
/// that has more to say (its default, say) replaces it with
/// `command.get_option("--voxel-size")->description(…)`.
void addSimOptions(CLI::App& command, SimOptions& options, std::initializer_list<SimOption> which);

/// The frame helper `options` ask for (--frame-helper), or null. Throws Error where there
/// is no spare core.
std::shared_ptr<FrameHelper> frameHelperFor(const SimOptions& options);

/// The voxel cache `options` ask for; by default userCacheDir()/voxels.
CacheOptions voxelCacheOptions(const SimOptions& options);

/// SceneModelOptions from `options`: the voxel size (default `defaultVoxelSizeM`), point
/// spacing (default `defaultPointSpacingM`, else the voxel size), offset, layer, awareness,
/// damping, sampling, capacity, device limits, and voxmaps and pointshells built through
/// the voxel cache (paged within --voxel-memory when given), whose warnings go to
/// `console` (which must outlive the result).
SceneModelOptions sceneModelOptions(const SimOptions& options, Console& console, double defaultVoxelSizeM,
                                    std::optional<double> defaultPointSpacingM = std::nullopt);

}  // namespace voxhap::cli
