// `voxhap view`: the front end (view/view_run.h).

#include <CLI/CLI.hpp>

#include "app/cli/command.h"
#include "app/cli/endpoint_options.h"
#include "app/cli/option_values.h"
#include "app/commands/commands.h"
#include "app/sim_options.h"
#include "app/view/view_run.h"

namespace voxhap::cli {
namespace {

struct ViewArgs {
  std::string scene;
  std::vector<std::string> moving;
  std::optional<std::string> connect;
  std::optional<std::string> tokenFile;
  std::string device;
  SimOptions sim;
  bool passive = false;
  bool noCache = false;
  bool noRealtime = false;
  std::optional<std::string> screenshot;
  std::optional<std::uint64_t> frames;
  std::optional<std::string> size;
  std::optional<double> maxFrameRateHz;
  bool json = false;
};

/// "WxH" in pixels, each 16 to 8192.
glm::ivec2 parseSize(const std::string& text) {
  const std::size_t x = text.find('x');
  if (x == std::string::npos)
    throw UsageError("--size wants WIDTHxHEIGHT, e.g. 1280x720, not '" + text + "'");
  const std::uint64_t w = parseUnsigned(text.substr(0, x), "size");
  const std::uint64_t h = parseUnsigned(text.substr(x + 1), "size");
  if (w < 16 || h < 16 || w > 8192 || h > 8192)
    throw UsageError("--size: " + text + " is outside 16x16 to 8192x8192 pixels");
  return {static_cast<int>(w), static_cast<int>(h)};
}

int runViewCommand(const ViewArgs& args, const CommandContext& c) {
  ViewOptions options;
  options.scene = args.scene;
  options.moving = args.moving;
  if (args.connect) {
    options.connect = parseHostPort(*args.connect, "--connect");
    if (!args.moving.empty()) throw UsageError("--move is the controller's to choose with --connect");
  } else {
    if (args.scene.empty())
      throw UsageError("view wants a SCENE, or --connect HOST:PORT to a running controller");
    if (args.tokenFile) throw UsageError("--token goes with --connect");
  }
  if (args.tokenFile) options.token = readTokenFile(*args.tokenFile, "--token");
  if (args.passive && !args.device.empty()) throw UsageError("--passive cannot grab with --device");
  if (args.frames && !args.screenshot) throw UsageError("--frames goes with --screenshot");
  options.device = args.device;
  options.model = sceneModelOptions(args.sim, c.console, 2.5e-3, 1e-3);
  options.realtime = !args.noRealtime;
  options.passive = args.passive;
  options.staticCache = !args.noCache;
  options.screenshot = args.screenshot;
  if (args.frames) {
    if (*args.frames < 1 || *args.frames > 1'000'000) throw UsageError("--frames wants 1 to 1000000");
    options.frames = static_cast<int>(*args.frames);
  }
  if (args.size) options.sizePx = parseSize(*args.size);
  if (args.maxFrameRateHz) {
    if (!(*args.maxFrameRateHz >= 1.0 && *args.maxFrameRateHz <= 1000.0))
      throw UsageError("--max-frame-rate wants 1 to 1000 frames a second");
    options.maxFrameRateHz = *args.maxFrameRateHz;
  }
  options.json = args.json;
  runView(options, c.console, c.out);
  return kExitOk;
}

}  // namespace

void addViewCommand(CommandTree& tree) {
  CommandHelp view;
  view.summary = "The front end: a window on the scene, its parts grabbed and dragged with the mouse.";
  view.usage =
      "voxhap view SCENE [--move NAME] [--device DEVICE] [--voxel-size LENGTH] [--point-spacing LENGTH]\n"
      "       voxhap view --connect HOST:PORT [SCENE] [--token FILE]\n"
      "       [--passive] [--no-static-cache] [--max-frame-rate HZ] [--screenshot FILE.png [--frames N]]\n"
      "       [--size WxH] [--json]";
  view.description =
      "Opens a window on a scene simulated by a haptic controller (paper §6): with a SCENE it\n"
      "starts one in this process and loads the scene into it (the window and its title show the\n"
      "progress; --move names what moves, by default the scene's dynamic objects); with --connect it\n"
      "talks to a running `voxhap controller`, loading this machine's copy of its scene (SCENE,\n"
      "or the path the controller names).\n\n"
      "The static parts are drawn once into colour and depth and reused while the eye is still\n"
      "(paper §7; --no-static-cache draws everything every frame; C toggles it); the moving parts are\n"
      "drawn over them, coloured warmer the closer they come to the static scene, with the\n"
      "static voxels near them highlighted like a shadow (paper §3.1).\n\n"
      "Mouse: left-click a moving part to grab it with the mouse as a 2-DOF device and drag it\n"
      "in the view plane (Shift: in depth; Ctrl: turn it about the grabbed point); the coupling\n"
      "pulls it after the mouse, so you see MaxTravel's viscosity as lag and contacts hold it\n"
      "back. Right-drag orbits, middle-drag pans, the wheel zooms, F frames the scene, Esc quits.\n"
      "The HUD shows rates, contacts, force, MaxTravel, clearance and voxel size; it changes the\n"
      "force layer, point offset and coupling stiffness, grabs and releases parts, and turns the\n"
      "force arrow on the parts you hold off and on.\n\n"
      "--passive sees without grabbing. --screenshot draws in a hidden window (a display is\n"
      "still needed: run under `xvfb-run -a`), waits for the scene, draws N frames (default 60)\n"
      "and writes the last to FILE.png. The summary gives frame rates with and without the\n"
      "cache, cache redraws, the time to the first frame, the haptic period and, per moving\n"
      "object, who held it last, how far (m) its centre ended from its place in the scene and\n"
      "by how many degrees it turned.\n\n"
      "Examples:\n"
      "  voxhap view landing-gear\n"
      "  voxhap view landing-gear --device script:assets/scripts/actuator-extract.txt\n"
      "  voxhap view --connect 127.0.0.1:7400 --passive\n"
      "  xvfb-run -a voxhap view ball-and-socket --screenshot ball.png --frames 30 --size 640x480";
  auto args = std::make_shared<ViewArgs>();
  CLI::App& command = tree.add(tree.root(), "view", std::move(view),
                               [args](const CommandContext& c) { return runViewCommand(*args, c); });
  command.add_option("SCENE", args->scene, "a .gltf/.glb file or built-in scene name");
  addRepeatedOption(command, "--move", "NAME", "an object or group that moves (repeatable)",
                    [&moving = args->moving](const std::string& name) { moving.push_back(name); });
  command.add_option("--connect", args->connect, "a running controller instead of one in this process")
      ->type_name("HOST:PORT");
  command.add_option("--token", args->tokenFile, "the controller's token (with --connect)")
      ->type_name("FILE");
  command.add_option("--device", args->device, "grab the first moving part with this device once loaded")
      ->type_name("script:FILE|hand:FILE|spacemouse");
  SimOptions& sim = args->sim;
  addSimOptions(
      command, sim,
      {SimOption::VoxelSize, SimOption::PointSpacing, SimOption::PointOffset, SimOption::ForceLayerOf,
       SimOption::PaperContact, SimOption::Capacity, SimOption::DeviceProfile});
  command.add_flag("--passive", args->passive, "see, never grab or change anything");
  command.add_flag("--no-static-cache", args->noCache,
                   "draw the static parts every frame (no FlyThru cache)");
  command.add_flag("--no-realtime", args->noRealtime, "the in-process controller does not try SCHED_FIFO");
  command.add_option("--screenshot", args->screenshot, "draw headless and write the last frame to this PNG")
      ->type_name("FILE.png");
  command.add_option("--frames", args->frames, "frames to draw before the screenshot (default 60)")
      ->type_name("N");
  command.add_option("--size", args->size, "window size in pixels (default 1280x720)")->type_name("WxH");
  command
      .add_option("--max-frame-rate", args->maxFrameRateHz,
                  "draw at most this many frames a second (default: as vsync allows), leaving the "
                  "processor to the haptic thread")
      ->type_name("HZ");
  addSimOptions(command, sim, {SimOption::Cache});
  command.add_flag("--json", args->json, "print the summary as one JSON document on stdout");
}

}  // namespace voxhap::cli
