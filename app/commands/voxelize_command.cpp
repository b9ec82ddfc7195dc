#include <nlohmann/json.hpp>
#include <sys/resource.h>

#include "app/cache_options.h"
#include "app/cli/command.h"
#include "app/cli/number_format.h"
#include "app/commands/commands.h"
#include "app/scene_source.h"
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

VoxelizeOptions voxelizeOptionsOf(const ParsedArgs& args) {
  const auto size = args.value("voxel-size");
  if (!size) throw UsageError("--voxel-size is required, e.g. --voxel-size 0.35mm");
  VoxelizeOptions options;
  options.voxelSizeM = parseLengthM(*size, "voxel-size");
  const std::uint64_t bits = args.value("bits") ? parseUnsigned(*args.value("bits"), "bits") : 4;
  if (bits != 2 && bits != 4 && bits != 8) {
    throw UsageError("--bits wants 2, 4 or 8 bits per distance field, not " + std::to_string(bits));
  }
  options.encoding = VoxelEncoding::forBits(static_cast<int>(bits));
  options.buildFeatureFields = !args.has("no-awareness");
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

int runVoxelize(const CommandContext& c) {
  if (c.args.positionals.size() != 1) {
    throw UsageError("expected one SCENE, got " + std::to_string(c.args.positionals.size()));
  }
  const VoxelizeOptions options = voxelizeOptionsOf(c.args);
  std::optional<SliceSpec> slice;
  if (c.args.has("slice") != c.args.has("png")) throw UsageError("--slice and --png go together");
  if (c.args.has("slice")) slice = parseSlice(*c.args.value("slice"));
  const CacheOptions cache = voxelCacheOptions(c.args);

  const std::uint64_t seed =
      c.args.value("seed") ? parseUnsigned(*c.args.value("seed"), "seed") : kDefaultSeed;
  const Scene scene = loadScene(c.args.positionals[0], seed, c.console);
  const std::optional<std::string> objectName = c.args.value("object");
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
    const std::string png = *c.args.value("png");
    const SliceLayout layout = sliceLayout(result.voxelized.voxmap, *slice);
    const RgbImage image = drawSlice(result.voxelized.voxmap, *slice, layout);
    writePng(png, image);
    json["slice"] = {{"axis", std::string(1, "xyz"[slice->axis])},
                     {"coordinate_m", slice->coordinateM},
                     {"layer", layout.layer},
                     {"png", png},
                     {"width_px", image.width},
                     {"height_px", image.height}};
  }
  if (c.args.has("json")) {
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

Command voxelizeCommand() {
  Command voxelize;
  voxelize.name = "voxelize";
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
  voxelize.options = {
      {"object", 0, "NAME", "voxelize this object only (default: all static objects as one)"},
      {"voxel-size", 0, "SIZE", "voxel edge, e.g. 0.35mm or 0.00035 (metres); required"},
      {"bits", 0, "N", "bits per distance field: 2, 4 (default) or 8"},
      {"no-awareness", 0, "", "build the surface field only (no edge and vertex fields)"},
      {"json", 0, "", "print one JSON document on stdout instead of a table"},
      kCacheDirOption,
      kNoCacheOption,
      {"slice", 0, "AXIS=COORD", "with --png: draw the fields across x, y or z at COORD"},
      {"png", 0, "FILE", "with --slice: where to write the picture"},
      {"seed", 0, "N", "seed of a generated scene (default 1)"},
  };
  voxelize.run = runVoxelize;
  return voxelize;
}

}  // namespace voxhap::cli
