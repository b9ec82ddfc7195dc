#include "haptics/voxel/voxelizer.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <sstream>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <unistd.h>

#include "haptics/core/error.h"
#include "haptics/core/parallel.h"
#include "haptics/geometry/embree_scene.h"
#include "haptics/voxel/chunk_distance.h"
#include "haptics/voxel/chunk_footprint.h"
#include "haptics/voxel/feature_rasterizer.h"
#include "haptics/voxel/hyperchunk_transform.h"
#include "haptics/voxel/interior_classifier.h"
#include "haptics/voxel/sparse_surface_planes.h"
#include "haptics/voxel/surface_planes.h"

namespace voxhap {
namespace {

constexpr int kLargestRange = 16;  // voxels; the halo of a hyperchunk's distance transform

/// Index of (x, y, z) in a box of nx × ny × … elements, x fastest; all arguments ≥ 0.
std::size_t at3(int x, int y, int z, int nx, int ny) {
  return static_cast<std::size_t>(x) +
         static_cast<std::size_t>(nx) *
             (static_cast<std::size_t>(y) + static_cast<std::size_t>(ny) * static_cast<std::size_t>(z));
}

/// Number of elements of a box nx × ny × nz.
std::size_t volume3(int nx, int ny, int nz) {
  return at3(0, 0, nz, nx, ny);
}

std::string gib(std::uint64_t bytes) {
  std::ostringstream s;
  s.precision(3);
  s << static_cast<double>(bytes) / double(1ull << 30) << " GiB";
  return s.str();
}

std::uint64_t physicalMemoryBytes() {
  const long pages = sysconf(_SC_PHYS_PAGES);
  const long pageSize = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && pageSize > 0 ? static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(pageSize)
                                   : (std::uint64_t{8} << 30);
}

/// What one hyperchunk contributes to the voxmap.
struct HyperResult {
  bool uniform = true;
  VoxelWord uniformWord = 0;
  std::vector<std::uint32_t> chunkEntries;                    // kUniform | word, or index into blocks
  std::vector<std::uint8_t> blocks;                           // packed words of the mixed chunks
  std::array<std::uint64_t, kChunksPerHyper / 64> bearing{};  // bit per chunk: a surface field not far
  VoxelizeStats stats;                                        // voxel counts and votes only
};

class Voxelizer {
public:
  Voxelizer(const VoxelGrid& grid, const VoxelizeOptions& options,
            const HyperchunkBlocks<std::uint8_t>& features, const InteriorClassifier& interior)
      : grid_(grid), options_(options), features_(features), interior_(interior) {}

