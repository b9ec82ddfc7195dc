// `voxhap controller`: the haptic controller process (controller/controller_run.h).

#include <CLI/CLI.hpp>

#include "app/cli/command.h"
#include "app/cli/endpoint_options.h"
#include "app/cli/option_values.h"
#include "app/commands/commands.h"
#include "app/commands/controller_options.h"
#include "app/controller/controller_run.h"
#include "app/extraction.h"
#include "app/sim_options.h"
#include "haptics/core/error.h"

namespace voxhap::cli {
namespace {

/// What `voxhap controller` was given.
struct ControllerArgs {
  std::string scene;
  std::vector<std::string> moving;
  std::optional<std::string> listen;
  std::optional<std::string> tokenFile;
  std::string device;
  ControllerRunArgs run;
};

int runControllerCommand(const ControllerArgs& args, const CommandContext& c) {
  ControllerOptions options;
  options.scene = args.scene;
  options.moving = args.moving;
  if (!options.scene.empty() && options.moving.empty())
    throw UsageError("--move NAME is required with a SCENE (the object the controller moves)");
  if (options.scene.empty() && !options.moving.empty()) throw UsageError("--move wants a SCENE");
  checkDeviceOption(args.device);
  if (!args.device.empty() && options.scene.empty()) throw UsageError("--device wants a SCENE");
  applyControllerRunArgs(args.run, c.console, options);
  if (args.listen) {
    const HostPort listen = parseHostPort(*args.listen, "--listen");
    options.listenHost = listen.host;
    options.listenPort = listen.port;
  }
  if (args.tokenFile) options.token = readTokenFile(*args.tokenFile, "--token");
  options.device = args.device;
  runController(options, c.console, c.out);
  return kExitOk;
}

}  // namespace

void addControllerCommand(CommandTree& tree) {
  CommandHelp controller;
  controller.summary =
      "The haptic controller: the 1 kHz simulation and its devices, serving front ends over TCP.";
  controller.usage =
      "voxhap controller [SCENE --move NAME] [--listen HOST:PORT] [--token FILE] [--device "
      "script:FILE|hand:FILE|spacemouse]\n"
      "       [--voxel-size LENGTH] [--point-spacing LENGTH] [--point-offset LENGTH] [--capacity N] "
      "[--duration SECONDS]\n"
      "       [--no-realtime] [--json]";
  controller.description =
      "Runs the paper's Haptic Controller (§6): a haptic thread keeps the 1 kHz loop on absolute\n"
      "1 ms deadlines (devices, dynamics, voxel sampling, forces), under SCHED_FIFO with its\n"
      "memory locked when the system allows it (it says so when not); after a stall it re-syncs\n"
      "to the clock instead of running the missed frames back to back. The calling thread\n"
      "serves front ends over TCP (docs/protocol.md): list objects, grab and release them with\n"
      "a device, move a handle, set the force layer, coupling and sizes, stream poses, read\n"
      "statistics, load another scene, shut down. Without a SCENE it waits for a client to\n"
      "load one.\n\n"
      "It listens on 127.0.0.1:7400 by default (port 0: any free port); the line 'listening on\n"
      "HOST:PORT' on stderr says where. Any address beyond loopback needs --token FILE, whose\n"
      "contents (without the final line end) every client must present in its hello.\n\n"
      "--device grabs the first --move object at start: script:FILE with a motion script, as\n"
      "`voxhap simulate` plays it; hand:FILE with the script as the target of a simulated hand\n"
      "holding a force-feedback handle, which the rendered force pushes back (the handle stops\n"
      "short of a wall the script goes through); spacemouse with the first SpaceMouse-class\n"
      "6-DOF controller found (spacemouse:/dev/hidrawN for that one): deflection drives the\n"
      "handle's velocity, button 1 releases the object and grabs it again. Clients can grab\n"
      "objects too. It runs until SIGINT or SIGTERM, a client's shutdown request, or\n"
      "--duration seconds of wall time, then prints the haptic period's p50/p99/p99.9/max and\n"
      "overruns (text, or one JSON document with\n"
      "--json) and exits 0.\n\n"
      "Examples:\n"
      "  voxhap controller landing-gear --move actuator --device script:assets/scripts/actuator-extract.txt\n"
      "  voxhap controller --listen 127.0.0.1:0      # waits for a client's load_scene\n"
      "  voxhap controller ball-and-socket --move ball --voxel-size 0.5mm --listen 127.0.0.1:0\n"
      "  voxhap controller ball-and-socket --move ball --listen 192.168.1.20:7400 --token ~/.voxhap-token";
  auto args = std::make_shared<ControllerArgs>();
  CLI::App& command = tree.add(tree.root(), "controller", std::move(controller),
                               [args](const CommandContext& c) { return runControllerCommand(*args, c); });
  command.add_option("SCENE", args->scene,
                     "a .gltf/.glb file or built-in scene name (default: none until a client loads one)");
  addRepeatedOption(command, "--move", "NAME", "an object or group the controller moves (repeatable)",
                    [&moving = args->moving](const std::string& name) { moving.push_back(name); });
  command.add_option("--listen", args->listen, "where front ends connect (default 127.0.0.1:7400)")
      ->type_name("HOST:PORT");
  command.add_option("--token", args->tokenFile, "a token clients must present; required beyond loopback")
      ->type_name("FILE");
  command.add_option("--device", args->device, "grab the first moved object at start with this device")
      ->type_name("script:FILE|hand:FILE|spacemouse[:PATH]");
  addControllerRunOptions(command, args->run);
}

}  // namespace voxhap::cli
