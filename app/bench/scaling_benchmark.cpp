// `voxhap bench scaling`: frame time against pointshell size, 10 thousand to 10 million
// points, in contact-rich scripted motion.
//
// Scene: a tile (80 × 80 × 8 mm box) over a plate (130 × 130 × 10 mm). Its handle
// presses it 0.5 mm into the plate while sliding it along a Lissajous curve (±15 mm in x,
// ±10 mm in y) and rocking it ±2° about x and y at other periods, so that it stands on two,
// three or four corners in turn. Under geometrical awareness the tile's face points sample
// the plate's vertex field and its edge points the plate's edge field, both far away, so
// its contacts stay a few dozen vertex points however dense the shell: the frame's cost is
// then that of time-critical sampling over millions of points out of contact.
//
// Resolutions: each row picks the tile's point spacing for its point count (the tile's
// area over the count) and voxelizes the plate at that same size, as the paper does
// (points ∝ 1 / voxel size²). The two must go together: a pointshell coarser than the
// voxmap puts its points (voxel centres, up to half a spacing off the surface) deeper
// than the force layer, into the plate's interior, where every field reports contact
// (tried: 1.24 mm points on a 0.25 mm plate rest on 2,600 contacts). The plate is 130 mm
// wide, so the 39 µm row voxelizes it in under a minute (--static-voxel-size fixes the
// plate's voxel size for every row instead).
//
// Per row: the coherent run (capacity measured online, or --capacity) times every frame;
// then a shorter run from the same start with coherence off (every point tested every
// frame) gives the brute-force frame time; speedup = brute p50 / coherent p50.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <numbers>
#include <optional>

#include <CLI/CLI.hpp>

#include "app/bench/analytic_scenes.h"
#include "app/bench/benchmark.h"
#include "app/cache_options.h"
#include "app/cli/number_format.h"
#include "app/sim_options.h"
#include "app/sim_run.h"
#include "haptics/core/error.h"
#include "haptics/sim/local_simulation.h"
#include "haptics/sim/scene_model.h"

