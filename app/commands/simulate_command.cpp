#include <algorithm>
#include <cmath>
#include <fstream>
#include <memory>

#include <nlohmann/json.hpp>

#include "app/cache_options.h"
#include "app/cli/command.h"
#include "app/commands/commands.h"
#include "app/exact_checks.h"
#include "app/scene_source.h"
#include "app/sim_run.h"
#include "haptics/core/error.h"
#include "haptics/sim/local_simulation.h"
#include "haptics/sim/scene_model.h"

namespace voxhap::cli {
namespace {

/// Voxel size of the static scene unless --voxel-size says otherwise, m.
constexpr double kDefaultVoxelSizeM = 1e-3;

/// Frames between two exact checks from --check-exact and --check-exact-every; 0: none.
std::uint64_t exactCheckEveryFromArgs(const ParsedArgs& args) {
  if (const auto every = args.value("check-exact-every")) {
    const std::uint64_t n = parseUnsigned(*every, "check-exact-every");
    if (n < 1) throw UsageError("--check-exact-every wants at least 1 frame");
    return n;
  }
  if (args.has("check-exact")) return 1;
  if (args.value("probe-spacing")) throw UsageError("--probe-spacing is for --check-exact");
  return 0;
}

int runSimulate(const CommandContext& c) {
  if (c.args.positionals.size() != 1) throw UsageError("expected one SCENE");
  const std::vector<std::string> moving = c.args.values("move");
  if (moving.empty()) throw UsageError("name the object to move with --move NAME");
  const std::vector<std::string> scripts = c.args.values("script");
  if (scripts.size() != 1 && scripts.size() != moving.size()) {
    throw UsageError("give one --script for all moving objects or one per --move (" +
                     std::to_string(moving.size()) + "), not " + std::to_string(scripts.size()));
  }
  const SceneModelOptions options = sceneModelOptionsFromArgs(c.args, c.console, kDefaultVoxelSizeM);
  std::vector<std::unique_ptr<ScriptedDevice>> devices;
  for (std::size_t i = 0; i < moving.size(); ++i) {
    devices.push_back(std::make_unique<ScriptedDevice>(loadMotionScript(scripts[scripts.size() == 1 ? 0 : i]),
                                                       options.sim.deviceLimits));
  }

  const std::uint64_t exactEvery = exactCheckEveryFromArgs(c.args);
  const double probeSpacingM = c.args.value("probe-spacing")
                                   ? parseLengthM(*c.args.value("probe-spacing"), "probe-spacing")
                                   : options.staticVoxelSizeM / kProbesPerVoxel;
  const Scene scene = loadScene(c.args.positionals[0], kDefaultSeed, c.console);
  BuiltScene built = buildScene(scene, moving, options, c.console.progress("preparing voxels"));
  const SimModel& model = built.model;
  std::unique_ptr<ExactChecks> exact;
  if (exactEvery > 0) {
    exact = std::make_unique<ExactChecks>(scene, model, options, probeSpacingM,
                                          c.console.progress("preparing probes"));
  }

  double scriptS = 0.0;
  for (const auto& d : devices) scriptS = std::max(scriptS, d->script().durationS());
  const double durationS = durationFromArgs(c.args, scriptS);
  const auto frames = static_cast<std::uint64_t>(std::llround(durationS / model.dtS));

  std::ofstream trace;
  if (const auto file = c.args.value("trace")) {
    trace.open(*file);
    if (!trace) throw Error(*file + ": cannot write the trace");
    trace << "frame,t_s,object,qw,qx,qy,qz,tx,ty,tz,fx,fy,fz,taux,tauy,tauz,contacts,tested,max_travel_m,"
             "compute_us\n";
  }

  std::vector<HapticDevice*> deviceOf(model.objects.size(), nullptr);
  for (std::size_t i = 0; i < devices.size(); ++i) deviceOf[i] = devices[i].get();
  LocalSimulation sim(model, std::move(built.staticPager));
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
  if (trace.is_open() && !trace.flush()) throw Error(*c.args.value("trace") + ": writing the trace failed");

  if (c.args.has("json")) {
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

Command simulateCommand() {
  Command simulate;
  simulate.name = "simulate";
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
  simulate.options = {
      {"move", 0, "NAME", "an object, or a group of the file (its objects as one), to move (repeatable)"},
      {"script", 0, "FILE", "motion script: one for all moving objects or one per --move"},
      {"voxel-size", 0, "LENGTH", "voxel size of the static scene, e.g. 0.35mm (default 1mm)"},
      {"point-spacing", 0, "LENGTH", "point spacing of the moving objects (default: the voxel size)"},
      {"point-offset", 0, "LENGTH", "move every point along its normal, negative inward (e.g. -0.175mm)"},
      {"point-layer", 0, "K", "take points from the free-space layer K voxels out (0 … 8; collision offset)"},
      {"no-awareness", 0, "", "turn geometrical awareness off (every point samples the surface field)"},
      {"pre-contact-damping", 0, "", "damp points approaching in the layer just outside the force layer"},
      kCapacityOption,
      kVoxelMemoryOption,
      kBruteForceOption,
      kNoDriftingOption,
      kDeviceProfileOption,
      {"duration", 0, "SECONDS", "simulated time (default: the longest script)"},
      {"trace", 0, "FILE.csv", "write the per-frame trace"},
      {"check-exact", 0, "", "measure the exact penetration (Embree, both ways, faces too) at every frame"},
      {"check-exact-every", 0, "N", "the same at frames 0, N, 2N, … and the last (implies --check-exact)"},
      {"probe-spacing", 0, "LENGTH", "spacing of the exact check's surface probes (default: voxel size / 4)"},
      kCacheDirOption,
      kNoCacheOption,
      {"json", 0, "", "print one JSON summary on stdout"}};
  simulate.run = runSimulate;
  return simulate;
}

}  // namespace voxhap::cli
