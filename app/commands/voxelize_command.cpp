#include <memory>
#include <optional>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <sys/resource.h>

#include "app/cli/command.h"
#include "app/cli/number_format.h"
#include "app/commands/commands.h"
#include "app/scene_source.h"
#include "app/sim_options.h"
#include "app/voxel_slice.h"
#include "app/voxelize_objects.h"
#include "haptics/core/error.h"
#include "haptics/voxel/voxel_cache.h"

namespace voxhap::cli {
namespace {

std::uint64_t peakRssBytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<std::uint64_t>(usage.ru_maxrss) * 1024u;  // Linux reports KiB
}

/// What `voxhap voxelize` was given.
struct VoxelizeArgs {
  std::string scene;
  std::optional<std::string> object;
  SimOptions sim;  ///< --voxel-size, --no-awareness and the cache
  std::uint64_t bits = 4;
  std::optional<SliceSpec> slice;
  std::optional<std::string> png;
  std::uint64_t seed = kDefaultSeed;
  bool json = false;
};

VoxelizeOptions voxelizeOptionsOf(const VoxelizeArgs& args) {
  if (!args.sim.voxelSizeM) throw UsageError("--voxel-size is required, e.g. --voxel-size 0.35mm");
  VoxelizeOptions options;
  options.voxelSizeM = *args.sim.voxelSizeM;
  options.encoding = VoxelEncoding::forBits(static_cast<int>(args.bits));
  options.buildFeatureFields = !args.sim.noAwareness;
  return options;
}

nlohmann::ordered_json resultJson(const std::string& objectName, const VoxelizeOptions& options,
                                  const CachedVoxelization& r) {
  const VoxelizeStats& s = r.voxelized.stats;
  return {{"object", objectName},
          {"voxel_size_m", options.voxelSizeM},
          {"bits", options.encoding.bitsPerField},
          {"triangles", s.triangles},
          {"polygons_after_merge", s.polygonsAfterMerge},
          {"points", s.surfaceVoxels},
          {"points_by_feature",
           {{"vertex", s.vertexPoints}, {"edge", s.edgePoints}, {"surface", s.surfacePoints}}},
          {"voxels",
           {{"interior", s.interiorVoxels},
            {"surface", s.surfaceVoxels},
            {"distance", s.distanceVoxels},
            {"total", s.totalVoxels()}}},
          {"voxelize_s", r.voxelizeS},
          {"load_s", r.loadS},
          {"memory_bytes", r.voxelized.voxmap.memoryBytes()},
          {"cache", r.cacheHit ? "hit" : "miss"},
          {"peak_rss_bytes", peakRssBytes()}};
}

void printTable(std::ostream& out, const std::string& objectName, const VoxelizeOptions& options,
                const CachedVoxelization& r) {
  const VoxelizeStats& s = r.voxelized.stats;
  const double mib = 1024.0 * 1024.0;
  auto row = [&out](const std::string& label, const std::string& value) {
    out << "  " << label << std::string(label.size() < 22 ? 22 - label.size() : 1, ' ') << value << "\n";
  };
  out << "voxelized " << objectName << " at " << fixed(options.voxelSizeM * 1e3, 3) << " mm ("
      << options.encoding.bitsPerField << "-bit fields, range " << options.encoding.rangeVoxels
      << (options.buildFeatureFields ? ", geometrical awareness" : ", no geometrical awareness") << ")\n";
  row("triangles", withCommas(s.triangles));
  row("polygons after merge", withCommas(s.polygonsAfterMerge));
  row("points", withCommas(s.surfaceVoxels) + "  (vertex " + withCommas(s.vertexPoints) + ", edge " +
                    withCommas(s.edgePoints) + ", surface " + withCommas(s.surfacePoints) + ")");
  row("voxels", withCommas(s.totalVoxels()) + "  (interior " + withCommas(s.interiorVoxels) + ", surface " +
                    withCommas(s.surfaceVoxels) + ", distance " + withCommas(s.distanceVoxels) + ")");
  row("voxelize", fixed(r.voxelizeS, 2) + " s");
  row("load", fixed(r.loadS, 2) + " s");
  row("voxmap memory", fixed(static_cast<double>(r.voxelized.voxmap.memoryBytes()) / mib, 1) + " MiB");
  row("peak RSS", fixed(static_cast<double>(peakRssBytes()) / mib, 1) + " MiB");
  row("cache", std::string(r.cacheHit ? "hit" : "miss") +
                   (r.cacheFile.empty() ? " (disabled)" : ", " + r.cacheFile.string()));
}

int runVoxelize(const VoxelizeArgs& args, const CommandContext& c) {
  const VoxelizeOptions options = voxelizeOptionsOf(args);
  if (args.slice.has_value() != args.png.has_value()) throw UsageError("--slice and --png go together");
  const std::optional<SliceSpec>& slice = args.slice;
  const CacheOptions cache = voxelCacheOptions(args.sim);

  const Scene scene = loadScene(args.scene, args.seed, c.console);
  const std::optional<std::string>& objectName = args.object;
  const std::vector<const SceneObject*> objects = objectsToVoxelize(scene, objectName);
  const std::string shownName = objectName.value_or(kStaticObjectsName);

  const CachedVoxelization result =
      voxelizeCached(objects, options, cache, c.console.progress("voxelizing " + shownName));
  warnAboutVoxelization(c.console, shownName, result);
  c.console.note(result.cacheHit ? "loaded " + result.cacheFile.string()
                                 : "voxelized in " + fixed(result.voxelizeS, 2) + " s, cached in " +
                                       fixed(result.saveS, 2) + " s");

  nlohmann::ordered_json json = resultJson(shownName, options, result);
  if (slice) {
    const std::string& png = *args.png;
    const SliceLayout layout = sliceLayout(result.voxelized.voxmap, *slice);
    const render::RgbImage image = drawSlice(result.voxelized.voxmap, *slice, layout);
    render::writePng(png, image);
    json["slice"] = {{"axis", std::string(1, "xyz"[slice->axis])},
                     {"coordinate_m", slice->coordinateM},
                     {"layer", layout.layer},
                     {"png", png},
                     {"width_px", image.width},
                     {"height_px", image.height}};
  }
  if (args.json) {
    c.out << json.dump(2) << "\n";
  } else {
    printTable(c.out, shownName, options, result);
    if (slice) {
      c.out << "  slice                 " << json["slice"]["png"].get<std::string>() << " ("
            << "xyz"[slice->axis] << " layer " << json["slice"]["layer"].get<int>() << ", "
            << json["slice"]["width_px"].get<int>() << " x " << json["slice"]["height_px"].get<int>()
            << " px: surface, edge, vertex fields)\n";
    }
  }
  return kExitOk;
}

}  // namespace

