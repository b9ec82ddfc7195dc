#include "haptics/voxel/voxel_cache.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <functional>
#include <optional>

#include "haptics/core/error.h"
#include "haptics/core/parallel.h"
#include "haptics/geometry/quasi_planar.h"
#include "haptics/voxel/cache_file.h"

namespace voxhap {
namespace {

namespace fs = std::filesystem;

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// The parts of some objects, in order, with their quasi-planar features.
struct ObjectParts {
  std::vector<const TriangleMesh*> meshes;
  std::vector<MeshFeatures> features;
};

std::vector<const TriangleMesh*> meshesOf(std::span<const SceneObject* const> objects) {
  std::vector<const TriangleMesh*> meshes;
  for (const SceneObject* object : objects) {
    for (const Part& part : object->parts) meshes.push_back(&part.mesh);
  }
  return meshes;
}

/// Features of every part at `voxelSizeM`, one part per task: the same whatever the thread count.
ObjectParts partsWithFeatures(std::span<const SceneObject* const> objects, double voxelSizeM, int threads) {
  ObjectParts parts{meshesOf(objects), {}};
  parts.features.resize(parts.meshes.size());
  parallelFor(parts.meshes.size(), threads,
              [&](std::size_t i) { parts.features[i] = extractFeatures(*parts.meshes[i], voxelSizeM); });
  return parts;
}

/// A hash of what the cache key always covers: format version, kind and every part's geometry.
ContentHash geometryHash(CacheKind kind, std::span<const SceneObject* const> objects) {
  ContentHash hash;
  hash.add(kCacheFormatVersion);
  hash.add(static_cast<std::uint32_t>(kind));
  const std::vector<const TriangleMesh*> meshes = meshesOf(objects);
  hash.add(static_cast<std::uint64_t>(meshes.size()));
  for (const TriangleMesh* mesh : meshes) {
    hash.addArray(std::span<const glm::vec3>(mesh->positionsWorld));
    hash.addArray(std::span<const glm::uvec3>(mesh->triangles));
  }
  return hash;
}

/// Runs `load` on the cache file when it holds the key, else `build` then `save`; fills
/// the timings, the hit flag and warnings of `result` (a CachedVoxelization or CachedPointshell).
template <typename Result>
void loadOrBuild(Result& result, const CacheOptions& cache, const std::string& fileName, CacheKind kind,
                 const Digest128& key, const std::function<void(CacheFileReader&)>& load,
                 const std::function<void()>& build, const std::function<void(CacheFileWriter&)>& save) {
  const fs::path file = cache.directory / fileName;
  const bool enabled = cache.enabled && !cache.directory.empty();
  if (enabled) {
    result.cacheFile = file;
    std::error_code ec;
    if (fs::exists(file, ec)) {
      const auto start = std::chrono::steady_clock::now();
      try {
        CacheFileReader reader(file, kind, key);
        load(reader);
        reader.finish();
        result.cacheHit = true;
        result.loadS = secondsSince(start);
        return;
      } catch (const CacheFileError& e) {
        result.warnings.push_back("cache file " + file.string() + " " + e.what() + "; rebuilt");
      } catch (const fs::filesystem_error& e) {
        result.warnings.push_back("cache file " + file.string() + " cannot be read (" + e.code().message() +
                                  "); rebuilt");
      }
    }
  }
  build();
  if (!enabled) return;
  const auto start = std::chrono::steady_clock::now();
  try {
    std::error_code ec;
    fs::create_directories(cache.directory, ec);
    if (ec) throw Error(cache.directory.string() + ": cannot create the cache folder: " + ec.message());
    CacheFileWriter writer(file, kind, key);
    save(writer);
    writer.commit();
  } catch (const Error& e) {
    result.warnings.push_back(std::string("not cached: ") + e.what());
  }
  result.saveS = secondsSince(start);
}

// ---- voxmaps ----

void putGrid(CacheFileWriter& w, const VoxelGrid& grid, const VoxelEncoding& encoding) {
  w.put(grid.originLocal);
  w.put(grid.voxelSizeM);
  w.put(grid.dimsHyper);
  w.put(static_cast<std::int32_t>(encoding.bitsPerField));
  w.put(static_cast<std::int32_t>(encoding.rangeVoxels));
}

/// The stats' counters in file order.
std::array<std::uint64_t*, 11> counters(VoxelizeStats& s) {
  return {&s.interiorVoxels, &s.surfaceVoxels,      &s.distanceVoxels,   &s.edgeVoxels,
          &s.vertexVoxels,   &s.vertexPoints,       &s.edgePoints,       &s.surfacePoints,
          &s.triangles,      &s.polygonsAfterMerge, &s.voteDisagreements};
}

void saveVoxelized(CacheFileWriter& w, const VoxelizedObject& v) {
  putGrid(w, v.voxmap.grid(), v.voxmap.encoding());
  VoxelizeStats stats = v.stats;
  for (const std::uint64_t* c : counters(stats)) w.put(*c);
  w.put(static_cast<std::uint8_t>(stats.firstDisagreementLocal.has_value()));
  w.put(stats.firstDisagreementLocal.value_or(glm::dvec3(0.0)));
  w.putArray(v.voxmap.hyperEntries());
  w.putArray(v.voxmap.chunkEntries());
  w.putArray(v.voxmap.voxelBytes());
  w.putArray(v.voxmap.chunkDistances());
  const SparseSurfacePlanes& planes = v.voxmap.surfacePlanes();
  w.putArray(planes.occupancy());
  w.put(static_cast<std::uint64_t>(planes.planeCount()));
  for (std::size_t k = 0; k < planes.segmentCount(); ++k)
    w.write(planes.segment(k).data(), planes.segment(k).size_bytes());
  w.write(planes.convexSides().data(), planes.convexSides().size_bytes());
}

/// What a voxmap cache file holds before its arrays.
struct VoxmapHeader {
  VoxelGrid grid;
  VoxelEncoding encoding;
  VoxelizeStats stats;
};

VoxmapHeader readVoxmapHeader(CacheFileReader& r, const VoxelizeOptions& options) {
  VoxmapHeader h;
  h.grid.originLocal = r.get<glm::dvec3>();
  h.grid.voxelSizeM = r.get<double>();
  h.grid.dimsHyper = r.get<glm::ivec3>();
  h.encoding.bitsPerField = r.get<std::int32_t>();
  h.encoding.rangeVoxels = r.get<std::int32_t>();
  if (h.grid.voxelSizeM != options.voxelSizeM || h.encoding.bitsPerField != options.encoding.bitsPerField ||
      h.encoding.rangeVoxels != options.encoding.rangeVoxels) {
    throw CacheFileError("holds other data (parameters differ)");
  }
  for (std::uint64_t* c : counters(h.stats)) *c = r.get<std::uint64_t>();
  const bool hasDisagreement = r.get<std::uint8_t>() != 0;
  const auto disagreement = r.get<glm::dvec3>();
  if (hasDisagreement) h.stats.firstDisagreementLocal = disagreement;
  return h;
}

/// The file's surface planes; throws CacheFileError unless they are consistent and what
/// `options` ask for (a chunk of them per mixed chunk, or none).
SparseSurfacePlanes readPlanes(CacheFileReader& r, std::size_t mixedChunks, const VoxelizeOptions& options) {
  SparseSurfacePlanes out;
  const std::string problem = out.resetTo(r.getArray<std::uint64_t>());
  if (!problem.empty()) throw CacheFileError("is corrupt (" + problem + ")");
  if (r.get<std::uint64_t>() != out.planeCount())
    throw CacheFileError("is corrupt (surface planes do not match their masks)");
  for (std::size_t k = 0; k < out.segmentCount(); ++k)
    r.read(out.segment(k).data(), out.segment(k).size_bytes());
  if (!out.complete()) throw CacheFileError("is corrupt (a stored surface plane is empty)");
  std::vector<std::uint8_t> sides(out.planeCount());
  r.read(sides.data(), sides.size());
  if (!std::ranges::all_of(sides, [](std::uint8_t s) { return s <= SurfacePlane::kAllSides; }))
    throw CacheFileError("is corrupt (a surface plane's convex sides are not six bits)");
  out.setConvexSides(std::move(sides));
  if (out.chunkCount() != (options.surfacePlanes ? mixedChunks : 0))
    throw CacheFileError("is corrupt (surface planes do not match the voxmap)");
  return out;
}

VoxelizedObject loadVoxelized(CacheFileReader& r, const VoxelizeOptions& options) {
  const auto [grid, encoding, stats] = readVoxmapHeader(r, options);
  VoxelizedObject v;
  v.stats = stats;
  auto hyper = r.getArray<std::uint32_t>();
  auto chunks = r.getArray<std::uint32_t>();
  auto voxelBytes = r.getArray<std::uint8_t>(Voxmap::kPadBytes);
  auto chunkDistances = r.getArray<std::uint8_t>();
  const std::string problem =
      Voxmap::validate(grid, encoding, hyper, chunks, voxelBytes.size(), chunkDistances.size());
  if (!problem.empty()) throw CacheFileError("is corrupt (" + problem + ")");
  v.voxmap = Voxmap(grid, encoding, std::move(hyper), std::move(chunks), std::move(voxelBytes),
                    std::move(chunkDistances));
  SparseSurfacePlanes planes = readPlanes(r, v.voxmap.mixedChunkCount(), options);
  if (options.surfacePlanes) v.voxmap.setSurfacePlanes(std::move(planes), options.threads);
  return v;
}

// ---- pointshells ----

void savePointshell(CacheFileWriter& w, const Pointshell& p) {
  w.put(p.pointSpacingM);
  w.putArray(std::span<const glm::vec3>(p.positionsLocal));
  w.putArray(std::span<const glm::vec3>(p.normalsLocal));
  w.putArray(std::span<const PointFeature>(p.features));
  w.putArray(std::span<const std::uint32_t>(p.chunkBegin));
  w.putArray(std::span<const glm::vec3>(p.chunkCentroidsLocal));
}

Pointshell loadPointshell(CacheFileReader& r, const PointshellOptions& options) {
  Pointshell p;
  p.pointSpacingM = r.get<double>();
  if (p.pointSpacingM != options.pointSpacingM) throw CacheFileError("holds other data (parameters differ)");
  p.positionsLocal = r.getArray<glm::vec3>();
  p.normalsLocal = r.getArray<glm::vec3>();
  p.features = r.getArray<PointFeature>();
  p.chunkBegin = r.getArray<std::uint32_t>();
  p.chunkCentroidsLocal = r.getArray<glm::vec3>();
  const std::size_t n = p.positionsLocal.size();
  bool valid = p.normalsLocal.size() == n && p.features.size() == n && !p.chunkBegin.empty() &&
               p.chunkBegin.front() == 0 && p.chunkBegin.back() == n &&
               p.chunkCentroidsLocal.size() + 1 == p.chunkBegin.size();
  for (std::size_t c = 1; valid && c < p.chunkBegin.size(); ++c)
    valid = p.chunkBegin[c - 1] <= p.chunkBegin[c];
  for (std::size_t i = 0; valid && i < n; ++i) valid = p.features[i] <= PointFeature::Vertex;
  if (!valid) throw CacheFileError("is corrupt (inconsistent pointshell arrays)");
  return p;
}

ProgressFn stage(const ProgressFn& progress, double begin, double end) {
  if (!progress) return {};
  return [progress, begin, end](double f) { progress(begin + (end - begin) * f); };
}

Digest128 voxmapKey(std::span<const SceneObject* const> objects, const VoxelizeOptions& options) {
  ContentHash hash = geometryHash(CacheKind::Voxmap, objects);
  hash.addDouble(options.voxelSizeM);
  hash.add(static_cast<std::int32_t>(options.encoding.bitsPerField));
  hash.add(static_cast<std::int32_t>(options.encoding.rangeVoxels));
  hash.add(static_cast<std::uint8_t>(options.buildFeatureFields));
  hash.add(static_cast<std::uint8_t>(options.surfacePlanes));
  return hash.digest();
}

std::string voxmapFileName(const Digest128& key) {
  return "voxmap-" + key.hex() + ".vxc";
}

/// Opens the voxmap cache file `file` for paging within `budgetBytes`: everything but the
/// voxel words is read, the words are only checksummed. Empty when the whole voxmap fits
/// the budget. Throws CacheFileError on a bad file, voxhap::Error when the budget cannot
/// hold even the voxmap's tables.
std::optional<BudgetedVoxmap> openPaged(const fs::path& file, const Digest128& key,
                                        const VoxelizeOptions& options, std::uint64_t budgetBytes) {
  CacheFileReader r(file, CacheKind::Voxmap, key);
  const auto [grid, encoding, stats] = readVoxmapHeader(r, options);
  auto hyper = r.getArray<std::uint32_t>();
  auto chunks = r.getArray<std::uint32_t>();
  const auto wordBytes = r.get<std::uint64_t>();
  // the trees, the file blocks of the chunk entries and the chunk-level field (a byte a chunk)
  const std::uint64_t tableBytes =
      (hyper.size() + 2 * chunks.size()) * sizeof(std::uint32_t) + hyper.size() * kChunksPerHyper;
  if (wordBytes + tableBytes <= budgetBytes) return std::nullopt;
  const std::uint64_t wordsOffset = r.fileOffset();
  r.skip(wordBytes);
  auto chunkDistances = r.getArray<std::uint8_t>();
  // a paged voxmap has no surface planes (its contacts take the voxels' tangent planes)
  const auto maskCount = r.get<std::uint64_t>();
  r.skip(maskCount * sizeof(std::uint64_t));
  const auto planeCount = r.get<std::uint64_t>();
  r.skip(planeCount * (sizeof(SurfacePlane) + 1));
  r.finish();
  const std::string problem =
      Voxmap::validate(grid, encoding, hyper, chunks, wordBytes, chunkDistances.size());
  if (!problem.empty()) throw CacheFileError("is corrupt (" + problem + ")");

  const std::size_t blockBytes =
      std::size_t{kVoxelsPerChunk} * static_cast<std::size_t>(encoding.bytesPerWord());
  if (budgetBytes < tableBytes + blockBytes + Voxmap::kSlotOverheadBytes) {
    throw Error("a voxel memory of " + std::to_string(budgetBytes) +
                " bytes cannot hold the voxmap's tables (" + std::to_string(tableBytes) +
                " bytes) and one chunk of voxel words; allow more");
  }
  const std::size_t slots =
      static_cast<std::size_t>((budgetBytes - tableBytes) / (blockBytes + Voxmap::kSlotOverheadBytes));
  std::vector<std::uint32_t> fileBlockOfEntry(chunks.size(), 0xFFFFFFFFu);
  for (std::size_t i = 0; i < chunks.size(); ++i) {
    if (chunks[i] & Voxmap::kUniform) continue;
    fileBlockOfEntry[i] = chunks[i];
    chunks[i] = Voxmap::kUniform | Voxmap::kMissingWord;
  }
  BudgetedVoxmap result;
  result.wordBytes = wordBytes;
  result.voxmap =
      Voxmap::paged(grid, encoding, std::move(hyper), std::move(chunks), slots, std::move(chunkDistances));
  result.pager = std::make_shared<VoxelPager>(result.voxmap.pagedArrays(), file, wordsOffset,
                                              std::move(fileBlockOfEntry), slots);
  return result;
}

}  // namespace

BudgetedVoxmap voxelizeWithinBudget(std::span<const SceneObject* const> objects,
                                    const VoxelizeOptions& options, const CacheOptions& cache,
                                    std::uint64_t budgetBytes, const ProgressFn& progress) {
  if (!cache.enabled || cache.directory.empty()) {
    throw Error("a voxel memory budget pages voxels from the voxel cache, which is off (--no-cache)");
  }
  checkVoxelizeOptions(options);
  const Digest128 key = voxmapKey(objects, options);
  const fs::path file = cache.directory / voxmapFileName(key);
  BudgetedVoxmap result;
  std::error_code ec;
  if (fs::exists(file, ec)) {
    try {
      if (auto paged = openPaged(file, key, options, budgetBytes)) return std::move(*paged);
    } catch (const CacheFileError& e) {
      result.warnings.push_back("cache file " + file.string() + " " + e.what() + "; rebuilt");
    }
  }
  CachedVoxelization whole = voxelizeCached(objects, options, cache, progress);
  for (std::string& w : whole.warnings) result.warnings.push_back(std::move(w));
  const std::uint64_t wordBytes = whole.voxelized.voxmap.voxelBytes().size();
  if (whole.voxelized.voxmap.memoryBytes() <= budgetBytes) {
    result.voxmap = std::move(whole.voxelized.voxmap);
    result.wordBytes = wordBytes;
    return result;
  }
  whole = CachedVoxelization{};  // free it before paging it back
  if (!fs::exists(file, ec))
    throw Error(file.string() + ": the voxmap could not be cached, so it cannot be paged");
  auto paged = openPaged(file, key, options, budgetBytes);
  if (!paged)
    throw Error(file.string() + ": the voxmap fits its budget after all");  // unreachable: same sizes
  paged->warnings = std::move(result.warnings);
  return std::move(*paged);
}

CachedVoxelization voxelizeCached(std::span<const SceneObject* const> objects, const VoxelizeOptions& options,
                                  const CacheOptions& cache, const ProgressFn& progress) {
  const Digest128 key = voxmapKey(objects, options);
  checkVoxelizeOptions(options);
  CachedVoxelization result;
  loadOrBuild(
      result, cache, voxmapFileName(key), CacheKind::Voxmap, key,
      [&](CacheFileReader& r) { result.voxelized = loadVoxelized(r, options); },
      [&] {
        const auto start = std::chrono::steady_clock::now();
        const ObjectParts parts = partsWithFeatures(objects, options.voxelSizeM, options.threads);
        if (progress) progress(0.02);
        result.voxelized = voxelize(parts.meshes, parts.features, options, stage(progress, 0.02, 1.0));
        result.voxelizeS = secondsSince(start);
      },
      [&](CacheFileWriter& w) { saveVoxelized(w, result.voxelized); });
  if (progress) progress(1.0);
  return result;
}

CachedPointshell pointshellCached(std::span<const SceneObject* const> objects,
                                  const PointshellOptions& options, const CacheOptions& cache,
                                  const ProgressFn& progress) {
  ContentHash hash = geometryHash(CacheKind::Pointshell, objects);
  hash.addDouble(options.pointSpacingM);
  hash.addDouble(options.displacementM);
  hash.add(options.freeLayer);
  // on the surface, 2: edge and vertex voxels' points on their features (1: at the nearest
  // surface point, whose cache entries are left behind)
  hash.add(static_cast<std::uint8_t>(options.onSurface ? 2 : 0));
  const Digest128 key = hash.digest();

  checkPointshellOptions(options);
  CachedPointshell result;
  loadOrBuild(
      result, cache, "pointshell-" + key.hex() + ".vxc", CacheKind::Pointshell, key,
      [&](CacheFileReader& r) { result.pointshell = loadPointshell(r, options); },
      [&] {
        const auto start = std::chrono::steady_clock::now();
        const ObjectParts parts = partsWithFeatures(objects, options.pointSpacingM, options.threads);
        if (progress) progress(0.02);
        result.pointshell =
            buildPointshell(parts.meshes, parts.features, options, stage(progress, 0.02, 1.0));
        result.buildS = secondsSince(start);
      },
      [&](CacheFileWriter& w) { savePointshell(w, result.pointshell); });
  if (progress) progress(1.0);
  return result;
}

}  // namespace voxhap
