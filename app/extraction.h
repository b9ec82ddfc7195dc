#pragma once
/// The landing gear's actuator extraction (paper §7), run headless for `voxhap demo` and
/// `voxhap bench extraction`: the actuator follows a motion script out of its clevises
/// and out of the gear at 1 kHz, while the run measures what the engine cannot tell
/// about itself: the exact penetration between the actuator's and the static meshes, both
/// ways, faces included (Embree ground truth, haptics/collide/exact_penetration.h), how
/// far along the path the actuator got compared with its handle, and when it came clear.

#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "app/cli/console.h"
#include "app/exact_checks.h"
#include "app/sim_run.h"
#include "haptics/device/motion_script.h"
#include "haptics/scene/scene.h"
#include "haptics/sim/scene_model.h"

namespace voxhap::cli {

/// The object the extraction moves.
inline constexpr const char* kActuatorName = "actuator";
/// Default resolution of the extraction (paper Table 1's coarser landing-gear row), m.
inline constexpr double kExtractionVoxelSizeM = 2.5e-3;
inline constexpr double kExtractionPointSpacingM = 1.0e-3;
/// Point tests per frame of `voxhap demo` unless --capacity says otherwise: what one core
/// of this class tests in half a frame (about 24 ns a test, issue 13's profile). Fixed, so
/// that the scripted job goes the same way on a loaded machine: measured online while two
/// compilers ran beside it, the capacity fell, MaxTravel held the actuator back behind
/// the handle and it stuck 21 mm along the path, its eyes still in the clevises.
inline constexpr double kDemoCapacityTests = 20000.0;
/// Frames between two exact penetration measurements by default (the last frame is always
/// measured).
inline constexpr std::uint64_t kPenetrationEveryFrames = 1;
/// Frames between two checks of whether the actuator is clear of the gear.
inline constexpr std::uint64_t kClearCheckEveryFrames = 100;

/// The committed extraction script, assets/scripts/actuator-extract.txt.
std::filesystem::path extractionScriptPath();

struct ExtractionOptions {
  std::string moving = kActuatorName;  ///< the object to pull out
  SceneModelOptions model;             ///< resolution, sampling, capacity, cache
  std::optional<double> durationS;     ///< simulated time; default: the script's
  std::uint64_t penetrationEvery =
      kPenetrationEveryFrames;  ///< measure the exact penetration every N frames (≥ 1)
  /// Probe spacing of the exact penetration, m; 0: the static voxel size / kProbesPerVoxel.
  double probeSpacingM = 0.0;
  std::string label = "extraction";  ///< progress bar label prefix
};

/// What one extraction run measured.
struct ExtractionResult {
  FrameStats stats;
  std::uint64_t points = 0;  ///< the actuator's pointshell
  double durationS = 0.0;    ///< simulated, s
  double wallS = 0.0;        ///< building the model (cache loads) and running the frames, s
  double framesWallS = 0.0;  ///< the frame loop, s (the exact measurement follows it: exact.wallS)
  // ground truth
  ExactCheckSummary exact;          ///< the exact penetration checks (one pair: actuator / static)
  std::uint64_t probesChecked = 0;  ///< probes on the actuator's surface
  double probeSpacingM = 0.0;       ///< their spacing, m
  // progress along the path, arc length of the actuator's centre along the script's path
  double pathLengthM = 0.0;        ///< of the whole script
  double handleProgressM = 0.0;    ///< where the handle ended
  double actuatorProgressM = 0.0;  ///< where the actuator ended
  double finalLagM = 0.0;          ///< distance between them at the end, m
  /// Simulated time from which the actuator stayed clear of the gear to the end (every
  /// point beyond the static distance field), or none when it ended near or in it.
  std::optional<double> completionS;

  /// Came out: clear of the gear at the end, with its centre within kArrivedM of the
  /// path's end.
  bool cameOut() const { return completionS.has_value() && actuatorProgressM >= pathLengthM - kArrivedM; }
  static constexpr double kArrivedM = 0.010;
};

/// Runs the extraction of `scene`'s object `options.moving` along `script`. Throws
/// voxhap::Error when the scene has no such object or the model cannot be built.
ExtractionResult runExtraction(const Scene& scene, const MotionScript& script,
                               const ExtractionOptions& options, Console& console);

}  // namespace voxhap::cli
