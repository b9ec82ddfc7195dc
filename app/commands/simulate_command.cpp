#include <algorithm>
#include <cmath>
#include <fstream>
#include <memory>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "app/cli/command.h"
#include "app/commands/commands.h"
#include "app/exact_checks.h"
#include "app/scene_source.h"
#include "app/sim_options.h"
#include "app/sim_run.h"
#include "haptics/core/error.h"
#include "haptics/sim/local_simulation.h"
#include "haptics/sim/scene_model.h"

namespace voxhap::cli {
namespace {

/// Voxel size of the static scene unless --voxel-size says otherwise, m.
constexpr double kDefaultVoxelSizeM = 1e-3;

/// What `voxhap simulate` was given.
struct SimulateArgs {
  std::string scene;
  std::vector<std::string> moving;   ///< --move, in order
  std::vector<std::string> scripts;  ///< --script, in order
  SimOptions sim;
  std::optional<std::string> trace;
  bool checkExact = false;
  std::optional<std::uint64_t> checkExactEvery;
  bool json = false;
};

/// Frames between two exact checks from --check-exact and --check-exact-every; 0: none.
std::uint64_t exactCheckEvery(const SimulateArgs& args) {
  if (args.checkExactEvery) return *args.checkExactEvery;
  if (args.checkExact) return 1;
  if (args.sim.probeSpacingM) throw UsageError("--probe-spacing is for --check-exact");
  return 0;
}

int runSimulate(const SimulateArgs& args, const CommandContext& c) {
  const std::vector<std::string>& moving = args.moving;
  if (moving.empty()) throw UsageError("name the object to move with --move NAME");
  const std::vector<std::string>& scripts = args.scripts;
  if (scripts.size() != 1 && scripts.size() != moving.size()) {
    throw UsageError("give one --script for all moving objects or one per --move (" +
                     std::to_string(moving.size()) + "), not " + std::to_string(scripts.size()));
  }
  const std::uint64_t exactEvery = exactCheckEvery(args);
  const SceneModelOptions options = sceneModelOptions(args.sim, c.console, kDefaultVoxelSizeM);
  std::vector<std::unique_ptr<ScriptedDevice>> devices;
  for (std::size_t i = 0; i < moving.size(); ++i) {
    devices.push_back(std::make_unique<ScriptedDevice>(loadMotionScript(scripts[scripts.size() == 1 ? 0 : i]),
                                                       options.sim.deviceLimits));
  }

  const double probeSpacingM = args.sim.probeSpacingM.value_or(options.staticVoxelSizeM / kProbesPerVoxel);
  const Scene scene = loadScene(args.scene, kDefaultSeed, c.console);
  BuiltScene built = buildScene(scene, moving, options, c.console.progress("preparing voxels"));
  const SimModel& model = built.model;
  std::unique_ptr<ExactChecks> exact;
  if (exactEvery > 0) {
    exact = std::make_unique<ExactChecks>(scene, model, options, probeSpacingM,
                                          c.console.progress("preparing probes"));
  }

  double scriptS = 0.0;
  for (const auto& d : devices) scriptS = std::max(scriptS, d->script().durationS());
  const double durationS = args.sim.durationS.value_or(scriptS);
  const auto frames = static_cast<std::uint64_t>(std::llround(durationS / model.dtS));

  std::ofstream trace;
  if (args.trace) {
    trace.open(*args.trace);
    if (!trace) throw Error(*args.trace + ": cannot write the trace");
    trace << "frame,t_s,object,qw,qx,qy,qz,tx,ty,tz,fx,fy,fz,taux,tauy,tauz,contacts,tested,max_travel_m,"
             "compute_us\n";
  }

  std::vector<HapticDevice*> deviceOf(model.objects.size(), nullptr);
  for (std::size_t i = 0; i < devices.size(); ++i) deviceOf[i] = devices[i].get();
  LocalSimulation sim(model, std::move(built.staticPager));
  sim.workspace.helper = frameHelperFor(args.sim);
  const SimState& state = sim.state;
  FrameStats stats;
  ExactCheckSummary exactSummary;
  const AfterFrameFn afterFrame = [&](std::uint64_t f, double us) {
    if (exact && (state.frame % exactEvery == 0 || f + 1 == frames)) exact->check(model, state, exactSummary);
    if (trace.is_open()) {
      for (std::size_t i = 0; i < model.objects.size(); ++i) {
        const ObjectFrame& o = sim.object(i);
        const Pose pose = objectPose(model, state, i);
        trace << state.frame << ',' << state.timeS << ',' << model.objects[i].name << ','
              << pose.orientation.w << ',' << pose.orientation.x << ',' << pose.orientation.y << ','
              << pose.orientation.z << ',' << pose.position.x << ',' << pose.position.y << ','
              << pose.position.z << ',' << o.contactForceWorld.x << ',' << o.contactForceWorld.y << ','
              << o.contactForceWorld.z << ',' << o.contactTorqueWorld.x << ',' << o.contactTorqueWorld.y
              << ',' << o.contactTorqueWorld.z << ',' << o.contacts << ',' << o.tested << ',' << o.maxTravelM
              << ',' << us << '\n';
      }
    }
  };
  if (exact) exact->check(model, state, exactSummary);  // the poses the scene file gives, frame 0
  runFrames(sim, deviceOf, frames, stats, c.console.progress("simulating"), afterFrame);
  if (trace.is_open() && !trace.flush()) throw Error(*args.trace + ": writing the trace failed");

  if (args.json) {
    nlohmann::ordered_json result = {{"scene", scene.sourceName},
                                     {"moving", moving},
                                     {"voxel_size_m", options.staticVoxelSizeM},
                                     {"point_spacing_m", options.pointSpacingM},
                                     {"coherence", options.sim.coherence.enabled}};
    const nlohmann::ordered_json frameSummary = frameStatsJson(stats);
    for (const auto& [key, value] : frameSummary.items()) result[key] = value;
    if (exact) {
      result["exact_penetration"] =
          exactCheckJson(exactSummary, exactEvery, probeSpacingM, options.staticVoxelSizeM);
    }
    c.out << result.dump(2) << "\n";
  } else {
    printFrameStats(c.out, stats, options.sim.coherence.enabled);
    if (exact) printExactChecks(c.out, exactSummary, exactEvery, probeSpacingM, options.staticVoxelSizeM);
  }
  return kExitOk;
}

}  // namespace

void addSimulateCommand(CommandTree& tree) {
  CommandHelp simulate;
  simulate.summary = "Run the haptic simulation headless at 1 kHz, driven by motion scripts.";
  simulate.usage = "voxhap simulate SCENE --move NAME [--move NAME2 …] --script FILE [options]";
  simulate.description =
      "Voxelizes the static objects of SCENE as one voxmap and gives every --move object a\n"
      "pointshell (and a voxmap when several move), all through the voxel cache; then runs\n"
      "simulated 1 kHz frames: each moving object follows its script's handle through a\n"
      "6-DOF virtual coupling and collides with the static scene and with the others.\n\n"
      "Motion script: one pose per line, `t qw qx qy qz tx ty tz` (seconds; the handle's\n"
      "rigid motion relative to where the scene file puts the object; slerp/lerp between\n"
      "lines); `#` starts a comment.\n\n"
      "Trace CSV (--trace): one row per moving object per frame, (q, t) mapping the object's\n"
      "vertices from the scene file's placement to now, f/tau the contact force (N) and\n"
      "torque about its centre of mass (N·m), world frame; compute_us is the frame's compute\n"
      "time.\n\n"
      "Time-critical sampling (paper §5): points in contact are tested every frame, the others\n"
      "as often as their distance from contact needs, within a capacity of point tests per\n"
      "frame; objects may then move at most MaxTravel per frame, which shrinks as the\n"
      "capacity runs short. The capacity is measured online from the real cost of a test and\n"
      "half the frame (--capacity N fixes it, for runs that repeat bit for bit). A frame with\n"
      "more points in contact than the capacity is a missed deadline: it tests them all and\n"
      "nothing moves; if the next is short too, frames run at full MaxTravel however long\n"
      "they take (time-criticality abandoned, paper §5) until the contacts fit again.\n\n"
      "Exact checks (--check-exact: at the start and after every frame; --check-exact-every\n"
      "N: at frames 0, N, 2N, … and the last): the ground truth the engine cannot give about\n"
      "itself, measured on the meshes with Embree outside the timed frames, for every moving\n"
      "object against the static scene and every pair of moving objects. Both surfaces of a\n"
      "pair are sampled by probes (--probe-spacing, default a quarter of --voxel-size) on\n"
      "every triangle's vertices, edges and interior; a probe inside the other body (by the\n"
      "side of its nearest surface point, or rays crossing a part an odd number of times) has\n"
      "its distance to that body's surface as depth. Voxmaps filter first (the static one,\n"
      "and each moving object's at the point spacing). The summary gives the deepest probe of\n"
      "the run, in mm and in static voxels, the frame it was found at (as the trace counts\n"
      "frames; 0: as the scene file places the objects), which surface went into which, and\n"
      "the least exact clearance from vertex and edge probes up to 4 voxels out. Cost grows\n"
      "with the surface near contact: mating surfaces (a seated ball, a peg in its hole) take\n"
      "far longer per check than a few contacts; check every Nth frame or with wider probes.\n\n"
      "Examples:\n"
      "  voxhap simulate ball-and-socket --move ball --script turn.txt --voxel-size 0.35mm \\\n"
      "      --point-offset=-0.175mm --json\n"
      "  voxhap simulate peg-in-hole --move peg --script insert.txt --voxel-size 0.05mm --trace out.csv\n"
      "  voxhap simulate peg-in-hole --move peg --script insert.txt --check-exact --json";
  auto args = std::make_shared<SimulateArgs>();
  CLI::App& command = tree.add(tree.root(), "simulate", std::move(simulate),
                               [args](const CommandContext& c) { return runSimulate(*args, c); });
  command.add_option("SCENE", args->scene, "a .gltf/.glb file or built-in scene name")->required();
  addRepeatedOption(command, "--move", "NAME",
                    "an object, or a group of the file (its objects as one), to move (repeatable)",
                    [&moving = args->moving](const std::string& name) { moving.push_back(name); });
  addRepeatedOption(command, "--script", "FILE",
                    "motion script: one for all moving objects or one per --move",
                    [&scripts = args->scripts](const std::string& file) { scripts.push_back(file); });
  SimOptions& sim = args->sim;
  addSimOptions(
      command, sim,
      {SimOption::VoxelSize, SimOption::PointSpacing, SimOption::PointOffset, SimOption::ForceLayerOf,
       SimOption::PointLayer, SimOption::NoAwareness, SimOption::PreContactDamping, SimOption::PaperContact,
       SimOption::Capacity, SimOption::VoxelMemory, SimOption::BruteForce, SimOption::NoDrifting,
       SimOption::FrameHelper, SimOption::DeviceProfile, SimOption::Duration});
  command.get_option("--voxel-size")
      ->description("voxel size of the static scene, e.g. 0.35mm (default 1mm)");
  command.get_option("--duration")->description("simulated time (default: the longest script)");
  command.add_option("--trace", args->trace, "write the per-frame trace")->type_name("FILE.csv");
  command.add_flag("--check-exact", args->checkExact,
                   "measure the exact penetration (Embree, both ways, faces too) at every frame");
  addParsedOption(command, "--check-exact-every", "N",
                  "the same at frames 0, N, 2N, … and the last (implies --check-exact)",
                  [&every = args->checkExactEvery](const std::string& text) {
                    every = parseUnsigned(text, "check-exact-every");
                    if (*every < 1) throw UsageError("--check-exact-every wants at least 1 frame");
                  });
  addSimOptions(command, sim, {SimOption::ProbeSpacing, SimOption::Cache});
  command.get_option("--probe-spacing")
      ->description("spacing of the exact check's surface probes (default: voxel size / 4)");
  command.add_flag("--json", args->json, "print one JSON summary on stdout");
}

}  // namespace voxhap::cli
