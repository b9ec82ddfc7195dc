#pragma once
/// The command line of an actuator extraction (extraction.h), shared by `voxhap demo` and
/// `voxhap bench extraction`: what to pull out of which scene along which script, and how
/// often to measure the exact penetration, besides the simulation options it takes.

#include <cstdint>
#include <optional>
#include <string>

#include "app/cli/console.h"
#include "app/extraction.h"
#include "app/sim_options.h"

namespace CLI {
class App;
}  // namespace CLI

namespace voxhap::cli {

/// The extraction's own options as given; empty when not.
struct ExtractionArgs {
  SimOptions sim;                                 ///< the simulation options the command takes
  std::optional<std::string> script;              ///< --script FILE: the handle's motion script
  std::optional<std::string> scene;               ///< --scene SCENE: a file or built-in scene name
  std::optional<std::string> move;                ///< --move NAME: the object or group to pull out
  std::optional<std::uint64_t> penetrationEvery;  ///< --penetration-every N: frames (≥ 1)

  /// The script file to run: --script, else extractionScriptPath().
  std::string scriptFile() const;
  /// The scene to load: --scene, else kDefaultSceneName.
  std::string sceneName() const;
};

/// Adds --penetration-every, --probe-spacing, --script, --scene and --move to `command`,
/// in that order, bound to `args`, which must outlive `command`.
void addExtractionOptions(CLI::App& command, ExtractionArgs& args);

/// The ExtractionOptions `args` ask for at the resolution given by --voxel-size and
/// --point-spacing or else by `defaultVoxelSizeM` and `defaultPointSpacingM`; the model's
/// warnings go to `console` (which must outlive the result).
ExtractionOptions extractionOptions(const ExtractionArgs& args, Console& console, double defaultVoxelSizeM,
                                    double defaultPointSpacingM);

}  // namespace voxhap::cli