namespace voxhap::cli {
namespace {

constexpr std::uint64_t kDefaultPoints[] = {10'000, 100'000, 1'000'000, 10'000'000};
const glm::dvec3 kTileHalfM(0.040, 0.040, 0.004);
constexpr double kPlateHalfM = 0.065;  // the tile's half width + slide + margin
constexpr double kPlateThicknessM = 0.010;
/// The tile starts this far above the plate; its handle aims kPressM below touching.
constexpr double kStartGapM = 0.001;
constexpr double kPressM = 0.0005;
/// The Lissajous slide: amplitudes (m) and periods (s) in x and y.
constexpr double kSlideXM = 0.015, kSlideXPeriodS = 4.0;
constexpr double kSlideYM = 0.010, kSlideYPeriodS = 3.0;
/// The rocking: amplitude (rad) and periods (s) about x and y.
constexpr double kRockRad = 2.0 * std::numbers::pi / 180.0;
constexpr double kRockXPeriodS = 1.5, kRockYPeriodS = 2.1;
constexpr double kDefaultSeconds = 5.0;
constexpr double kQuickSeconds = 1.0;
/// Point tests the brute-force run may spend (its frames = this over the points).
constexpr double kBruteTests = 3e8;
constexpr double kQuickBruteTests = 2e7;
constexpr std::uint64_t kBruteMinFrames = 20, kBruteMaxFrames = 1000;
/// The 1 kHz frame's budget, µs.
constexpr double kBudgetUs = 1000.0;

double tileAreaM2() {
  const glm::dvec3 e = 2.0 * kTileHalfM;
  return 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
}

/// The point spacing that gives about `points` points on the tile: one point per
/// spacing² of its area (its faces lie off voxel boundaries), a little more at edges.
double spacingFor(std::uint64_t points) {
  return std::sqrt(tileAreaM2() / static_cast<double>(points));
}

std::vector<BenchColumn> scalingColumns() {
  return {
      {"points", "points", BenchStyle::Count},
      {"voxel_size_m", "spacing mm", BenchStyle::Millimetres, 3},
      {"static_voxel_size_m", "plate vox mm", BenchStyle::Millimetres, 3},
      {"frames", "frames", BenchStyle::Count},
      {"compute_p50_us", "p50 us", BenchStyle::Fixed, 0},
      {"compute_p99_us", "p99 us", BenchStyle::Fixed, 0},
      {"compute_p999_us", "p99.9 us", BenchStyle::Fixed, 0},
      {"compute_max_us", "max us", BenchStyle::Fixed, 0},
      {"missed_deadlines", "missed", BenchStyle::Count},
      {"frames_over_budget", ">1 ms", BenchStyle::Count},
      {"mean_tested", "tests/frame", BenchStyle::Fixed, 0},
      {"mean_contacts", "contacts", BenchStyle::Fixed, 1},
      {"max_contacts", "max cont.", BenchStyle::Count},
      {"mean_travel_scale", "MaxTravel", BenchStyle::Fixed, 3},
      {"mean_max_travel_m", "travel mm", BenchStyle::Millimetres, 4},
      {"brute_frames", "brute frames", BenchStyle::Count},
      {"brute_p50_us", "brute p50 us", BenchStyle::Fixed, 0},
      {"speedup", "speedup", BenchStyle::Fixed, 1},
      {"build_s", "build s", BenchStyle::Fixed, 1},
  };
}

/// What `voxhap bench scaling` was given.
struct ScalingArgs {
  bool quick = false;
  std::vector<std::uint64_t> points;       ///< --points, in order
  std::optional<double> staticVoxelSizeM;  ///< --static-voxel-size
  std::optional<std::uint64_t> seconds;    ///< --seconds (≥ 1)
  SimOptions sim;                          ///< --capacity and the cache
};

std::vector<std::uint64_t> pointCounts(const ScalingArgs& args) {
  if (args.quick) return {kDefaultPoints[0], kDefaultPoints[1]};
  if (args.points.empty()) return {std::begin(kDefaultPoints), std::end(kDefaultPoints)};
  return args.points;
}

Scene tileScene() {
  Scene scene;
  scene.sourceName = "tile-on-plate";
  scene.objects.push_back(plateObject("plate", kPlateHalfM, kPlateThicknessM));
  // off the voxel boundaries of any spacing, so a face is one layer of points
  const glm::dvec3 centre(0.13e-3, -0.21e-3, kTileHalfM.z + kStartGapM + 0.07e-3);
  scene.objects.push_back(boxObject("tile", centre, kTileHalfM));
  return scene;
}

Pose handlePoseAt(double tS) {
  constexpr double twoPi = 2.0 * std::numbers::pi;
  const glm::dvec3 slide(kSlideXM * std::sin(twoPi * tS / kSlideXPeriodS),
                         kSlideYM * std::sin(twoPi * tS / kSlideYPeriodS), -(kStartGapM + kPressM));
  const glm::dvec3 rock(kRockRad * std::sin(twoPi * tS / kRockXPeriodS),
                        kRockRad * std::sin(twoPi * tS / kRockYPeriodS), 0.0);
  return {slide, quatFromRotationVector(rock)};
}

/// The handle at `tS`, with its velocity by central differences.
HandleInput handleAt(double tS) {
  constexpr double h = 1e-5;
  const Pose before = handlePoseAt(tS - h), after = handlePoseAt(tS + h);
  HandleInput input{handlePoseAt(tS), {}, true};
  input.velocity.linearWorld = (after.position - before.position) / (2.0 * h);
  input.velocity.angularWorld =
      rotationVector(after.orientation * glm::conjugate(before.orientation)) / (2.0 * h);
  return input;
}

double microsecondsOfStep(LocalSimulation& sim, const HandleInput& handle) {
  const HandleInput handles[1] = {handle};
  sim.step(handles);
  return sim.lastStepS * 1e6;
}

void measureRow(const Scene& scene, std::uint64_t targetPoints, double staticVoxelM, double seconds,
                bool quick, const ScalingArgs& args, Console& console, const CacheOptions& cache,
                BenchTable& table, const std::string& label) {
  const double spacingM = spacingFor(targetPoints);
  SceneModelOptions options;
  options.staticVoxelSizeM = staticVoxelM > 0.0 ? staticVoxelM : spacingM;
  options.pointSpacingM = spacingM;
  if (args.sim.capacity) options.sim.coherence.capacityTests = static_cast<double>(*args.sim.capacity);
  useVoxelCache(options, cache, console);
  const auto buildStart = std::chrono::steady_clock::now();
  SimModel model = buildSceneModel(scene, {"tile"}, options, console.progress(label + ": preparing"));
  const double buildS = secondsSince(buildStart);
  const std::size_t points = model.objects[0].shell.size();

  // coherent: the real thing
  const auto frames = static_cast<std::uint64_t>(std::llround(seconds / model.dtS));
  LocalSimulation sim(model);
  const SimState& state = sim.state;
  std::vector<double> computeUs;
  computeUs.reserve(frames);
  double sumTested = 0.0, sumContacts = 0.0, sumScale = 0.0, sumTravel = 0.0;
  std::uint32_t maxContacts = 0;
  std::uint64_t overBudget = 0;
  const ProgressFn progress = console.progress(label + ": coherent");
  for (std::uint64_t f = 0; f < frames; ++f) {
    const double us = microsecondsOfStep(sim, handleAt(state.timeS + model.dtS));
    computeUs.push_back(us);
    overBudget += us > kBudgetUs ? 1 : 0;
    sumTested += sim.outputs.coherence.tested;
    sumContacts += sim.object(0).contacts;
    maxContacts = std::max(maxContacts, sim.object(0).contacts);
    sumScale += sim.outputs.coherence.travelScale;
    sumTravel += sim.object(0).maxTravelM;
    if (progress && f % 100 == 0) progress(static_cast<double>(f) / static_cast<double>(frames));
  }
  const std::uint64_t missed = sim.workspace.counters.missedDeadlines;
  const double coherentP50 = percentile(computeUs, 0.5);

  // brute force: every point every frame, from the same start
  model.coherence.enabled = false;
  const double bruteTests = quick ? kQuickBruteTests : kBruteTests;
  const std::uint64_t bruteFrames = std::clamp<std::uint64_t>(
      static_cast<std::uint64_t>(bruteTests / static_cast<double>(std::max<std::size_t>(points, 1))),
      kBruteMinFrames, std::min(kBruteMaxFrames, frames));
  LocalSimulation brute(model);
  std::vector<double> bruteUs;
  bruteUs.reserve(bruteFrames);
  const ProgressFn bruteProgress = console.progress(label + ": brute force");
  for (std::uint64_t f = 0; f < bruteFrames; ++f) {
    bruteUs.push_back(microsecondsOfStep(brute, handleAt(brute.state.timeS + model.dtS)));
    if (bruteProgress) bruteProgress(static_cast<double>(f) / static_cast<double>(bruteFrames));
  }
  const double bruteP50 = percentile(bruteUs, 0.5);

  const auto n = static_cast<double>(frames);
  const std::size_t r = table.addRow();
  table.set(r, "points", static_cast<std::int64_t>(points));
  table.set(r, "voxel_size_m", spacingM);
  table.set(r, "static_voxel_size_m", options.staticVoxelSizeM);
  table.set(r, "frames", static_cast<std::int64_t>(frames));
  table.set(r, "compute_p50_us", coherentP50);
  table.set(r, "compute_p99_us", percentile(computeUs, 0.99));
  table.set(r, "compute_p999_us", percentile(computeUs, 0.999));
  table.set(r, "compute_max_us", *std::max_element(computeUs.begin(), computeUs.end()));
  table.set(r, "missed_deadlines", static_cast<std::int64_t>(missed));
  table.set(r, "frames_over_budget", static_cast<std::int64_t>(overBudget));
  table.set(r, "mean_tested", sumTested / n);
  table.set(r, "mean_contacts", sumContacts / n);
  table.set(r, "max_contacts", static_cast<std::int64_t>(maxContacts));
  table.set(r, "mean_travel_scale", sumScale / n);
  table.set(r, "mean_max_travel_m", sumTravel / n);
  table.set(r, "brute_frames", static_cast<std::int64_t>(bruteFrames));
  table.set(r, "brute_p50_us", bruteP50);
  table.set(r, "speedup", coherentP50 > 0.0 ? bruteP50 / coherentP50 : 0.0);
  table.set(r, "build_s", buildS);
  console.note(label + ": " + withCommas(points) + " points, p50 " + fixed(coherentP50, 0) + " us, brute " +
               fixed(bruteP50, 0) + " us, " + withCommas(missed) + " missed deadlines");
}

BenchTable runScaling(const ScalingArgs& args, Console& console) {
  const bool quick = args.quick;
  const std::vector<std::uint64_t> counts = pointCounts(args);
  // 0: the plate's voxels as fine as the row's points
  const double staticVoxelM = args.staticVoxelSizeM.value_or(0.0);
  const double seconds =
      args.seconds ? static_cast<double>(*args.seconds) : (quick ? kQuickSeconds : kDefaultSeconds);
  const CacheOptions cache = voxelCacheOptions(args.sim);
  const Scene scene = tileScene();
  BenchTable table("scaling", scalingColumns());
  table.extra["quick"] = quick;
  table.extra["scene"] = "tile 80 x 80 x 8 mm pressed 0.5 mm into a plate, sliding and rocking";
  table.extra["capacity"] = args.sim.capacity ? "fixed" : "measured online";
  table.extra["seconds"] = seconds;
  table.extra["budget_us"] = kBudgetUs;
  for (std::size_t i = 0; i < counts.size(); ++i) {
    measureRow(scene, counts[i], staticVoxelM, seconds, quick, args, console, cache, table,
               "scaling " + std::to_string(i + 1) + "/" + std::to_string(counts.size()) + " " +
                   scientific(static_cast<double>(counts[i]), 1) + " points");
  }
  return table;
}

}  // namespace

Benchmark scalingBenchmark() {
  Benchmark b;
  b.name = "scaling";
  b.summary = "Frame time against pointshell size, 10^4 to 10^7 points, coherent and brute force.";
  b.usage =
      "[--quick] [--points N …] [--static-voxel-size LENGTH] [--seconds S] [--capacity N]\n"
      "       [--cache-dir DIR] [--no-cache]";
  b.description =
      "A tile (80 x 80 x 8 mm) pressed 0.5 mm into a plate by its handle slides along a\n"
      "Lissajous curve (+-15 mm, +-10 mm) and rocks +-2 degrees about x and y, standing on\n"
      "two to four corners in turn. Each row sets the tile's point spacing for its point\n"
      "count and voxelizes the plate at the same size (--static-voxel-size fixes the plate's\n"
      "voxel size instead). Geometrical awareness is on: the tile's face and edge points\n"
      "sample the plate's far vertex and edge fields.\n\n"
      "The coherent run (5 s of frames; capacity measured online unless --capacity) times\n"
      "every frame: percentiles, frames over the 1 ms budget, missed deadlines (more points\n"
      "in contact than the capacity), point tests, contacts and MaxTravel\n"
      "(mean_travel_scale: over its bound of half a voxel). A shorter run from the\n"
      "same start with coherence off tests every point every frame: brute_p50_us, and\n"
      "speedup = brute p50 / coherent p50.\n\n"
      "Rows: 10^4, 10^5, 10^6 and 10^7 points (the last builds a 10-million-point shell and a\n"
      "39 um plate: about a minute and 2 GB). --quick: the first two, 1 s each.\n\n"
      "Examples:\n"
      "  voxhap bench scaling --quick\n"
      "  voxhap bench scaling --csv scaling.csv --svg scaling.svg\n"
      "  voxhap bench scaling --points 300000 --capacity 20000 --json";
  b.addOptions = [](CLI::App& command) -> BenchRunFn {
    auto args = std::make_shared<ScalingArgs>();
    command.add_flag("--quick", args->quick, "only 10^4 and 10^5 points, 1 s each, for CI");
    addRepeatedOption(command, "--points", "N",
                      "a pointshell size to measure (repeatable; default the four above)",
                      [&points = args->points](const std::string& text) {
                        const std::uint64_t n = parseUnsigned(text, "points");
                        if (n < 100 || n > 100'000'000)
                          throw UsageError("--points wants 100 … 100000000, got " + text);
                        points.push_back(n);
                      });
    addLengthOption(command, "--static-voxel-size", args->staticVoxelSizeM,
                    "the plate's voxel size in every row (default: the row's spacing)");
    addParsedOption(command, "--seconds", "S", "length of the coherent run, s (default 5)",
                    [&seconds = args->seconds](const std::string& text) {
                      seconds = parseUnsigned(text, "seconds");
                      if (*seconds < 1) throw UsageError("--seconds wants at least 1");
                    });
    addSimOptions(command, args->sim, {SimOption::Capacity, SimOption::Cache});
    return [args](Console& console) { return runScaling(*args, console); };
  };
  b.plot = [] {
    SvgPlotSpec spec;
    spec.title = "Frame compute against pointshell size";
    spec.xKey = "points";
    spec.yKey = "compute_p99_us";
    spec.xLabel = "points";
    spec.yLabel = "compute p99, us";
    spec.logX = true;
    return spec;
  }();
  return b;
}

}  // namespace voxhap::cli