  bool nearFeatures(const glm::ivec3& ijkHyper) const {
    for (int dz = -1; dz <= 1; ++dz) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          if (features_.hyperHasBlocks(ijkHyper + glm::ivec3(dx, dy, dz))) return true;
        }
      }
    }
    return false;
  }

  /// Buffers one thread reuses from hyperchunk to hyperchunk.
  struct Scratch {
    std::vector<std::uint8_t> bits;
    std::vector<std::uint8_t> distance[kFieldCount];
    std::vector<VoxelWord> words;
  };

  HyperResult build(const glm::ivec3& ijkHyper, HyperchunkTransform& transform, Scratch& scratch) const {
    HyperResult result;
    const VoxelEncoding& enc = options_.encoding;
    const glm::ivec3 core = ijkHyper * kHyperEdgeVoxels;
    std::vector<std::uint8_t> votes;
    if (!nearFeatures(ijkHyper)) {
      // no surface within range: every voxel is inside, or every voxel is far
      interior_.votes(core + kHyperEdgeVoxels / 2, glm::ivec3(1), votes);
      const bool inside = votes[0] >= 2;
      result.uniformWord = inside ? enc.pack(kValueInterior, kValueInterior, kValueInterior) : 0;
      if (inside)
        result.stats.interiorVoxels = std::uint64_t{kHyperEdgeVoxels} * kHyperEdgeVoxels * kHyperEdgeVoxels;
      return result;
    }

    const int r = enc.rangeVoxels;
    const int n = transform.haloSize();
    const int c = kHyperEdgeVoxels;
    const std::uint8_t bitsHere[kFieldCount] = {kSurfaceBit, kEdgeBit, kVertexBit};
    const int fields = options_.buildFeatureFields ? kFieldCount : 1;
    std::vector<std::uint8_t>& bits = scratch.bits;
    gatherBits(core - r, n, bits);
    bool hasDistance[kFieldCount] = {false, false, false};
    for (int f = 0; f < fields; ++f) hasDistance[f] = transform.run(bits, bitsHere[f], scratch.distance[f]);
    interior_.votes(core, glm::ivec3(c), votes);

    std::vector<VoxelWord>& words = scratch.words;
    words.resize(volume3(c, c, c));
    // fields left out (no geometrical awareness) stay far; fields with no feature in reach read far distances
    std::uint8_t keep[kFieldCount];
    const std::uint8_t* distanceOf[kFieldCount];
    std::array<std::uint8_t, kHyperEdgeVoxels> farRow;
    farRow.fill(static_cast<std::uint8_t>(r + 1));
    for (int f = 0; f < kFieldCount; ++f) keep[f] = f < fields ? 0xFF : 0;
    for (int z = 0; z < c; ++z) {
      for (int y = 0; y < c; ++y) {
        const std::size_t i0 = at3(0, y, z, c, c);
        for (int f = 0; f < kFieldCount; ++f)
          distanceOf[f] = hasDistance[f] ? &scratch.distance[f][i0] : farRow.data();
        composeRow(&bits[at3(r, y + r, z + r, n, n)], &votes[i0], distanceOf, keep, &words[i0], result.stats);
        if (result.stats.voteDisagreements > 0 && !result.stats.firstDisagreementLocal) {
          for (int x = 0; x < c; ++x) {
            const std::uint8_t v = votes[i0 + static_cast<std::size_t>(x)];
            if (!(bits[at3(r + x, y + r, z + r, n, n)] & kSurfaceBit) && v != 0 && v != 3) {
              result.stats.firstDisagreementLocal = grid_.voxelCentre(core + glm::ivec3(x, y, z));
              break;
            }
          }
        }
      }
    }
    packChunks(words, result);
    return result;
  }

