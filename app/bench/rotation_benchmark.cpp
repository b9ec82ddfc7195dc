// `voxhap bench rotation`: the paper's ball-and-socket measure (§7): how long one full
// turn of the ball in its socket takes when the user pushes it faster than MaxTravel lets
// it go, for the 25 mm ball of the paper's text and the 12.5 mm one of its Table 1's point
// counts (DESIGN §6).
//
// The ball's points are displaced a voxel inward and its pair with the socket has the
// surface voxels for its force layer, so that it seats (kBallForceLayer). Its handle
// always leads the ball by kLeadRad about the socket's x axis, through the ball's centre,
// so the coupling asks for more speed than MaxTravel allows in every frame. Capacity is
// measured online from the real cost of a test (or fixed with --capacity), and the frame
// budget is enforced in real time: a frame whose compute exceeds the 1 ms period stretches
// the turn by its overrun, as it would in a haptic loop. So
//   rotation_s = Σ over the turn's frames of max(period, compute time),
//   limit_s    = frames at MaxTravel = s/2: 2π·r / (s/2) periods, r the farthest point's
//                lever arm (the paper's 0.898 s at 0.35 mm for r = 25 mm).

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <numbers>
#include <sstream>

#include <CLI/CLI.hpp>
#include <glm/gtc/quaternion.hpp>

#include "app/bench/analytic_scenes.h"
#include "app/bench/ball_seating.h"
#include "app/bench/benchmark.h"
#include "app/cache_options.h"
#include "app/cli/number_format.h"
#include "app/exact_checks.h"
#include "app/scene_source.h"
#include "app/sim_options.h"
#include "app/sim_run.h"
#include "haptics/core/error.h"
#include "haptics/sim/local_simulation.h"

