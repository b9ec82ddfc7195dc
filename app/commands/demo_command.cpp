#include "app/cli/command.h"
#include "app/commands/commands.h"
#include "app/commands/scene_summary.h"
#include "app/scene_source.h"

namespace voxhap::cli {
namespace {

int runDemo(const CommandContext& c) {
  if (!c.args.positionals.empty()) throw UsageError("takes no arguments; use --scene SCENE");
  const std::string name = c.args.value("scene").value_or(kDefaultSceneName);
  const Scene scene = loadScene(name, kDefaultSeed, c.console);
  if (c.args.has("json")) {
    c.out << sceneSummaryJson(scene).dump(2) << "\n";
  } else {
    printSceneSummary(c.out, scene, c.console.verbosity() == Verbosity::Verbose);
  }
  return kExitOk;
}

}  // namespace

Command demoCommand() {
  Command demo;
  demo.name = "demo";
  demo.summary = "The main job on the built-in landing gear: load it and summarise it.";
  demo.usage = "voxhap demo [--scene SCENE] [--json]";
  demo.description =
      "Generates the built-in landing-gear scene on first use (cached afterwards under\n"
      "$VOXHAP_CACHE_DIR, $XDG_CACHE_HOME/voxhap or ~/.cache/voxhap), loads it and prints\n"
      "its objects. Later versions run the actuator extraction here.\n\n"
      "Examples:\n"
      "  voxhap demo\n"
      "  voxhap demo --scene assets/peg-in-hole.glb --json";
  demo.options = {{"scene", 0, "SCENE", "a .gltf/.glb file or built-in scene name (default landing-gear)"},
                  {"json", 0, "", "print one JSON document on stdout instead of a table"}};
  demo.run = runDemo;
  return demo;
}

}  // namespace voxhap::cli