private:
  /// The words of one row of 64 voxels from their feature bits, inside votes (0 … 3) and
  /// capped distances per field; adds the row's voxels to `stats`. Written as one
  /// branch-free pass so that the compiler vectorizes it (out of line: inlined, it does not).
  [[gnu::noinline]] void composeRow(const std::uint8_t* bits, const std::uint8_t* votes,
                                    const std::uint8_t* const* distance, const std::uint8_t* keep,
                                    VoxelWord* words, VoxelizeStats& stats) const {
    const VoxelEncoding& enc = options_.encoding;
    const int shift = enc.bitsPerField;
    const auto range = static_cast<std::uint8_t>(enc.rangeVoxels);
    const std::uint8_t* d0 = distance[0];
    const std::uint8_t* d1 = distance[1];
    const std::uint8_t* d2 = distance[2];
    const std::uint8_t keep0 = keep[0], keep1 = keep[1], keep2 = keep[2];
    // one field's value: feature voxel, else interior, else free space within range, else far
    auto value = [range](std::uint8_t isFeature, std::uint8_t inside, std::uint8_t d, std::uint8_t kept) {
      std::uint8_t v = d <= range ? static_cast<std::uint8_t>(kValueFeature + d) : kValueFar;
      v = inside ? kValueInterior : v;
      v = isFeature ? kValueFeature : v;
      return static_cast<std::uint8_t>(v & kept);
    };
    std::uint32_t interior = 0, surface = 0, distant = 0, edges = 0, vertices = 0;
    std::uint32_t vertexPoints = 0, edgePoints = 0, surfacePoints = 0, disagreements = 0;
    // byte arithmetic only, no shifts of bytes and no short-circuits, so that it vectorizes
    for (int x = 0; x < kHyperEdgeVoxels; ++x) {
      const std::uint8_t b = bits[x];
      const std::uint8_t vote = votes[x];
      const auto isSurface = static_cast<std::uint8_t>(b & kSurfaceBit);
      const auto isEdge = static_cast<std::uint8_t>(b & kEdgeBit);
      const auto isVertex = static_cast<std::uint8_t>(b & kVertexBit);
      const auto notSurface = static_cast<std::uint8_t>(isSurface - 1);      // 0xFF or 0
      const auto inside = static_cast<std::uint8_t>(vote & 2 & notSurface);  // two votes or three
      const std::uint8_t v0 = value(isSurface, inside, d0[x], keep0);
      const std::uint8_t v1 = value(isEdge, inside, d1[x], keep1);
      const std::uint8_t v2 = value(isVertex, inside, d2[x], keep2);
      words[x] = VoxelWord{v0} | (VoxelWord{v1} << shift) | (VoxelWord{v2} << (2 * shift));
      interior += v0 == kValueInterior;
      surface += v0 == kValueFeature;
      distant += v0 > kValueFeature;
      edges += isEdge;
      vertices += isVertex;
      vertexPoints += (b & (kSurfaceBit | kVertexBit)) == (kSurfaceBit | kVertexBit);
      edgePoints += (b & (kSurfaceBit | kEdgeBit | kVertexBit)) == (kSurfaceBit | kEdgeBit);
      surfacePoints += (b & (kSurfaceBit | kEdgeBit | kVertexBit)) == kSurfaceBit;
      disagreements += static_cast<std::uint8_t>((vote == 1 || vote == 2) ? notSurface & 1 : 0);
    }
    stats.interiorVoxels += interior;
    stats.surfaceVoxels += surface;
    stats.distanceVoxels += distant;
    stats.edgeVoxels += edges / kEdgeBit;
    stats.vertexVoxels += vertices / kVertexBit;
    stats.vertexPoints += vertexPoints;
    stats.edgePoints += edgePoints;
    stats.surfacePoints += surfacePoints;
    stats.voteDisagreements += disagreements;
  }

  /// Copies into `bits` (n³, x fastest) the feature bytes of the voxels [lo, lo + n).
  void gatherBits(const glm::ivec3& lo, int n, std::vector<std::uint8_t>& bits) const {
    bits.assign(volume3(n, n, n), 0);
    const glm::ivec3 chunkLo = lo >> kChunkEdgeLog2;
    const glm::ivec3 chunkHi = (lo + n - 1) >> kChunkEdgeLog2;
    for (int cz = chunkLo.z; cz <= chunkHi.z; ++cz) {
      for (int cy = chunkLo.y; cy <= chunkHi.y; ++cy) {
        for (int cx = chunkLo.x; cx <= chunkHi.x; ++cx) {
          const auto* block = features_.find({cx, cy, cz});
          if (!block) continue;
          // the part of the chunk inside the box, copied row by row
          const glm::ivec3 base = glm::ivec3(cx, cy, cz) * kChunkEdgeVoxels;
          const glm::ivec3 from = glm::max(base, lo);
          const glm::ivec3 to = glm::min(base + kChunkEdgeVoxels, lo + n);
          for (int z = from.z; z < to.z; ++z) {
            for (int y = from.y; y < to.y; ++y) {
              const std::uint8_t* src = block->data() + voxelInChunk({from.x, y, z});
              std::copy(src, src + (to.x - from.x), &bits[at3(from.x - lo.x, y - lo.y, z - lo.z, n, n)]);
            }
          }
        }
      }
    }
  }

  /// Splits the hyperchunk's words into chunks; uniform chunks become one word.
  void packChunks(const std::vector<VoxelWord>& words, HyperResult& result) const {
    const int c = kHyperEdgeVoxels;
    const int e = kChunkEdgeVoxels;
    const std::size_t bytesPerWord = static_cast<std::size_t>(options_.encoding.bytesPerWord());
    const std::size_t blockBytes = bytesPerWord * kVoxelsPerChunk;
    result.chunkEntries.assign(kChunksPerHyper, 0);
    result.uniform = true;
    result.uniformWord = words[0];
    VoxelWord chunkWords[kVoxelsPerChunk];
    const VoxelWord surfaceMask = options_.encoding.fieldMask();
    for (int cz = 0; cz < kHyperEdgeChunks; ++cz) {
      for (int cy = 0; cy < kHyperEdgeChunks; ++cy) {
        for (int cx = 0; cx < kHyperEdgeChunks; ++cx) {
          for (int z = 0; z < e; ++z) {
            for (int y = 0; y < e; ++y) {
              const VoxelWord* row = &words[at3(cx * e, cy * e + y, cz * e + z, c, c)];
              std::copy(row, row + e, &chunkWords[voxelInChunk({0, y, z})]);
            }
          }
          VoxelWord differs = 0;
          VoxelWord bearing = 0;
          for (VoxelWord w : chunkWords) {
            differs |= w ^ chunkWords[0];
            bearing |= w & surfaceMask;
          }
          const std::uint32_t chunkIndex = chunkInHyper({cx, cy, cz});
          if (bearing) result.bearing[chunkIndex / 64] |= std::uint64_t{1} << (chunkIndex % 64);
          std::uint32_t& entry = result.chunkEntries[chunkIndex];
          if (!differs) {
            entry = Voxmap::kUniform | chunkWords[0];
            result.uniform = result.uniform && chunkWords[0] == result.uniformWord;
            continue;
          }
          result.uniform = false;
          entry = static_cast<std::uint32_t>(result.blocks.size() / blockBytes);
          // the words' low bytes, as the voxmap reads them
          static_assert(std::endian::native == std::endian::little);
          const std::size_t at = result.blocks.size();
          result.blocks.resize(at + blockBytes);
          for (std::size_t i = 0; i < kVoxelsPerChunk; ++i) {
            std::memcpy(&result.blocks[at + i * bytesPerWord], &chunkWords[i], bytesPerWord);
          }
        }
      }
    }
    if (result.uniform) {
      result.chunkEntries.clear();
      result.blocks.clear();
    }
  }

  const VoxelGrid& grid_;
  const VoxelizeOptions& options_;
  const HyperchunkBlocks<std::uint8_t>& features_;
  const InteriorClassifier& interior_;
};

