// `voxhap bench extraction`: the paper's landing-gear task (§7) at several resolutions,
// the same run as `voxhap demo` (app/extraction.h) once per row.

#include <cstdint>
#include <memory>
#include <optional>
#include <thread>

#include <CLI/CLI.hpp>

#include "app/bench/benchmark.h"
#include "app/cache_options.h"
#include "app/cli/number_format.h"
#include "app/extraction.h"
#include "app/extraction_options.h"
#include "app/scene_source.h"
#include "app/sim_options.h"
#include "app/sim_run.h"
#include "haptics/core/error.h"

namespace voxhap::cli {
namespace {

/// One resolution of the extraction.
struct ExtractionRow {
  double voxelSizeM;     ///< of the static gear
  double pointSpacingM;  ///< of the actuator
  bool quick;            ///< part of `--quick` (for CI)
};

constexpr ExtractionRow kRows[] = {
    {2.5e-3, 1.0e-3, true},
    {1.25e-3, 0.7e-3, false},
    {1.0e-3, 0.5e-3, false},
    {0.7e-3, 0.35e-3, false},
};

std::vector<BenchColumn> extractionColumns() {
  return {
      {"voxel_size_m", "voxel mm", BenchStyle::Millimetres, 2},
      {"point_spacing_m", "spacing mm", BenchStyle::Millimetres, 2},
      {"points", "points", BenchStyle::Count},
      {"frames", "frames", BenchStyle::Count},
      {"completion_s", "clear at s", BenchStyle::Fixed, 2},
      {"wall_s", "wall s", BenchStyle::Fixed, 1},
      {"frames_over_budget", ">1 ms", BenchStyle::Count},
      {"missed_deadlines", "missed", BenchStyle::Count},
      {"compute_p50_us", "p50 us", BenchStyle::Fixed, 0},
      {"compute_p99_us", "p99 us", BenchStyle::Fixed, 0},
      {"compute_max_us", "max us", BenchStyle::Fixed, 0},
      {"max_contacts", "contacts", BenchStyle::Count},
      {"max_penetration_m", "penetr. mm", BenchStyle::Millimetres, 3},
      {"exact_wall_s", "exact s", BenchStyle::Fixed, 1},
      {"mean_travel_scale", "MaxTravel", BenchStyle::Fixed, 3},
      {"actuator_progress_m", "got m", BenchStyle::Fixed, 3},
      {"path_length_m", "of m", BenchStyle::Fixed, 3},
      {"error", "error", BenchStyle::Text},
  };
}

/// What `voxhap bench extraction` was given.
struct ExtractionBenchArgs {
  bool quick = false;
  ExtractionArgs extraction;
};

BenchTable runExtractionBench(const ExtractionBenchArgs& args, Console& console) {
  const bool quick = args.quick;
  const std::string scriptFile = args.extraction.scriptFile();
  const MotionScript script = loadMotionScript(scriptFile);
  const SimOptions& sim = args.extraction.sim;

  BenchTable table("extraction", extractionColumns());
  table.extra["quick"] = quick;
  table.extra["coherence"] = !sim.bruteForce;
  table.extra["capacity"] = sim.capacity ? nlohmann::ordered_json(static_cast<double>(*sim.capacity))
                                         : nlohmann::ordered_json("measured online");
  table.extra["script"] = scriptFile;
  table.extra["threads"] = std::thread::hardware_concurrency();

  const Scene scene = loadScene(args.extraction.sceneName(), kDefaultSeed, console);
  table.extra["scene"] = scene.sourceName;
  std::size_t rowsToRun = 0;
  for (const ExtractionRow& row : kRows) rowsToRun += (!quick || row.quick) ? 1 : 0;
  std::size_t rowNumber = 0;
  for (const ExtractionRow& row : kRows) {
    if (quick && !row.quick) continue;
    ++rowNumber;
    ExtractionOptions options =
        extractionOptions(args.extraction, console, row.voxelSizeM, row.pointSpacingM);
    options.label = "extraction " + std::to_string(rowNumber) + "/" + std::to_string(rowsToRun) + " " +
                    fixed(row.pointSpacingM * 1e3, 2) + "/" + fixed(row.voxelSizeM * 1e3, 2) + " mm";
    const std::size_t i = table.addRow();
    table.set(i, "voxel_size_m", row.voxelSizeM);
    table.set(i, "point_spacing_m", row.pointSpacingM);
    std::optional<ExtractionResult> result;
    try {
      result = runExtraction(scene, script, options, console);
    } catch (const Error& e) {
      // a row this machine cannot hold (the voxelizer's memory estimate) leaves the others
      console.warning(options.label + ": " + e.what());
      table.set(i, "error", std::string(e.what()));
      continue;
    }
    const ExtractionResult& r = *result;
    console.note(options.label + ": " + fixed(r.wallS, 1) + " s, actuator " + fixed(r.actuatorProgressM, 3) +
                 " m along the path of " + fixed(r.pathLengthM, 3) + " m");
    table.set(i, "points", static_cast<std::int64_t>(r.points));
    table.set(i, "frames", static_cast<std::int64_t>(r.stats.frames()));
    if (r.cameOut()) table.set(i, "completion_s", *r.completionS);
    table.set(i, "wall_s", r.wallS);
    table.set(i, "frames_over_budget", static_cast<std::int64_t>(r.stats.framesOverBudget));
    table.set(i, "missed_deadlines", static_cast<std::int64_t>(r.stats.counters.missedDeadlines));
    table.set(i, "compute_p50_us", r.stats.computePercentileUs(0.5));
    table.set(i, "compute_p99_us", r.stats.computePercentileUs(0.99));
    table.set(i, "compute_max_us", r.stats.computeMaxUs());
    table.set(i, "max_contacts", static_cast<std::int64_t>(r.stats.maxContacts));
    table.set(i, "max_penetration_m", r.exact.maxDepthM);
    table.set(i, "exact_wall_s", r.exact.wallS);
    table.set(i, "mean_travel_scale", r.stats.meanTravelScale());
    table.set(i, "actuator_progress_m", r.actuatorProgressM);
    table.set(i, "path_length_m", r.pathLengthM);
  }
  return table;
}

}  // namespace

Benchmark extractionBenchmark() {
  Benchmark b;
  b.name = "extraction";
  b.summary = "The paper's landing-gear task: pull the actuator out at several resolutions.";
  b.usage =
      "[--quick] [--paper-contact] [--brute-force] [--capacity N] [--duration SECONDS] [--penetration-every "
      "N]\n"
      "       [--probe-spacing LENGTH]\n"
      "       [--script FILE] [--scene SCENE --move NAME] [--cache-dir DIR] [--no-cache]";
  b.description =
      "Rows (actuator point spacing / static voxel size):\n"
      "  1.0 / 2.5 mm    (--quick)\n"
      "  0.7 / 1.25 mm   (the paper's finer landing-gear row)\n"
      "  0.5 / 1.0 mm\n"
      "  0.35 / 0.7 mm   (voxelizing the gear peaks at about 12 GiB with the surface planes of\n"
      "                  contact finer than a voxel, 9 GiB without: --paper-contact)\n\n"
      "Each row is one `voxhap extract` run (see `voxhap extract --help` for the path and how\n"
      "the exact penetration is measured): the model is built through the voxel cache (a cold\n"
      "cache voxelizes first, which wall_s then includes), then the 18 s script runs at 1 kHz\n"
      "simulated time. completion_s: simulated time from which the actuator stayed clear of\n"
      "the gear (null: it never came out); wall_s: model build plus frames plus the exact\n"
      "measurements; frames_over_budget: frames whose compute time exceeded 1 ms;\n"
      "missed_deadlines: frames with more points in contact than the capacity (the engine's\n"
      "count); compute_*_us: per-frame compute time of the engine alone; max_penetration_m:\n"
      "deepest probe of either surface inside the other (actuator into static or back; Embree,\n"
      "probes a quarter voxel apart on every triangle); exact_wall_s: of wall_s, the time spent\n"
      "measuring it; mean_travel_scale: mean\n"
      "MaxTravel over its bound (below ~0.16 at 1.25 mm the actuator cannot keep up with the\n"
      "0.1 m/s handle); actuator_progress_m: how far its centre got along the path, of\n"
      "path_length_m; error: why a row did not run (the voxelizer refuses a voxel size\n"
      "whose estimated memory exceeds 3/4 of this machine's; the other rows still run).\n"
      "With --brute-force every\n"
      "row tests every point every frame instead (a comparison run).\n\n"
      "Examples:\n"
      "  voxhap bench extraction\n"
      "  voxhap bench extraction --quick --json\n"
      "  voxhap bench extraction --quick --brute-force --csv brute.csv";
  b.addOptions = [](CLI::App& command) -> BenchRunFn {
    auto args = std::make_shared<ExtractionBenchArgs>();
    SimOptions& sim = args->extraction.sim;
    command.add_flag("--quick", args->quick, "only the first row (1.0 / 2.5 mm), for CI");
    addSimOptions(command, sim,
                  {SimOption::PaperContact, SimOption::BruteForce, SimOption::Capacity,
                   SimOption::VoxelMemory, SimOption::Duration});
    command.get_option("--duration")->description("simulated time per row (default: the whole script)");
    addExtractionOptions(command, args->extraction);
    addSimOptions(command, sim, {SimOption::Cache});
    return [args](Console& console) { return runExtractionBench(*args, console); };
  };
  return b;
}

}  // namespace voxhap::cli
