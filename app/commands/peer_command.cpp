// `voxhap peer`: a haptic controller that is one peer of a collaborative session, and
// (unless headless) its window (controller/controller_run.h, view/view_run.h).

#include <sstream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "app/cli/command.h"
#include "app/cli/endpoint_options.h"
#include "app/cli/option_values.h"
#include "app/commands/commands.h"
#include "app/commands/controller_options.h"
#include "app/controller/controller_run.h"
#include "app/controller/inprocess_controller.h"
#include "app/extraction.h"
#include "app/sim_options.h"
#include "app/view/view_run.h"
#include "haptics/core/error.h"

namespace voxhap::cli {
namespace {

/// What `voxhap peer` was given.
struct PeerArgs {
  std::string scene;
  std::vector<std::string> moving;
  ControllerRunArgs run;
  std::optional<std::string> listen;
  std::optional<std::string> frontend;
  std::optional<std::string> advertise;
  std::optional<std::string> join;
  std::optional<std::string> keyFile;
  std::string take;
  std::string share;
  bool noPassivity = false;
  std::string device;
  std::string name;
  double streamHz = 200.0;
  std::optional<double> timeoutS;
  bool passive = false;
  bool headless = false;
};

int runPeerCommand(const PeerArgs& args, const CommandContext& c) {
  ControllerOptions options;
  options.scene = args.scene;
  options.moving = args.moving;
  const std::string& d = args.device;
  checkDeviceOption(d);
  if (!args.take.empty() && !args.share.empty())
    throw UsageError("--take and --share: a peer either owns an object or shares one; give one of them");
  if (!d.empty() && args.take.empty() && args.share.empty())
    throw UsageError("--device holds the --take or --share OBJECT: name it");
  if (args.passive && (!args.take.empty() || !args.share.empty() || !d.empty()))
    throw UsageError("--passive cannot --take, --share or hold");
  if (args.noPassivity && args.share.empty())
    throw UsageError("--no-passivity is for a --share OBJECT's coupling");
  if (!(args.streamHz >= 100.0 && args.streamHz <= 1000.0))
    throw UsageError("--rate wants 100 to 1000 states per second");
  applyControllerRunArgs(args.run, c.console, options);
  options.device = args.device;
  options.listenPort = 0;  // several peers on one machine: any free port, printed
  if (args.frontend) {
    const HostPort frontend = parseHostPort(*args.frontend, "--frontend");
    options.listenHost = frontend.host;
    options.listenPort = frontend.port;
  }
  PeerRunOptions peer;
  if (args.listen) {
    const HostPort listen = parseHostPort(*args.listen, "--listen");
    peer.listenHost = listen.host;
    peer.listenPort = listen.port;
  }
  if (args.advertise) {
    const HostPort advertise = parseHostPort(*args.advertise, "--advertise");
    if (advertise.port == 0) throw UsageError("--advertise wants the port the others send to");
    peer.advertise = advertise.host + ":" + std::to_string(advertise.port);
  }
  if (args.join) {
    const HostPort join = parseHostPort(*args.join, "--join");
    if (join.port == 0) throw UsageError("--join wants a member's port");
    peer.joinHost = join.host;
    peer.joinPort = join.port;
    if (!args.keyFile) throw UsageError("--join needs --key FILE: the session key its first member printed");
  }
  if (args.keyFile) peer.keyFile = *args.keyFile;
  peer.take = args.take;
  peer.share = args.share;
  peer.passivity = !args.noPassivity;
  peer.name = args.name.empty() ? (std::getenv("USER") ? std::getenv("USER") : "") : args.name;
  peer.streamHz = args.streamHz;
  if (args.timeoutS) peer.timeoutS = *args.timeoutS;
  options.peer = peer;
  if (args.headless) {
    runController(options, c.console, c.out);
    return kExitOk;
  }
  // the window talks to this peer's controller over loopback, as to any controller
  InProcessController controller(options, c.console);
  ViewOptions view;
  view.scene = args.scene;
  view.connect = HostPort{"127.0.0.1", controller.port()};
  view.passive = args.passive;
  view.realtime = options.realtime;
  view.endsWithController = true;  // on --duration or a signal
  view.json = args.run.json;
  std::ostringstream viewSummary;
  runView(view, c.console, args.run.json ? viewSummary : c.out);
  const std::string summary = controller.stopAndWait();
  if (args.run.json) {
    nlohmann::ordered_json all = nlohmann::ordered_json::parse(summary);
    all["view"] = nlohmann::ordered_json::parse(viewSummary.str());
    c.out << all.dump(2) << "\n";
  }
  return kExitOk;
}

}  // namespace

void addPeerCommand(CommandTree& tree) {
  CommandHelp help;
  help.summary =
      "A peer of a collaborative session: a haptic controller joined to others over UDP, and its window.";
  help.usage =
      "voxhap peer SCENE [--listen HOST:PORT] [--join HOST:PORT --key FILE]\n"
      "       [--take OBJECT | --share OBJECT [--no-passivity]] [--device …]\n"
      "       [--move NAME]… [--advertise HOST:PORT] [--frontend HOST:PORT] [--name NAME] [--rate HZ] "
      "[--timeout SECONDS] "
      "[--passive] [--headless]\n"
      "       [--duration SECONDS] [--no-realtime] [--json]";
  help.description =
      "Engineers at several sites each run a peer: a full haptic controller (see `voxhap\n"
      "controller`) that simulates the whole scene at 1 kHz, and a window on it (`voxhap view`;\n"
      "none with --headless). Peers talk to each other over UDP, with no server (DESIGN §8,\n"
      "docs/protocol.md). Each moving object has one owner, whose peer integrates it; every\n"
      "other peer moves it as its owner's stream says, and feels its own parts collide with it\n"
      "at once. --take asks for an object (it is handed over once nobody holds it where it is);\n"
      "--device then holds it.\n\n"
      "--share OBJECT: several users hold the same part (type-2). Each sharing peer integrates\n"
      "its own instance of it, joined to the others' instances by a spring whose stiffness\n"
      "falls with each one's measured one-way delay, to nothing at 1 s (paper §6.1); a\n"
      "passivity controller takes out the energy the delay would add (--no-passivity: not).\n"
      "A peer that begins sharing starts where the others' instance is; the peers that do not\n"
      "share it see the lowest-numbered sharer's instance. Instances held apart (a wall between\n"
      "them) are flagged divergent on every peer. --device then holds this peer's instance.\n\n"
      "The first peer makes the session: without --key it makes a key and prints it. The others\n"
      "join through any member with --join HOST:PORT and that key in a file (--key FILE, 64\n"
      "hexadecimal digits). Every peer must load the same SCENE with the same --move set (checked\n"
      "at join: another scene is refused; other sizes or force layer are accepted, with a\n"
      "warning to both). Every datagram is encrypted and authenticated with the session key;\n"
      "peers listen on loopback unless told otherwise. A peer not heard from for --timeout\n"
      "seconds (default 2) is gone; its objects stop where they are, nobody's.\n\n"
      "With --headless, front ends (`voxhap view --connect`) reach its controller over TCP at\n"
      "--frontend (default: a free loopback port, printed as 'listening on HOST:PORT').\n"
      "Without --move the scene's dynamic objects move. It runs until SIGINT or SIGTERM (or the\n"
      "window closes, or --duration), leaves the session, and prints a summary: headless, the\n"
      "controller's, with the session's members, round trips, bytes and dropped datagrams; with\n"
      "a window, the window's. --json prints one JSON document: the controller's summary, and\n"
      "the window's under \"view\".\n\n"
      "Examples:\n"
      "  voxhap peer landing-gear --listen 127.0.0.1:7500 --take actuator --headless\n"
      "  voxhap peer landing-gear --listen 127.0.0.1:7501 --join 127.0.0.1:7500 --key session.key\n"
      "  voxhap peer landing-gear --join 127.0.0.1:7500 --key session.key --share actuator --device "
      "spacemouse\n"
      "  voxhap peer ball-and-socket --move ball --take ball --device script:press.txt --headless --json";
  auto args = std::make_shared<PeerArgs>();
  CLI::App& command = tree.add(tree.root(), "peer", std::move(help),
                               [args](const CommandContext& c) { return runPeerCommand(*args, c); });
  command
      .add_option("SCENE", args->scene, "a .gltf/.glb file or built-in scene name, the same on every peer")
      ->required();
  addRepeatedOption(command, "--move", "NAME",
                    "an object or group that moves (repeatable; default: the dynamic ones)",
                    [&moving = args->moving](const std::string& name) { moving.push_back(name); });
  command
      .add_option("--listen", args->listen,
                  "where the other peers reach this one over UDP (default 127.0.0.1, any port)")
      ->type_name("HOST:PORT");
  command
      .add_option("--frontend", args->frontend,
                  "where front ends connect over TCP, headless (default 127.0.0.1, any port)")
      ->type_name("HOST:PORT");
  command
      .add_option("--advertise", args->advertise,
                  "where the others send to, when not --listen (a relay in front of this peer)")
      ->type_name("HOST:PORT");
  command.add_option("--join", args->join, "a member of the session to join through")->type_name("HOST:PORT");
  command
      .add_option("--key", args->keyFile,
                  "the session key (64 hex digits); the first peer prints one without")
      ->type_name("FILE");
  command.add_option("--take", args->take, "an object to ask for at once")->type_name("OBJECT");
  command
      .add_option("--share", args->share, "an object to share with the other peers that share it (type-2)")
      ->type_name("OBJECT");
  command.add_flag("--no-passivity", args->noPassivity,
                   "the shared object's coupling without the passivity controller");
  command
      .add_option("--device", args->device,
                  "hold the --take object once it is this peer's, or the --share object")
      ->type_name("script:FILE|hand:FILE|spacemouse[:PATH]");
  command.add_option("--name", args->name, "the user's name the others see (default $USER)");
  command
      .add_option("--rate", args->streamHz, "states sent to each peer per second, 100 to 1000 (default 200)")
      ->type_name("HZ");
  addParsedOption(command, "--timeout", "SECONDS", "a peer not heard from this long is gone (default 2)",
                  [&t = args->timeoutS](const std::string& text) { t = parseSeconds(text, "timeout"); });
  command.add_flag("--passive", args->passive, "see the session, never take or hold anything");
  command.add_flag("--headless", args->headless, "no window: the controller and the peer only");
  addControllerRunOptions(command, args->run);
}

}  // namespace voxhap::cli
