// `voxhap bench table1`: the paper's Table 1 for the built-in scenes.
//
// Per row the static objects are voxelized as one at the voxel size and the dynamic
// object at its point spacing, as `voxhap voxelize` does (points = the dynamic object's
// surface voxels, voxels = the static environment's interior + surface + distance
// voxels). Cold: into a fresh scratch cache folder, so nothing is read; warm: the same
// calls again, now loading the files just written (the OS file cache is warm too).

#include <filesystem>
#include <memory>
#include <optional>
#include <thread>

#include <CLI/CLI.hpp>
#include <unistd.h>

#include "app/bench/benchmark.h"
#include "app/cache_options.h"
#include "app/cli/number_format.h"
#include "app/scene_source.h"
#include "app/sim_options.h"
#include "app/voxelize_objects.h"
#include "haptics/core/error.h"
#include "haptics/voxel/voxel_cache.h"

namespace voxhap::cli {
namespace {

namespace fs = std::filesystem;

/// One row of Table 1: a built-in scene and its two resolutions.
struct Table1Row {
  const char* scene;          ///< built-in scene name, also the "scenario" column
  const char* dynamicObject;  ///< the moving object, voxelized at the point spacing
  double voxelSizeM;          ///< of the static environment
  double pointSpacingM;       ///< of the dynamic object
  bool quick;                 ///< part of `--quick` (small enough for CI)
};

/// The paper's rows, in its order (rows of one scene together: each scene loads once).
constexpr Table1Row kRows[] = {
    {"ball-and-socket", "ball", 0.35e-3, 0.35e-3, true},
    {"ball-and-socket", "ball", 0.15e-3, 0.15e-3, false},
    {"landing-gear", "actuator", 2.5e-3, 1.0e-3, true},
    {"landing-gear", "actuator", 1.25e-3, 0.7e-3, false},
};

std::vector<BenchColumn> table1Columns() {
  return {
      {"scenario", "scenario", BenchStyle::Text},
      {"voxel_size_m", "voxel mm", BenchStyle::Millimetres, 2},
      {"point_spacing_m", "spacing mm", BenchStyle::Millimetres, 2},
      {"voxelize_s", "voxelize s", BenchStyle::Fixed, 2},
      {"load_s", "load s", BenchStyle::Fixed, 3},
      {"dynamic_triangles", "dyn. tris", BenchStyle::Count},
      {"points", "points", BenchStyle::Count},
      {"static_triangles", "static tris", BenchStyle::Count},
      {"voxels", "voxels", BenchStyle::Scientific},
  };
}

/// A fresh folder for the cold builds' cache files, removed with everything in it.
class ScratchCache {
public:
  explicit ScratchCache(const fs::path& parent)
      : path_(parent / ("bench-table1-" + std::to_string(::getpid()))) {
    std::error_code ec;
    fs::remove_all(path_, ec);
    fs::create_directories(path_, ec);
    if (ec) throw Error(path_.string() + ": cannot create the benchmark's cache folder: " + ec.message());
  }
  ~ScratchCache() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  ScratchCache(const ScratchCache&) = delete;
  ScratchCache& operator=(const ScratchCache&) = delete;