/// Coordinates of hyperchunk `h` of a grid of `dimsHyper` hyperchunks (x fastest).
glm::ivec3 hyperCoordinates(std::size_t h, const glm::ivec3& dimsHyper) {
  const auto nx = static_cast<std::size_t>(dimsHyper.x);
  const auto ny = static_cast<std::size_t>(dimsHyper.y);
  return {static_cast<int>(h % nx), static_cast<int>((h / nx) % ny), static_cast<int>(h / (nx * ny))};
}

/// Marks in `chunkField` (the grid's chunks, x fastest) with 0 the chunks of hyperchunk
/// `ijkHyper` that hold a voxel whose surface field is not far.
void markBearingChunks(const HyperResult& r, const glm::ivec3& ijkHyper, const glm::ivec3& dimsChunks,
                       VoxelWord surfaceMask, std::vector<std::uint8_t>& chunkField) {
  const bool uniformBearing = (r.uniformWord & surfaceMask) != 0;
  if (r.uniform && !uniformBearing) return;
  for (int c = 0; c < kChunksPerHyper; ++c) {
    const glm::ivec3 local(c & (kHyperEdgeChunks - 1), (c >> kHyperEdgeLog2) & (kHyperEdgeChunks - 1),
                           c >> (2 * kHyperEdgeLog2));
    const auto bit = static_cast<std::uint32_t>(c);
    const bool bearing = r.uniform ? uniformBearing : ((r.bearing[bit / 64] >> (bit % 64)) & 1u) != 0;
    if (!bearing) continue;
    const glm::ivec3 v = ijkHyper * kHyperEdgeChunks + local;
    chunkField[at3(v.x, v.y, v.z, dimsChunks.x, dimsChunks.y)] = 0;
  }
}

