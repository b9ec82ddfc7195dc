#include "app/extraction_options.h"

#include <CLI/CLI.hpp>

#include "app/cli/option_values.h"
#include "app/scene_source.h"

namespace voxhap::cli {

std::string ExtractionArgs::scriptFile() const {
  return script.value_or(extractionScriptPath().string());
}

std::string ExtractionArgs::sceneName() const {
  return scene.value_or(kDefaultSceneName);
}

void addExtractionOptions(CLI::App& command, ExtractionArgs& args) {
  addParsedOption(command, "--penetration-every", "N",
                  "measure the exact penetration every N frames (default 1)",
                  [&args](const std::string& text) {
                    args.penetrationEvery = parseUnsigned(text, "penetration-every");
                    if (*args.penetrationEvery < 1)
                      throw UsageError("--penetration-every wants at least 1 frame");
                  });
  addSimOptions(command, args.sim, {SimOption::ProbeSpacing});
  command
      .add_option("--script", args.script,
                  "motion script of the handle (default assets/scripts/actuator-extract.txt)")
      ->type_name("FILE");
  command
      .add_option("--scene", args.scene, "a .gltf/.glb file or built-in scene name (default landing-gear)")
      ->type_name("SCENE");
  command.add_option("--move", args.move, "the object or group to pull out (default actuator)")
      ->type_name("NAME");
}

ExtractionOptions extractionOptions(const ExtractionArgs& args, Console& console, double defaultVoxelSizeM,
                                    double defaultPointSpacingM) {
  ExtractionOptions options;
  options.moving = args.move.value_or(kActuatorName);
  options.model = sceneModelOptions(args.sim, console, defaultVoxelSizeM, defaultPointSpacingM);
  options.durationS = args.sim.durationS;
  options.penetrationEvery = args.penetrationEvery.value_or(kPenetrationEveryFrames);
  options.probeSpacingM = args.sim.probeSpacingM.value_or(0.0);
  return options;
}

}  // namespace voxhap::cli
