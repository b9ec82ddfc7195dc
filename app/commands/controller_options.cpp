#include "app/commands/controller_options.h"

#include "app/cli/option_values.h"
#include "app/extraction.h"

namespace voxhap::cli {

void addControllerRunOptions(CLI::App& command, ControllerRunArgs& args) {
  addSimOptions(command, args.sim,
                {SimOption::VoxelSize, SimOption::PointSpacing, SimOption::PointOffset,
                 SimOption::ForceLayerOf, SimOption::PaperContact, SimOption::Capacity,
                 SimOption::VoxelMemory, SimOption::DeviceProfile, SimOption::FrameHelper});
  command.get_option("--voxel-size")
      ->description("voxel size of the static scene (default 2.5mm, as the demo)");
  command.get_option("--point-spacing")->description("point spacing of the moving objects (default 1mm)");
  addParsedOption(
      command, "--duration", "SECONDS", "stop after this much wall time (default: run until told)",
      [&duration = args.durationS](const std::string& text) { duration = parseSeconds(text, "duration"); });
  command.add_flag("--no-realtime", args.noRealtime, "do not try SCHED_FIFO and mlockall");
  addSimOptions(command, args.sim, {SimOption::Cache});
  command.add_flag("--json", args.json, "print the summary as one JSON document on stdout");
}

void applyControllerRunArgs(const ControllerRunArgs& args, Console& console, ControllerOptions& options) {
  options.model = sceneModelOptions(args.sim, console, kExtractionVoxelSizeM, kExtractionPointSpacingM);
  options.durationS = args.durationS;
  options.realtime = !args.noRealtime;
  options.frameHelper = args.sim.frameHelper;
  options.json = args.json;
}

void checkDeviceOption(const std::string& d) {
  if (!d.empty() && d.rfind("script:", 0) != 0 && d.rfind("hand:", 0) != 0 && d != "spacemouse" &&
      d.rfind("spacemouse:", 0) != 0)
    throw UsageError("--device wants script:FILE, hand:FILE or spacemouse[:/dev/hidrawN], not '" + d + "'");
}

}  // namespace voxhap::cli