void addVoxelizeCommand(CommandTree& tree) {
  CommandHelp voxelize;
  voxelize.summary = "Voxelize an object or the static environment; print the paper's Table 1 figures.";
  voxelize.usage =
      "voxhap voxelize SCENE [--object NAME] --voxel-size SIZE [--bits N] [--no-awareness] [--json]\n"
      "       [--cache-dir DIR] [--no-cache] [--slice AXIS=COORD --png FILE.png]";
  voxelize.description =
      "Builds the voxmap of one object (--object NAME) or of every static object merged into one\n"
      "static environment (reported as object \"static\"), and prints what Table 1 of the VPS paper\n"
      "reports: triangles, quasi-planar polygons, points (surface voxels: the pointshell at this\n"
      "spacing, by feature), voxels (interior, surface, distance-field), voxelize and load seconds\n"
      "and memory. SIZE is a length: 0.35mm, 2.5 mm, 0.00035m or 0.00035 (metres).\n\n"
      "Results are cached on disk (default " +
      (userCacheDir() / "voxels").string() +
      "), keyed by a hash of the\n"
      "geometry and parameters: a second run loads the voxmap instead of building it. A corrupt\n"
      "or stale cache file is rebuilt with a warning.\n\n"
      "--slice AXIS=COORD --png FILE draws the layer of voxels at COORD (metres, or mm with 'mm',\n"
      "object frame) across AXIS, once per distance field (surface, edge, vertex) side by side:\n"
      "dark grey far, blue interior, white feature voxels, yellow to green free space 1 … range.\n\n"
      "Examples:\n"
      "  voxhap voxelize ball-and-socket --object ball --voxel-size 0.35mm\n"
      "  voxhap voxelize ball-and-socket --voxel-size 0.15mm --json\n"
      "  voxhap voxelize landing-gear --voxel-size 1.25mm --json\n"
      "  voxhap voxelize ball-and-socket --object ball --voxel-size 0.35mm --slice z=0 --png ball.png\n"
      "  voxhap voxelize my-assembly.glb --object bracket --voxel-size 1mm --bits 8 --no-cache";
  auto args = std::make_shared<VoxelizeArgs>();
  CLI::App& command = tree.add(tree.root(), "voxelize", std::move(voxelize),
                               [args](const CommandContext& c) { return runVoxelize(*args, c); });
  command.add_option("SCENE", args->scene, "a .gltf/.glb file or built-in scene name")->required();
  command
      .add_option("--object", args->object, "voxelize this object only (default: all static objects as one)")
      ->type_name("NAME");
  addSimOptions(command, args->sim, {SimOption::VoxelSize});
  command.get_option("--voxel-size")
      ->description("voxel edge, e.g. 0.35mm or 0.00035 (metres); required")
      ->type_name("SIZE");
  addParsedOption(
      command, "--bits", "N", "bits per distance field: 2, 4 (default) or 8",
      [&bits = args->bits](const std::string& text) {
        bits = parseUnsigned(text, "bits");
        if (bits != 2 && bits != 4 && bits != 8) {
          throw UsageError("--bits wants 2, 4 or 8 bits per distance field, not " + std::to_string(bits));
        }
      });
  addSimOptions(command, args->sim, {SimOption::NoAwareness});
  command.get_option("--no-awareness")
      ->description("build the surface field only (no edge and vertex fields)");
  command.add_flag("--json", args->json, "print one JSON document on stdout instead of a table");
  addSimOptions(command, args->sim, {SimOption::Cache});
  addParsedOption(command, "--slice", "AXIS=COORD", "with --png: draw the fields across x, y or z at COORD",
                  [&slice = args->slice](const std::string& text) { slice = parseSlice(text); });
  command.add_option("--png", args->png, "with --slice: where to write the picture")->type_name("FILE");
  addUnsignedOption(command, "--seed", args->seed, "seed of a generated scene (default 1)");
}

}  // namespace voxhap::cli