namespace voxhap::cli {
namespace {

constexpr double kDefaultSizesM[] = {0.35e-3, 0.15e-3, 0.07e-3, 0.035e-3};
/// The built-in scenes turned, in the order of the rows.
constexpr const char* kScenes[] = {"ball-and-socket", "small-ball-and-socket"};
/// How far the handle leads the ball, rad: a user turning it steadily.
constexpr double kLeadRad = 0.1;
/// The ball's exact penetration of the socket is measured at every this many frames' poses
/// (after the turn), probes a quarter voxel apart but no closer than kMinProbeSpacingM.
constexpr std::uint64_t kExactEveryFrames = 25;
constexpr double kMinProbeSpacingM = 0.05e-3;
/// A turn not done in this many times its limit is given up (no rotation_s).
constexpr double kGiveUpLimits = 4.0;

std::vector<BenchColumn> rotationColumns() {
  return {
      {"scene", "scene", BenchStyle::Text},
      {"ball_radius_m", "ball mm", BenchStyle::Millimetres, 1},
      {"voxel_size_m", "voxel mm", BenchStyle::Millimetres, 3},
      {"points", "points", BenchStyle::Count},
      {"force_layer", "layer", BenchStyle::Count},
      {"point_offset_m", "offset mm", BenchStyle::Millimetres, 3},
      {"rotation_s", "turn s", BenchStyle::Fixed, 3},
      {"limit_s", "limit s", BenchStyle::Fixed, 3},
      {"mean_contacts", "contacts", BenchStyle::Fixed, 0},
      {"missed_deadlines", "missed", BenchStyle::Count},
      {"frames", "frames", BenchStyle::Count},
      {"frames_over_budget", ">1 ms", BenchStyle::Count},
      {"mean_tested", "tests/frame", BenchStyle::Fixed, 0},
      {"mean_mandatory", "mandatory", BenchStyle::Fixed, 0},
      {"mean_capacity", "capacity", BenchStyle::Fixed, 0},
      {"mean_travel_scale", "MaxTravel", BenchStyle::Fixed, 3},
      {"compute_p50_us", "p50 us", BenchStyle::Fixed, 0},
      {"compute_p99_us", "p99 us", BenchStyle::Fixed, 0},
      {"turned_rad", "turned rad", BenchStyle::Fixed, 2},
      {"max_penetration_m", "pen mm", BenchStyle::Millimetres, 3},
      {"max_centre_drift_m", "drift mm", BenchStyle::Millimetres, 3},
  };
}

/// What `voxhap bench rotation` was given.
struct RotationArgs {
  bool quick = false;
  std::vector<double> voxelSizesM;  ///< --voxel-size, in order
  SimOptions sim;                   ///< --capacity and the cache
};

std::vector<double> voxelSizes(const RotationArgs& args) {
  if (args.quick) return {kDefaultSizesM[0]};
  if (args.voxelSizesM.empty()) return {std::begin(kDefaultSizesM), std::end(kDefaultSizesM)};
  return args.voxelSizesM;
}

/// The handle `angleRad` about x through `centre`, turning at `rateRadPerS`.
HandleInput handleAt(const glm::dvec3& centre, double angleRad, double rateRadPerS) {
  const glm::dquat turn = glm::angleAxis(angleRad, glm::dvec3(1.0, 0.0, 0.0));
  const Pose pose{centre - turn * centre, turn};
  const glm::dvec3 omega(rateRadPerS, 0.0, 0.0);
  return {pose, {glm::cross(omega, pose.position - centre), omega}};
}

void measureRow(const std::string& sceneName, const Scene& scene, double voxelM, const RotationArgs& args,
                Console& console, const CacheOptions& cache, const std::shared_ptr<FrameHelper>& helper,
                BenchTable& table, const std::string& label) {
  SceneModelOptions options;
  options.staticVoxelSizeM = voxelM;
  options.pointSpacingM = voxelM;
  options.pointDisplacementM = args.sim.pointOffsetM.value_or(kBallPointOffsetVoxels * voxelM);
  options.forceLayerOf = {{"ball", kBallForceLayer}};
  for (const auto& [name, layer] : args.sim.forceLayerOf) options.forceLayerOf[name] = layer;
  if (args.sim.capacity) options.sim.coherence.capacityTests = static_cast<double>(*args.sim.capacity);
  useVoxelCache(options, cache, console);
  const SimModel model = buildSceneModel(scene, {"ball"}, options, console.progress(label + ": preparing"));
  const MovingObjectModel& ball = model.objects[0];
  const glm::dvec3 centre = ball.body.comLocal;  // the scene file's placement is the world frame
  const double limitFrames = 2.0 * std::numbers::pi * ball.shellRadiusM / ball.maxTravelM;
  const auto giveUpFrames = static_cast<std::uint64_t>(kGiveUpLimits * limitFrames) + 1000;
  // a handle turning at the limit's rate, kLeadRad ahead of the ball
  const double rateRadPerS = ball.maxTravelM / ball.shellRadiusM / model.dtS;

  std::vector<SimState> toMeasure;  // measured after the turn: the checks would slow the frames after them
  double maxDriftM = 0.0;

  LocalSimulation sim(model);
  sim.workspace.helper = helper;
  const SimState& state = sim.state;
  std::vector<double> computeUs;
  computeUs.reserve(giveUpFrames);
  double turnedRad = 0.0;
  double realTimeS = 0.0;
  double sumContacts = 0.0, sumTested = 0.0, sumScale = 0.0, sumMandatory = 0.0, sumCapacity = 0.0;
  std::uint64_t overBudget = 0;
  const ProgressFn progress = console.progress(label + ": turning");
  HandleInput handles[1];
  while (turnedRad < 2.0 * std::numbers::pi && computeUs.size() < giveUpFrames) {
    handles[0] = handleAt(centre, turnedRad + kLeadRad, rateRadPerS);
    const glm::dquat before = state.bodies[0].orientation;
    sim.step(handles);
    const double us = sim.lastStepS * 1e6;
    computeUs.push_back(us);
    realTimeS += std::max(model.dtS, us * 1e-6);
    overBudget += us > model.dtS * 1e6 ? 1 : 0;
    turnedRad += rotationVector(state.bodies[0].orientation * glm::conjugate(before)).x;
    sumContacts += sim.object(0).contacts;
    sumTested += sim.outputs.coherence.tested;
    sumScale += sim.outputs.coherence.travelScale;
    sumMandatory += sim.outputs.coherence.mandatory;
    sumCapacity += sim.outputs.coherence.capacityTests;
    maxDriftM = std::max(maxDriftM, glm::length(state.bodies[0].comWorld - centre));
    if (computeUs.size() % kExactEveryFrames == 0) toMeasure.push_back(state);
    if (progress && computeUs.size() % 100 == 0)
      progress(std::clamp(turnedRad / (2.0 * std::numbers::pi), 0.0, 1.0));
  }
  if (progress) progress(1.0);
  ExactChecks exact(scene, model, options, std::max(voxelM / kProbesPerVoxel, kMinProbeSpacingM),
                    console.progress(label + ": preparing probes"));
  ExactCheckSummary penetration;
  for (const SimState& s : toMeasure) exact.check(model, s, penetration, false);

  const auto frames = static_cast<double>(computeUs.size());
  const std::size_t r = table.addRow();
  const Bounds ballBounds = scene.find("ball")->bounds();
  table.set(r, "scene", sceneName);
  table.set(r, "ball_radius_m", 0.5 * (ballBounds.max.x - ballBounds.min.x));
  table.set(r, "voxel_size_m", voxelM);
  table.set(r, "points", static_cast<std::int64_t>(ball.shell.size()));
  table.set(r, "force_layer", static_cast<std::int64_t>(model.pairs[0].forceLayer(state.forceLayer)));
  table.set(r, "point_offset_m", *options.pointDisplacementM);
  if (turnedRad >= 2.0 * std::numbers::pi) table.set(r, "rotation_s", realTimeS);
  table.set(r, "limit_s", limitFrames * model.dtS);
  table.set(r, "mean_contacts", sumContacts / frames);
  table.set(r, "missed_deadlines", static_cast<std::int64_t>(sim.workspace.counters.missedDeadlines));
  table.set(r, "frames", static_cast<std::int64_t>(computeUs.size()));
  table.set(r, "frames_over_budget", static_cast<std::int64_t>(overBudget));
  table.set(r, "mean_tested", sumTested / frames);
  table.set(r, "mean_travel_scale", sumScale / frames);
  table.set(r, "mean_mandatory", sumMandatory / frames);
  table.set(r, "mean_capacity", sumCapacity / frames);
  table.set(r, "compute_p50_us", percentile(computeUs, 0.5));
  table.set(r, "compute_p99_us", percentile(computeUs, 0.99));
  table.set(r, "turned_rad", turnedRad);
  table.set(r, "max_penetration_m", penetration.maxDepthM);
  table.set(r, "max_centre_drift_m", maxDriftM);
  console.note(label + ": " +
               (turnedRad >= 2.0 * std::numbers::pi ? "turned once in " + fixed(realTimeS, 3) + " s"
                                                    : "gave up after " + fixed(frames * model.dtS, 1) +
                                                          " s at " + fixed(turnedRad, 2) + " rad"));
}

BenchTable runRotation(const RotationArgs& args, Console& console) {
  const std::vector<double> sizes = voxelSizes(args);
  const CacheOptions cache = voxelCacheOptions(args.sim);
  BenchTable table("rotation", rotationColumns());
  table.extra["lead_rad"] = kLeadRad;
  table.extra["capacity"] = args.sim.capacity ? "fixed" : "measured online";
  const std::shared_ptr<FrameHelper> helper = frameHelperFor(args.sim);
  table.extra["frame_helper"] = helper ? "on CPU " + std::to_string(helper->cpu()) : "none";
  table.extra["paper"] = {{"voxel_size_m", 0.35e-3}, {"rotation_s", 1.28}, {"mean_contacts", 250}};
  const std::size_t rows = std::size(kScenes) * sizes.size();
  for (std::size_t k = 0; k < std::size(kScenes); ++k) {
    const Scene scene = loadScene(kScenes[k], kDefaultSeed, console);
    for (std::size_t i = 0; i < sizes.size(); ++i) {
      measureRow(kScenes[k], scene, sizes[i], args, console, cache, helper, table,
                 "rotation " + std::to_string(k * sizes.size() + i + 1) + "/" + std::to_string(rows) + " " +
                     kScenes[k] + " " + fixed(sizes[i] * 1e3, 3) + " mm");
    }
  }
  return table;
}

}  // namespace

Benchmark rotationBenchmark() {
  Benchmark b;
  b.name = "rotation";
  b.summary = "The ball turned once in its socket at MaxTravel: turn time against its limit.";
  b.usage =
      "[--quick] [--voxel-size LENGTH …] [--point-offset LENGTH] [--force-layer-of ball=N] [--capacity N] "
      "[--frame-helper] [--cache-dir DIR] [--no-cache]";
  b.description =
      "The paper's ball-and-socket measure (§7: 1.28 s for one turn at 0.35 mm, about 250\n"
      "points in contact), for both built-in balls: ball-and-socket, the 25 mm ball of the\n"
      "paper's text, and small-ball-and-socket, the 12.5 mm one whose point counts match its\n"
      "Table 1. The ball seats by the settings of a mating pair (paper §3.2): its points a\n"
      "voxel inward and the surface voxels for its pair's force layer (columns layer and\n"
      "offset; --point-offset and --force-layer-of ball=N try others; the paper's reading\n"
      "is half a voxel and layer 4, the session's default, slower and looser here). Its\n"
      "handle always leads it by 0.1 rad about the x axis, so the user asks for more speed\n"
      "than MaxTravel allows in every frame.\n\n"
      "Capacity is measured online from the real cost of each point test (--capacity N fixes\n"
      "it) and the frame budget is enforced in real time: rotation_s adds up max(1 ms, the\n"
      "frame's compute) over the turn, so overrunning frames stretch it. limit_s is the turn at\n"
      "MaxTravel = s/2 throughout (0.898 s at 0.35 mm for the paper's 25 mm lever arm, 0.449 s\n"
      "for 12.5 mm). A frame with more mandatory tests than its capacity (mean_mandatory:\n"
      "points in contact or a layer beyond it, tested whatever the travel; mean_capacity) is\n"
      "a missed deadline: the first of a run moves nothing, the rest run at full MaxTravel\n"
      "however long they take (their compute stretches the turn). A turn not done within 4\n"
      "limits (+1 s) is given up: rotation_s is empty and turned_rad says how far it got.\n"
      "--frame-helper lets a second thread, on a spare core, test half the points of each\n"
      "frame (the same turn, more capacity).\n\n"
      "Seating, measured exactly after the turn (Embree, probes a quarter voxel apart, at\n"
      "least 0.05 mm) at every 25th frame's pose: max_penetration_m, the deepest probe of\n"
      "either surface inside the other (the meshes' facets cross by up to 0.1 mm with the\n"
      "ball centred); max_centre_drift_m, how far the ball's centre strayed from the\n"
      "socket's.\n\n"
      "Rows: each ball at voxel sizes 0.35, 0.15, 0.07 and 0.035 mm (the last needs about 10\n"
      "million points for the 25 mm ball and minutes to voxelize).\n\n"
      "Examples:\n"
      "  voxhap bench rotation --quick\n"
      "  voxhap bench rotation --voxel-size 0.35mm --voxel-size 0.15mm --json\n"
      "  voxhap bench rotation --quick --force-layer-of ball=4 --point-offset=-0.175mm\n"
      "  voxhap bench rotation --capacity 100000 --csv rotation.csv\n"
      "  voxhap bench rotation --quick --frame-helper";
  b.addOptions = [](CLI::App& command) -> BenchRunFn {
    auto args = std::make_shared<RotationArgs>();
    command.add_flag("--quick", args->quick, "only 0.35 mm (both balls), for CI");
    addLengthListOption(command, "--voxel-size", args->voxelSizesM,
                        "a voxel size to measure (repeatable; default the four above)");
    addSimOptions(command, args->sim,
                  {SimOption::PointOffset, SimOption::ForceLayerOf, SimOption::Capacity,
                   SimOption::FrameHelper, SimOption::Cache});
    return [args](Console& console) { return runRotation(*args, console); };
  };
  b.plot = [] {
    SvgPlotSpec spec;
    spec.title = "Ball turned once in its socket";
    spec.xKey = "voxel_size_m";
    spec.yKey = "rotation_s";
    spec.seriesKey = "scene";
    spec.xLabel = "voxel size, m";
    spec.yLabel = "one turn, s (real time)";
    spec.logX = true;
    return spec;
  }();
  return b;
}

}  // namespace voxhap::cli
