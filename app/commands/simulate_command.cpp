#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <memory>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "app/cache_options.h"
#include "app/cli/command.h"
#include "app/commands/commands.h"
#include "app/scene_source.h"
#include "haptics/core/error.h"
#include "haptics/sim/scene_model.h"
#include "haptics/sim/simulation.h"
#include "haptics/voxel/voxel_cache.h"

namespace voxhap::cli {
namespace {

double percentile(std::vector<double> values, double p) {
  if (values.empty()) return 0.0;
  const auto k = static_cast<std::size_t>(std::ceil(p * static_cast<double>(values.size()))) - 1;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  return values[k];
}

int runSimulate(const CommandContext& c) {
  if (c.args.positionals.size() != 1) throw UsageError("expected one SCENE");
  const std::vector<std::string> moving = c.args.values("move");
  if (moving.empty()) throw UsageError("name the object to move with --move NAME");
  const std::vector<std::string> scripts = c.args.values("script");
  if (scripts.size() != 1 && scripts.size() != moving.size()) {
    throw UsageError("give one --script for all moving objects or one per --move (" + std::to_string(moving.size()) +
                     "), not " + std::to_string(scripts.size()));
  }
  std::vector<std::unique_ptr<ScriptedDevice>> devices;
  for (std::size_t i = 0; i < moving.size(); ++i) {
    devices.push_back(std::make_unique<ScriptedDevice>(loadMotionScript(scripts[scripts.size() == 1 ? 0 : i])));
  }

  SceneModelOptions options;
  options.staticVoxelSizeM = parseLengthM(c.args.value("voxel-size").value_or("1mm"), "voxel-size");
  options.pointSpacingM = c.args.value("point-spacing")
                              ? parseLengthM(*c.args.value("point-spacing"), "point-spacing")
                              : options.staticVoxelSizeM;
  if (const auto offset = c.args.value("point-offset")) {
    options.pointDisplacementM = parseLengthM(*offset, "point-offset", LengthSign::Any);
  }
  if (const auto layer = c.args.value("point-layer")) {
    options.pointFreeLayer = static_cast<int>(std::min<std::uint64_t>(parseUnsigned(*layer, "point-layer"), 1000));
  }
  options.sim.geometricalAwareness = !c.args.has("no-awareness");
  options.sim.preContactDamping = c.args.has("pre-contact-damping");
  options.sim.coherence.enabled = !c.args.has("brute-force");
  options.sim.coherence.pointDrifting = !c.args.has("no-drifting");
  if (const auto capacity = c.args.value("capacity")) {
    options.sim.coherence.capacityTests = static_cast<double>(parseUnsigned(*capacity, "capacity"));
    if (options.sim.coherence.capacityTests < 1) throw UsageError("--capacity wants at least one point test");
  }
  const CacheOptions cache = voxelCacheOptions(c.args);
  useVoxelCache(options, cache, c.console);

  const Scene scene = loadScene(c.args.positionals[0], kDefaultSeed, c.console);
  const SimModel model = buildSceneModel(scene, moving, options, c.console.progress("preparing voxels"));

  double durationS = 0.0;
  for (const auto& d : devices) durationS = std::max(durationS, d->script().durationS());
  if (const auto duration = c.args.value("duration")) {
    durationS = std::stod(*duration);
    if (!(durationS >= 0.0) || !std::isfinite(durationS)) throw UsageError("--duration wants seconds ≥ 0");
  }
  const auto frames = static_cast<std::uint64_t>(std::llround(durationS / model.dtS));

  std::ofstream trace;
  if (const auto file = c.args.value("trace")) {
    trace.open(*file);
    if (!trace) throw Error(*file + ": cannot write the trace");
    trace << "frame,t_s,object,qw,qx,qy,qz,tx,ty,tz,fx,fy,fz,taux,tauy,tauz,contacts,tested,max_travel_m,compute_us\n";
  }

  std::vector<HapticDevice*> deviceOf(model.objects.size(), nullptr);
  for (std::size_t i = 0; i < devices.size(); ++i) deviceOf[i] = devices[i].get();
  std::vector<HandleInput> handles(model.objects.size());
  std::vector<double> computeUs;
  computeUs.reserve(frames);
  SimState state = makeSimState(model);
  std::uint32_t maxContacts = 0;
  double maxForceN = 0.0;
  double sumContacts = 0.0;
  double sumTested = 0.0;
  double sumChunkTests = 0.0;
  double sumDrifted = 0.0;
  double sumTravelScale = 0.0;
  std::uint64_t framesOverBudget = 0;
  const ProgressFn progress = c.console.progress("simulating");
  for (std::uint64_t f = 0; f < frames; ++f) {
    const auto start = std::chrono::steady_clock::now();
    stepWithDevices(model, state, deviceOf, handles);
    const double us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
    computeUs.push_back(us);
    framesOverBudget += us > model.dtS * 1e6 ? 1 : 0;
    sumTested += state.coherent.tested;
    sumChunkTests += state.coherent.chunkTests;
    sumDrifted += state.coherent.drifted;
    sumTravelScale += state.coherent.travelScale;
    for (std::size_t i = 0; i < model.objects.size(); ++i) {
      const ObjectFrame& o = state.last[i];
      maxContacts = std::max(maxContacts, o.contacts);
      sumContacts += o.contacts;
      maxForceN = std::max(maxForceN, glm::length(o.contactForceWorld));
      if (!trace.is_open()) continue;
      const Pose pose = objectPose(model, state, i);
      trace << state.frame << ',' << state.timeS << ',' << model.objects[i].name << ',' << pose.orientation.w << ','
            << pose.orientation.x << ',' << pose.orientation.y << ',' << pose.orientation.z << ','
            << pose.position.x << ',' << pose.position.y << ',' << pose.position.z << ','
            << o.contactForceWorld.x << ',' << o.contactForceWorld.y << ',' << o.contactForceWorld.z << ','
            << o.contactTorqueWorld.x << ',' << o.contactTorqueWorld.y << ',' << o.contactTorqueWorld.z << ','
            << o.contacts << ',' << o.tested << ',' << o.maxTravelM << ',' << us << '\n';
    }
    if (progress && f % 100 == 0) progress(static_cast<double>(f) / static_cast<double>(frames));
  }
  if (progress) progress(1.0);
  if (trace.is_open() && !trace.flush()) throw Error(*c.args.value("trace") + ": writing the trace failed");

  const double p50 = percentile(computeUs, 0.5);
  const double p99 = percentile(computeUs, 0.99);
  const double worst = computeUs.empty() ? 0.0 : *std::max_element(computeUs.begin(), computeUs.end());
  const double perFrame = frames > 0 ? 1.0 / static_cast<double>(frames) : 0.0;
  if (c.args.has("json")) {
    nlohmann::ordered_json result = {{"scene", scene.sourceName},
                                     {"moving", moving},
                                     {"voxel_size_m", options.staticVoxelSizeM},
                                     {"point_spacing_m", options.pointSpacingM},
                                     {"coherence", options.sim.coherence.enabled},
                                     {"frames", frames},
                                     {"max_contacts", maxContacts},
                                     {"mean_contacts", sumContacts * perFrame},
                                     {"max_force_n", maxForceN},
                                     {"mean_tested", sumTested * perFrame},
                                     {"mean_drifted", sumDrifted * perFrame},
                                     {"mean_chunk_tests", sumChunkTests * perFrame},
                                     {"mean_travel_scale", sumTravelScale * perFrame},
                                     {"missed_deadlines", state.missedDeadlines},
                                     {"frames_over_budget", framesOverBudget},
                                     {"pairs_skipped", state.pairsSkipped},
                                     {"travel_limited_frames", state.travelLimitedFrames},
                                     {"compute_us", {{"p50", p50}, {"p99", p99}, {"max", worst}}}};
    c.out << result.dump(2) << "\n";
  } else {
    c.out << "frames          " << frames << "\nmax contacts    " << maxContacts << "\nmean contacts   "
          << sumContacts * perFrame << "\nmax force       " << maxForceN << " N\nmean tests      "
          << sumTested * perFrame << " per frame (" << (options.sim.coherence.enabled ? "time-critical" : "brute force")
          << "), and " << sumChunkTests * perFrame << " chunk tests\nMaxTravel       " << sumTravelScale * perFrame << " of its bound on average\nmissed deadlines "
          << state.missedDeadlines << "\nover 1 ms        " << framesOverBudget << " frames\ncompute         p50 "
          << p50 << " us, p99 " << p99 << " us, max " << worst << " us\n";
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
      "nothing moves.\n\n"
      "Examples:\n"
      "  voxhap simulate ball-and-socket --move ball --script turn.txt --voxel-size 0.35mm \\\n"
      "      --point-offset=-0.175mm --json\n"
      "  voxhap simulate peg-in-hole --move peg --script insert.txt --voxel-size 0.05mm --trace out.csv";
  simulate.options = {
      {"move", 0, "NAME", "an object to move (repeatable)"},
      {"script", 0, "FILE", "motion script: one for all moving objects or one per --move"},
      {"voxel-size", 0, "LENGTH", "voxel size of the static scene, e.g. 0.35mm (default 1mm)"},
      {"point-spacing", 0, "LENGTH", "point spacing of the moving objects (default: the voxel size)"},
      {"point-offset", 0, "LENGTH", "move every point along its normal, negative inward (e.g. -0.175mm)"},
      {"point-layer", 0, "K", "take points from the free-space layer K voxels out (0 … 8; collision offset)"},
      {"no-awareness", 0, "", "turn geometrical awareness off (every point samples the surface field)"},
      {"pre-contact-damping", 0, "", "damp points approaching in the layer just outside the force layer"},
      {"capacity", 0, "N", "point tests per frame (default: measured online)"},
      {"brute-force", 0, "", "test every point every frame (no time-critical sampling), for comparison"},
      {"no-drifting", 0, "", "look every due point up in the voxmap (no point drifting, paper §5.2)"},
      {"duration", 0, "SECONDS", "simulated time (default: the longest script)"},
      {"trace", 0, "FILE.csv", "write the per-frame trace"},
      kCacheDirOption,
      kNoCacheOption,
      {"json", 0, "", "print one JSON summary on stdout"}};
  simulate.run = runSimulate;
  return simulate;
}

}  // namespace voxhap::cli