double surfaceArea(std::span<const TriangleMesh* const> meshes) {
  double area = 0.0;
  for (const TriangleMesh* mesh : meshes) {
    for (const glm::uvec3& t : mesh->triangles) {
      const glm::dvec3 a(mesh->positionsWorld[t.x]);
      area += 0.5 * glm::length(glm::cross(glm::dvec3(mesh->positionsWorld[t.y]) - a,
                                           glm::dvec3(mesh->positionsWorld[t.z]) - a));
    }
  }
  return area;
}

}  // namespace

VoxelGrid gridAround(const Bounds& boundsLocal, double voxelSizeM, int paddingVoxels) {
  VoxelGrid grid;
  grid.voxelSizeM = voxelSizeM;
  const glm::dvec3 lo = glm::floor(boundsLocal.min / voxelSizeM) - double(paddingVoxels);
  const glm::dvec3 hi = glm::floor(boundsLocal.max / voxelSizeM) + double(paddingVoxels + 1);
  grid.originLocal = lo * voxelSizeM;
  const glm::dvec3 hypers = glm::ceil((hi - lo) / double(kHyperEdgeVoxels));
  grid.dimsHyper = glm::ivec3(hypers);
  return grid;
}

VoxelizeEstimate estimateVoxelizeBytes(std::span<const TriangleMesh* const> meshes, const VoxelGrid& grid,
                                       const VoxelizeOptions& options, std::uint64_t budgetBytes) {
  const double s = options.voxelSizeM;
  // per surface chunk: its feature bits; per mixed chunk: its words twice (the
  // hyperchunks' and the assembled array), and its planes' index
  const double featureBytesPerChunk = kVoxelsPerChunk;
  const double planeIndexBytesPerChunk =
      SparseSurfacePlanes::kMasksPerChunk * (sizeof(std::uint64_t) + sizeof(std::uint32_t));
  const double mixedBytesPerChunk = kVoxelsPerChunk * 2.0 * options.encoding.bytesPerWord() +
                                    (options.surfacePlanes ? planeIndexBytesPerChunk : 0.0);
  const int reachChunks = (options.encoding.rangeVoxels + kChunkEdgeVoxels - 1) / kChunkEdgeVoxels;
  const auto mostSurfaceChunks =
      static_cast<std::uint64_t>(double(budgetBytes) / (featureBytesPerChunk + mixedBytesPerChunk));
  const ChunkFootprint chunks = chunkFootprint(meshes, grid, reachChunks, mostSurfaceChunks);
  const double area = surfaceArea(meshes);
  const double crossingBytes = 3.0 * 1.2 * area / (s * s) * 8.0;
  // planes fill a band about six voxels thick (two layers out, two in, the surface
  // voxels between); the landing gear has 4.3 to 4.6 per A/s² at 2.5 to 1 mm voxels
  const double planeBytes =
      options.surfacePlanes ? std::min(6.0 * area / (s * s), double(chunks.mixedChunks) * kVoxelsPerChunk) *
                                  (sizeof(SurfacePlane) + 1)  // and its convex sides
                            : 0.0;
  std::uint64_t triangles = 0;
  for (const TriangleMesh* mesh : meshes) triangles += mesh->triangles.size();
  const double meshBytes = static_cast<double>(triangles) * 200.0;
  const double bytes = double(chunks.surfaceChunks) * featureBytesPerChunk +
                       double(chunks.mixedChunks) * mixedBytesPerChunk + crossingBytes + planeBytes +
                       meshBytes;
  return {static_cast<std::uint64_t>(bytes), !chunks.complete};
}

