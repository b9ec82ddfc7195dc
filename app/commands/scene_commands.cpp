#include <chrono>
#include <filesystem>
#include <memory>
#include <optional>

#include <CLI/CLI.hpp>

#include "app/cli/command.h"
#include "app/commands/commands.h"
#include "app/commands/scene_summary.h"
#include "app/scene_source.h"
#include "haptics/core/error.h"
#include "haptics/scene/builtin/builtin_scenes.h"
#include "haptics/scene/gltf_writer.h"

namespace voxhap::cli {
namespace {

constexpr const char* kJsonHelp = "print one JSON document on stdout instead of a table";
constexpr const char* kSeedHelp = "seed of a generated scene (default 1); same seed, same bytes";

/// What `voxhap scene info` was given.
struct InfoArgs {
  std::string scene;
  std::uint64_t seed = kDefaultSeed;
  bool json = false;
};

/// What `voxhap scene generate` was given.
struct GenerateArgs {
  std::string name;
  std::optional<std::string> output;
  std::uint64_t seed = kDefaultSeed;
  bool json = false;
};

int runInfo(const InfoArgs& args, const CommandContext& c) {
  const Scene scene = loadScene(args.scene, args.seed, c.console);
  if (args.json) {
    c.out << sceneSummaryJson(scene).dump(2) << "\n";
  } else {
    printSceneSummary(c.out, scene, c.console.verbosity() == Verbosity::Verbose);
  }
  return kExitOk;
}

int runGenerate(const GenerateArgs& args, const CommandContext& c) {
  const std::string& name = args.name;
  const std::uint64_t seed = args.seed;
  const std::filesystem::path file = args.output.value_or(name + ".glb");
  const auto start = std::chrono::steady_clock::now();
  const Scene scene = makeBuiltinScene(name, seed, c.console.progress("generating " + name));
  writeGlbFile(scene, file);
  const double seconds = secondsSince(start);
  const auto bytes = std::filesystem::file_size(file);
  if (args.json) {
    nlohmann::ordered_json result = {{"scene", name},
                                     {"seed", seed},
                                     {"file", file.string()},
                                     {"bytes", bytes},
                                     {"objects_count", scene.objects.size()},
                                     {"triangles", scene.triangleCount()},
                                     {"static_triangles", scene.triangleCount(ObjectRole::Static)},
                                     {"dynamic_triangles", scene.triangleCount(ObjectRole::Dynamic)},
                                     {"seconds", seconds}};
    c.out << result.dump(2) << "\n";
  } else {
    c.out << "wrote " << file.string() << ": " << name << " (seed " << seed << "), " << scene.objects.size()
          << " objects, " << scene.triangleCount() << " triangles, " << bytes << " bytes\n";
  }
  return kExitOk;
}

}  // namespace

void addSceneCommands(CommandTree& tree) {
  CommandHelp scene;
  scene.summary = "Inspect glTF scenes and generate the built-in ones.";
  scene.usage = "voxhap scene COMMAND [OPTIONS]";
  scene.description =
      "Examples:\n"
      "  voxhap scene info assets/peg-in-hole.glb\n"
      "  voxhap scene generate landing-gear -o gear.glb";
  CLI::App& group = tree.add(tree.root(), "scene", std::move(scene));

  CommandHelp info;
  info.summary = "Describe a scene: objects, groups, parts, triangles, bounds, closed or not, roles.";
  info.usage = "voxhap scene info SCENE [--json] [--seed N]";
  info.description =
      "SCENE is a .gltf or .glb file, or a built-in scene name (ball-and-socket,\n"
      "peg-in-hole, landing-gear, landing-gear-crew). Bounds are in metres, world frame. An object is\n"
      "closed when every edge of every part is shared by exactly two triangles, and\n"
      "consistently oriented when those two triangles walk it in opposite directions.\n"
      "Roles and merged objects come from the nodes' extras, e.g.\n"
      "  \"extras\": {\"voxhap\": {\"role\": \"dynamic\", \"object\": \"actuator\"}}\n"
      "Without extras every mesh node is a static object of its own. A node with no\n"
      "mesh and no extras that holds parts (a sub-assembly) is listed as a group:\n"
      "`voxhap simulate --move GROUP` moves its objects as one rigid body.\n\n"
      "Examples:\n"
      "  voxhap scene info assets/ball-and-socket.glb\n"
      "  voxhap scene info landing-gear --json\n"
      "  voxhap scene info -v my-assembly.gltf      # one line per part, every object of a group";
  auto infoArgs = std::make_shared<InfoArgs>();
  CLI::App& infoCommand = tree.add(group, "info", std::move(info),
                                   [infoArgs](const CommandContext& c) { return runInfo(*infoArgs, c); });
  infoCommand.add_option("SCENE", infoArgs->scene, "a .gltf/.glb file or built-in scene name")->required();
  infoCommand.add_flag("--json", infoArgs->json, kJsonHelp);
  addUnsignedOption(infoCommand, "--seed", infoArgs->seed, kSeedHelp);

  CommandHelp generate;
  generate.summary =
      "Write a built-in scene as .glb (ball-and-socket, small-ball-and-socket, peg-in-hole, landing-gear…).";
  generate.usage = "voxhap scene generate NAME [-o FILE] [--seed N] [--json]";
  generate.description =
      "Generates a built-in scene procedurally and writes it atomically as binary glTF.\n"
      "landing-gear is a maintenance scene of landing-gear class (about 4.1 x 1.9 x 4.8 m,\n"
      "2.7 million static triangles, Z up) with a hydraulic actuator to pull out.\n"
      "The same NAME and seed always give the same bytes.\n\n"
      "Examples:\n"
      "  voxhap scene generate landing-gear -o gear.glb\n"
      "  voxhap scene generate landing-gear --seed 7 -o gear7.glb";
  auto generateArgs = std::make_shared<GenerateArgs>();
  CLI::App& generateCommand =
      tree.add(group, "generate", std::move(generate),
               [generateArgs](const CommandContext& c) { return runGenerate(*generateArgs, c); });
  generateCommand.add_option("NAME", generateArgs->name, "a built-in scene name")->required();
  generateCommand.add_option("-o,--output", generateArgs->output, "where to write (default NAME.glb)")
      ->type_name("FILE");
  addUnsignedOption(generateCommand, "--seed", generateArgs->seed, kSeedHelp);
  generateCommand.add_flag("--json", generateArgs->json, kJsonHelp);
}

}  // namespace voxhap::cli