  const fs::path& path() const { return path_; }

private:
  fs::path path_;
};

/// What one voxelization contributes to a row.
struct Measured {
  double voxelizeS = 0.0;
  std::optional<double> loadS;  ///< empty when the cache is off or the file was not written
  std::uint64_t triangles = 0;
  std::uint64_t surfaceVoxels = 0;
  std::uint64_t totalVoxels = 0;
};

/// Builds `objects` at `voxelSizeM` through `cache` (cold), then loads it back (warm).
Measured measure(std::span<const SceneObject* const> objects, const std::string& shownName, double voxelSizeM,
                 const CacheOptions& cache, Console& console, const std::string& label) {
  VoxelizeOptions options;
  options.voxelSizeM = voxelSizeM;
  Measured m;
  {
    const CachedVoxelization cold =
        voxelizeCached(objects, options, cache, console.progress(label + ": voxelizing " + shownName));
    warnAboutVoxelization(console, shownName, cold);
    if (cold.cacheHit) throw Error(cold.cacheFile.string() + ": the scratch cache folder was not empty");
    const VoxelizeStats& s = cold.voxelized.stats;
    m = {cold.voxelizeS, std::nullopt, s.triangles, s.surfaceVoxels, s.totalVoxels()};
    std::error_code ec;
    if (cold.cacheFile.empty() || !fs::exists(cold.cacheFile, ec)) return m;
  }  // the cold voxmap is freed before the warm one is loaded
  const CachedVoxelization warm =
      voxelizeCached(objects, options, cache, console.progress(label + ": loading " + shownName));
  for (const std::string& warning : warm.warnings) console.warning(warning);
  if (warm.cacheHit) m.loadS = warm.loadS;
  return m;
}

/// What `voxhap bench table1` was given.
struct Table1Args {
  bool quick = false;
  std::uint64_t seed = kDefaultSeed;
  SimOptions sim;  ///< the cache
};

BenchTable runTable1(const Table1Args& args, Console& console) {
  const bool quick = args.quick;
  const std::uint64_t seed = args.seed;
  const CacheOptions userCache = voxelCacheOptions(args.sim);
  std::unique_ptr<ScratchCache> scratch;
  CacheOptions cache{{}, false};
  if (userCache.enabled) {
    scratch = std::make_unique<ScratchCache>(userCache.directory);
    cache = {scratch->path(), true};
  }

  BenchTable table("table1", table1Columns());
  table.extra["quick"] = quick;
  table.extra["seed"] = seed;
  table.extra["threads"] = std::thread::hardware_concurrency();
  table.extra["cache"] = cache.enabled ? "cold: fresh folder; warm: the files just written" : "disabled";

  std::size_t rowsToRun = 0;
  for (const Table1Row& row : kRows) rowsToRun += (!quick || row.quick) ? 1 : 0;
  std::optional<Scene> scene;
  std::string sceneName;
  std::size_t rowNumber = 0;
  for (const Table1Row& row : kRows) {
    if (quick && !row.quick) continue;
    ++rowNumber;
    if (sceneName != row.scene) {
      scene.reset();  // one scene in memory at a time
      scene = loadScene(row.scene, seed, console);
      sceneName = row.scene;
    }
    const std::string label = "table1 " + std::to_string(rowNumber) + "/" + std::to_string(rowsToRun) + " " +
                              row.scene + " " + fixed(row.pointSpacingM * 1e3, 2) + "/" +
                              fixed(row.voxelSizeM * 1e3, 2) + " mm";
    const std::vector<const SceneObject*> statics = objectsToVoxelize(*scene, std::nullopt);
    const std::vector<const SceneObject*> dynamic = objectsToVoxelize(*scene, std::string(row.dynamicObject));
    const Measured s = measure(statics, kStaticObjectsName, row.voxelSizeM, cache, console, label);
    const Measured d = measure(dynamic, row.dynamicObject, row.pointSpacingM, cache, console, label);
    console.note(label + ": voxelized in " + fixed(s.voxelizeS + d.voxelizeS, 2) + " s" +
                 (s.loadS && d.loadS ? ", loaded in " + fixed(*s.loadS + *d.loadS, 2) + " s" : ""));

    const std::size_t r = table.addRow();
    table.set(r, "scenario", std::string(row.scene));
    table.set(r, "voxel_size_m", row.voxelSizeM);
    table.set(r, "point_spacing_m", row.pointSpacingM);
    table.set(r, "voxelize_s", s.voxelizeS + d.voxelizeS);
    if (s.loadS && d.loadS) table.set(r, "load_s", *s.loadS + *d.loadS);
    table.set(r, "dynamic_triangles", static_cast<std::int64_t>(d.triangles));
    table.set(r, "points", static_cast<std::int64_t>(d.surfaceVoxels));
    table.set(r, "static_triangles", static_cast<std::int64_t>(s.triangles));
    table.set(r, "voxels", static_cast<std::int64_t>(s.totalVoxels));
  }
  return table;
}

}  // namespace

Benchmark table1Benchmark() {
  Benchmark b;
  b.name = "table1";
  b.summary = "The paper's Table 1: voxelize and load s, triangles, points, voxels per scene.";
  b.usage = "[--quick] [--seed N] [--cache-dir DIR] [--no-cache]";
  b.description =
      "Rows (scenario, static voxel size / dynamic point spacing):\n"
      "  ball-and-socket 0.35 / 0.35 mm   (--quick)\n"
      "  ball-and-socket 0.15 / 0.15 mm\n"
      "  landing-gear    2.5  / 1.0 mm    (--quick)\n"
      "  landing-gear    1.25 / 0.7 mm    (minutes and several GB of memory)\n\n"
      "Per row the static objects are voxelized as one environment at the voxel size and the\n"
      "dynamic object (ball, actuator) at its point spacing, as `voxhap voxelize` does:\n"
      "points are the dynamic object's surface voxels (its pointshell), voxels the static\n"
      "environment's interior, surface and distance-field voxels. voxelize_s is the cold build\n"
      "of both, into a fresh folder made under the cache folder and removed afterwards;\n"
      "load_s is loading both back from the files just written (so the OS file cache is warm).\n"
      "With --no-cache nothing is written and load_s is not measured.\n\n"
      "Examples:\n"
      "  voxhap bench table1\n"
      "  voxhap bench table1 --quick --json\n"
      "  voxhap bench table1 --csv table1.csv --cache-dir /scratch/voxhap";
  b.addOptions = [](CLI::App& command) -> BenchRunFn {
    auto args = std::make_shared<Table1Args>();
    command.add_flag("--quick", args->quick,
                     "only the small rows (ball 0.35 mm, landing gear 2.5 / 1.0 mm), for CI");
    addUnsignedOption(command, "--seed", args->seed, "seed of the generated landing gear (default 1)");
    addSimOptions(command, args->sim, {SimOption::Cache});
    return [args](Console& console) { return runTable1(*args, console); };
  };
  return b;
}

}  // namespace voxhap::cli