void checkVoxelizeOptions(const VoxelizeOptions& options) {
  if (!(options.voxelSizeM > 0.0) || !std::isfinite(options.voxelSizeM)) {
    throw Error("voxel size must be a positive number of metres, not " + std::to_string(options.voxelSizeM));
  }
  if (!options.encoding.valid() || options.encoding.rangeVoxels > kLargestRange) {
    throw Error("distance fields of " + std::to_string(options.encoding.bitsPerField) + " bits with range " +
                std::to_string(options.encoding.rangeVoxels) +
                " are not supported (2, 4 or 8 bits, range 1 … 16)");
  }
}

VoxelizedObject voxelize(std::span<const TriangleMesh* const> meshes, std::span<const MeshFeatures> features,
                         const VoxelizeOptions& options, const ProgressFn& progress) {
  checkVoxelizeOptions(options);
  Bounds bounds;
  std::uint64_t triangles = 0;
  for (const TriangleMesh* mesh : meshes) {
    triangles += mesh->triangles.size();
    for (const glm::uvec3& t : mesh->triangles) {
      for (int k = 0; k < 3; ++k) bounds.add(glm::dvec3(mesh->positionsWorld[t[k]]));
    }
  }
  if (bounds.empty()) throw Error("nothing to voxelize: no triangles");
  const glm::dvec3 extent = bounds.extent();
  const double longestVoxels = std::max({extent.x, extent.y, extent.z}) / options.voxelSizeM;
  if (longestVoxels > double(1 << 24)) {
    throw Error("voxel size " + std::to_string(options.voxelSizeM * 1e3) + " mm makes " +
                std::to_string(static_cast<long long>(longestVoxels)) +
                " voxels along one axis (at most 16777216)");
  }
  const VoxelGrid grid = gridAround(bounds, options.voxelSizeM, options.encoding.rangeVoxels + 1);
  const std::uint64_t budget =
      options.memoryBudgetBytes ? options.memoryBudgetBytes : physicalMemoryBytes() / 4 * 3;
  const VoxelizeEstimate estimate = estimateVoxelizeBytes(meshes, grid, options, budget);
  if (estimate.bytes > budget) {
    throw Error("voxel size " + std::to_string(options.voxelSizeM * 1e3) + " mm would need " +
                (estimate.lowerBound ? "more than " : "about ") + gib(estimate.bytes) +
                " to voxelize (budget " + gib(budget) + "); choose a larger voxel size");
  }

  auto stage = [&](double begin, double end) -> ProgressFn {
    if (!progress) return {};
    return [&progress, begin, end](double f) { progress(begin + (end - begin) * f); };
  };
  std::vector<FeatureGeometry> geometry;
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    geometry.push_back(
        {meshes[i], options.buildFeatureFields && i < features.size() ? &features[i] : nullptr});
  }
  const HyperchunkBlocks<std::uint8_t> featureBits =
      rasterizeFeatures(grid, geometry, options.threads, stage(0.0, 0.3));
  const EmbreeScene scene(meshes);
  const InteriorClassifier interior(grid, meshes, scene, options.threads);
  if (progress) progress(0.5);

  const Voxelizer voxelizer(grid, options, featureBits, interior);
  const std::size_t hyperCount = featureBits.hyperCount();
  std::vector<HyperResult> results(hyperCount);
  const glm::ivec3 dims = grid.dimsHyper;
  parallelFor(
      hyperCount, options.threads,
      [&](std::size_t h) {
        thread_local std::unique_ptr<HyperchunkTransform> transform;
        thread_local Voxelizer::Scratch scratch;
        if (!transform || transform->range() != options.encoding.rangeVoxels) {
          transform = std::make_unique<HyperchunkTransform>(options.encoding.rangeVoxels);
        }
        results[h] = voxelizer.build(hyperCoordinates(h, dims), *transform, scratch);
      },
      stage(0.5, options.surfacePlanes ? 0.7 : 0.95));

  // assemble in hyperchunk order, so the arrays do not depend on scheduling
  VoxelizeStats stats;
  const VoxelWord surfaceMask = options.encoding.fieldMask();
  const glm::ivec3 dimsChunks = grid.dimsChunks();
  // every chunk starts as a non-source of the chunk-level transform
  std::vector<std::uint8_t> chunkDistances(static_cast<std::size_t>(dimsChunks.x) *
                                               static_cast<std::size_t>(dimsChunks.y) *
                                               static_cast<std::size_t>(dimsChunks.z),
                                           kChunkDistanceCap);
  std::vector<std::uint32_t> hyper(hyperCount);
  std::vector<std::uint32_t> chunks;
  std::vector<std::uint8_t> voxelBytes;
  // sized once (with the voxmap's read padding), so that nothing is copied twice
  std::size_t chunkEntryCount = 0;
  std::size_t voxelByteCount = 0;
  for (const HyperResult& r : results) {
    chunkEntryCount += r.chunkEntries.size();
    voxelByteCount += r.blocks.size();
  }
  chunks.reserve(chunkEntryCount);
  voxelBytes.reserve(voxelByteCount + Voxmap::kPadBytes);
  const std::size_t blockBytes = static_cast<std::size_t>(options.encoding.bytesPerWord()) * kVoxelsPerChunk;
  for (std::size_t h = 0; h < hyperCount; ++h) {
    HyperResult& r = results[h];
    stats.interiorVoxels += r.stats.interiorVoxels;
    stats.surfaceVoxels += r.stats.surfaceVoxels;
    stats.distanceVoxels += r.stats.distanceVoxels;
    stats.edgeVoxels += r.stats.edgeVoxels;
    stats.vertexVoxels += r.stats.vertexVoxels;
    stats.voteDisagreements += r.stats.voteDisagreements;
    stats.vertexPoints += r.stats.vertexPoints;
    stats.edgePoints += r.stats.edgePoints;
    stats.surfacePoints += r.stats.surfacePoints;
    if (!stats.firstDisagreementLocal) stats.firstDisagreementLocal = r.stats.firstDisagreementLocal;
    markBearingChunks(r, hyperCoordinates(h, dims), dims * kHyperEdgeChunks, surfaceMask, chunkDistances);
    if (r.uniform) {
      hyper[h] = Voxmap::kUniform | r.uniformWord;
      continue;
    }
    hyper[h] = static_cast<std::uint32_t>(chunks.size() / kChunksPerHyper);
    const auto firstBlock = static_cast<std::uint32_t>(voxelBytes.size() / blockBytes);
    for (std::uint32_t entry : r.chunkEntries)
      chunks.push_back((entry & Voxmap::kUniform) ? entry : entry + firstBlock);
    voxelBytes.insert(voxelBytes.end(), r.blocks.begin(), r.blocks.end());
    r = HyperResult{};
  }
  chessboardChunkTransform(chunkDistances, dimsChunks, options.threads);
  stats.triangles = triangles;
  for (const MeshFeatures& f : features) stats.polygonsAfterMerge += f.polygonCount;
  VoxelizedObject out{Voxmap(grid, options.encoding, std::move(hyper), std::move(chunks),
                             std::move(voxelBytes), std::move(chunkDistances)),
                      stats};
  if (options.surfacePlanes)
    out.voxmap.setSurfacePlanes(
        computeSurfacePlanes(out.voxmap, meshes, scene, options.threads, stage(0.7, 1.0)), options.threads);
  if (progress) progress(1.0);
  return out;
}

}  // namespace voxhap
