#include "haptics/voxel/voxelizer.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "haptics/core/error.h"
#include "haptics/core/parallel.h"
#include "haptics/geometry/embree_scene.h"
#include "haptics/voxel/chunk_distance.h"
#include "haptics/voxel/feature_rasterizer.h"
#include "haptics/voxel/interior_classifier.h"

namespace voxhap {
namespace {

constexpr int kLargestRange = 16;  // voxels; the halo of a hyperchunk's distance transform

/// Index of (x, y, z) in a box of nx × ny × … elements, x fastest; all arguments ≥ 0.
std::size_t at3(int x, int y, int z, int nx, int ny) {
  return static_cast<std::size_t>(x) +
         static_cast<std::size_t>(nx) * (static_cast<std::size_t>(y) + static_cast<std::size_t>(ny) * static_cast<std::size_t>(z));
}

/// Number of elements of a box nx × ny × nz.
std::size_t volume3(int nx, int ny, int nz) { return at3(0, 0, nz, nx, ny); }

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
  std::vector<std::uint32_t> chunkEntries;  // kUniform | word, or index into blocks
  std::vector<std::uint8_t> blocks;         // packed words of the mixed chunks
  std::array<std::uint64_t, kChunksPerHyper / 64> bearing{};  // bit per chunk: a surface field not far
  VoxelizeStats stats;                      // voxel counts and votes only
};

/// Chessboard distance transforms of one hyperchunk and its halo. Each field's
/// distance is capped at range + 1 ("far"). Buffers are reused across hyperchunks.
class HyperchunkTransform {
public:
  explicit HyperchunkTransform(int range) : range_(range), n_(kHyperEdgeVoxels + 2 * range) {}

  /// `sources` holds N³ flags (x fastest), N = 64 + 2·range; writes 64³ distances.
  void run(const std::vector<std::uint8_t>& sources, std::vector<std::uint8_t>& out) {
    const int c = kHyperEdgeVoxels;
    const int n = n_;
    const int r = range_;
    const std::uint8_t far = static_cast<std::uint8_t>(r + 1);
    // x: distance along the row to the nearest source, kept for the core columns only
    a_.assign(volume3(c, n, n), far);
    for (int z = 0; z < n; ++z) {
      for (int y = 0; y < n; ++y) {
        const std::uint8_t* row = &sources[at3(0, y, z, n, n)];
        std::uint8_t* outRow = &a_[at3(0, y, z, c, n)];
        int last = -1000;
        for (int x = 0; x < n; ++x) {
          if (row[x]) last = x;
          if (x >= r && x < r + c) outRow[x - r] = static_cast<std::uint8_t>(std::min(x - last, r + 1));
        }
        last = 1000 + n;
        for (int x = n - 1; x >= r; --x) {
          if (row[x]) last = x;
          if (x < r + c) {
            std::uint8_t& d = outRow[x - r];
            d = std::min(d, static_cast<std::uint8_t>(std::min(last - x, r + 1)));
          }
        }
      }
    }
    // y, then z: out = min over |k| ≤ r of max(|k|, in shifted by k)
    b_.assign(volume3(c, c, n), far);
    for (int z = 0; z < n; ++z) {
      for (int y = 0; y < c; ++y) {
        std::uint8_t* outRow = &b_[at3(0, y, z, c, c)];
        for (int k = -r; k <= r; ++k) {
          const std::uint8_t* in = &a_[at3(0, y + r + k, z, c, n)];
          const std::uint8_t shift = static_cast<std::uint8_t>(k < 0 ? -k : k);
          for (int x = 0; x < c; ++x) outRow[x] = std::min(outRow[x], std::max(shift, in[x]));
        }
      }
    }
    out.assign(volume3(c, c, c), far);
    for (int z = 0; z < c; ++z) {
      for (int k = -r; k <= r; ++k) {
        const std::uint8_t shift = static_cast<std::uint8_t>(k < 0 ? -k : k);
        const std::uint8_t* in = &b_[at3(0, 0, z + r + k, c, c)];
        std::uint8_t* outLayer = &out[at3(0, 0, z, c, c)];
        for (int i = 0; i < c * c; ++i) outLayer[i] = std::min(outLayer[i], std::max(shift, in[i]));
      }
    }
  }

  int haloSize() const { return n_; }

private:
  int range_;
  int n_;
  std::vector<std::uint8_t> a_;
  std::vector<std::uint8_t> b_;
};

class Voxelizer {
public:
  Voxelizer(const VoxelGrid& grid, const VoxelizeOptions& options, const HyperchunkBlocks<std::uint8_t>& features,
            const InteriorClassifier& interior)
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

  HyperResult build(const glm::ivec3& ijkHyper, HyperchunkTransform& transform) const {
    HyperResult result;
    const VoxelEncoding& enc = options_.encoding;
    const glm::ivec3 core = ijkHyper * kHyperEdgeVoxels;
    std::vector<std::uint8_t> votes;
    if (!nearFeatures(ijkHyper)) {
      // no surface within range: every voxel is inside, or every voxel is far
      interior_.votes(core + kHyperEdgeVoxels / 2, glm::ivec3(1), votes);
      const bool inside = votes[0] >= 2;
      result.uniformWord = inside ? enc.pack(kValueInterior, kValueInterior, kValueInterior) : 0;
      if (inside) result.stats.interiorVoxels = std::uint64_t{kHyperEdgeVoxels} * kHyperEdgeVoxels * kHyperEdgeVoxels;
      return result;
    }

    const int r = enc.rangeVoxels;
    const int n = transform.haloSize();
    const int c = kHyperEdgeVoxels;
    const glm::ivec3 haloLo = core - r;
    std::uint8_t bitsHere[kFieldCount] = {kSurfaceBit, kEdgeBit, kVertexBit};
    const int fields = options_.buildFeatureFields ? kFieldCount : 1;
    std::vector<std::uint8_t> sources(volume3(n, n, n));
    std::vector<std::uint8_t> distance[kFieldCount];
    for (int f = 0; f < fields; ++f) {
      gatherSources(haloLo, n, bitsHere[f], sources);
      transform.run(sources, distance[f]);
    }
    interior_.votes(core, glm::ivec3(c), votes);

    std::vector<VoxelWord> words(volume3(c, c, c));
    const std::uint8_t* block = nullptr;  // feature bits of the current chunk
    for (int z = 0; z < c; ++z) {
      for (int y = 0; y < c; ++y) {
        for (int x = 0; x < c; ++x) {
          const std::size_t i = at3(x, y, z, c, c);
          const glm::ivec3 v = core + glm::ivec3(x, y, z);
          if ((x & (kChunkEdgeVoxels - 1)) == 0) {
            const auto* found = features_.find(v >> kChunkEdgeLog2);
            block = found ? found->data() : nullptr;
          }
          const std::uint8_t bits = block ? block[voxelInChunk(v)] : 0;
          const bool surface = bits & kSurfaceBit;
          const bool inside = !surface && votes[i] >= 2;
          if (!surface && votes[i] != 0 && votes[i] != 3) {
            ++result.stats.voteDisagreements;
            if (!result.stats.firstDisagreementLocal) result.stats.firstDisagreementLocal = grid_.voxelCentre(v);
          }
          std::uint8_t value[kFieldCount] = {kValueFar, kValueFar, kValueFar};
          for (int f = 0; f < fields; ++f) {
            if (bits & bitsHere[f]) {
              value[f] = kValueFeature;
            } else if (inside) {
              value[f] = kValueInterior;
            } else if (distance[f][i] <= r) {
              value[f] = distanceValue(distance[f][i]);
            }
          }
          words[i] = enc.pack(value[0], value[1], value[2]);
          result.stats.edgeVoxels += (bits & kEdgeBit) ? 1 : 0;
          result.stats.vertexVoxels += (bits & kVertexBit) ? 1 : 0;
          if (bits & kSurfaceBit) {
            result.stats.vertexPoints += (bits & kVertexBit) ? 1 : 0;
            result.stats.edgePoints += (bits & kVertexBit) == 0 && (bits & kEdgeBit) ? 1 : 0;
            result.stats.surfacePoints += (bits & (kVertexBit | kEdgeBit)) ? 0 : 1;
          }
          if (value[0] == kValueInterior) {
            ++result.stats.interiorVoxels;
          } else if (value[0] == kValueFeature) {
            ++result.stats.surfaceVoxels;
          } else if (value[0] != kValueFar) {
            ++result.stats.distanceVoxels;
          }
        }
      }
    }
    packChunks(words, result);
    return result;
  }

private:
  /// Flags in `sources` (n³, from `lo`) the voxels whose feature byte has `bit`.
  void gatherSources(const glm::ivec3& lo, int n, std::uint8_t bit, std::vector<std::uint8_t>& sources) const {
    std::fill(sources.begin(), sources.end(), std::uint8_t{0});
    const glm::ivec3 chunkLo = lo >> kChunkEdgeLog2;
    const glm::ivec3 chunkHi = (lo + n - 1) >> kChunkEdgeLog2;
    for (int cz = chunkLo.z; cz <= chunkHi.z; ++cz) {
      for (int cy = chunkLo.y; cy <= chunkHi.y; ++cy) {
        for (int cx = chunkLo.x; cx <= chunkHi.x; ++cx) {
          const auto* block = features_.find({cx, cy, cz});
          if (!block) continue;
          const glm::ivec3 base = glm::ivec3(cx, cy, cz) * kChunkEdgeVoxels;
          for (int i = 0; i < kVoxelsPerChunk; ++i) {
            if (!((*block)[static_cast<std::size_t>(i)] & bit)) continue;
            const glm::ivec3 v = base + glm::ivec3(i & 7, (i >> 3) & 7, i >> 6) - lo;
            if (v.x < 0 || v.y < 0 || v.z < 0 || v.x >= n || v.y >= n || v.z >= n) continue;
            sources[at3(v.x, v.y, v.z, n, n)] = 1;
          }
        }
      }
    }
  }

  /// Splits the hyperchunk's words into chunks; uniform chunks become one word.
  void packChunks(const std::vector<VoxelWord>& words, HyperResult& result) const {
    const int c = kHyperEdgeVoxels;
    const std::size_t bytesPerWord = static_cast<std::size_t>(options_.encoding.bytesPerWord());
    result.chunkEntries.assign(kChunksPerHyper, 0);
    result.uniform = true;
    result.uniformWord = words[0];
    VoxelWord chunkWords[kVoxelsPerChunk];
    const VoxelWord surfaceMask = options_.encoding.fieldMask();
    for (int cz = 0; cz < kHyperEdgeChunks; ++cz) {
      for (int cy = 0; cy < kHyperEdgeChunks; ++cy) {
        for (int cx = 0; cx < kHyperEdgeChunks; ++cx) {
          bool chunkUniform = true;
          bool bearing = false;
          for (int i = 0; i < kVoxelsPerChunk; ++i) {
            const glm::ivec3 v = glm::ivec3(cx, cy, cz) * kChunkEdgeVoxels + glm::ivec3(i & 7, (i >> 3) & 7, i >> 6);
            chunkWords[i] = words[at3(v.x, v.y, v.z, c, c)];
            chunkUniform = chunkUniform && chunkWords[i] == chunkWords[0];
            bearing = bearing || (chunkWords[i] & surfaceMask) != 0;
          }
          const std::uint32_t chunkIndex = chunkInHyper({cx, cy, cz});
          if (bearing) result.bearing[chunkIndex / 64] |= std::uint64_t{1} << (chunkIndex % 64);
          std::uint32_t& entry = result.chunkEntries[chunkIndex];
          if (chunkUniform) {
            entry = Voxmap::kUniform | chunkWords[0];
            result.uniform = result.uniform && chunkWords[0] == result.uniformWord;
            continue;
          }
          result.uniform = false;
          entry = static_cast<std::uint32_t>(result.blocks.size() / (bytesPerWord * kVoxelsPerChunk));
          for (VoxelWord w : chunkWords) {
            for (std::size_t b = 0; b < bytesPerWord; ++b) result.blocks.push_back(static_cast<std::uint8_t>(w >> (8 * b)));
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

std::uint64_t estimateVoxelizeBytes(double surfaceAreaM2, std::uint64_t triangles, const VoxelizeOptions& options) {
  const double s = options.voxelSizeM;
  const double chunkM = s * kChunkEdgeVoxels;
  // chunks the surface passes through (a tilted surface meets up to ~√3 times more)
  const double surfaceChunks = 1.8 * surfaceAreaM2 / (chunkM * chunkM) + 0.5 * static_cast<double>(triangles);
  // mixed chunks: the surface's and one chunk of distance field on each side
  const double mixedChunks = 3.0 * surfaceChunks;
  const double featureBytes = surfaceChunks * kVoxelsPerChunk;
  const double voxmapBytes = mixedChunks * kVoxelsPerChunk * options.encoding.bytesPerWord();
  const double crossingBytes = 3.0 * 1.2 * surfaceAreaM2 / (s * s) * 8.0;
  const double meshBytes = static_cast<double>(triangles) * 200.0;
  return static_cast<std::uint64_t>(featureBytes + 2.0 * voxmapBytes + crossingBytes + meshBytes);
}

void checkVoxelizeOptions(const VoxelizeOptions& options) {
  if (!(options.voxelSizeM > 0.0) || !std::isfinite(options.voxelSizeM)) {
    throw Error("voxel size must be a positive number of metres, not " + std::to_string(options.voxelSizeM));
  }
  if (!options.encoding.valid() || options.encoding.rangeVoxels > kLargestRange) {
    throw Error("distance fields of " + std::to_string(options.encoding.bitsPerField) + " bits with range " +
                std::to_string(options.encoding.rangeVoxels) + " are not supported (2, 4 or 8 bits, range 1 … 16)");
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
                std::to_string(static_cast<long long>(longestVoxels)) + " voxels along one axis (at most 16777216)");
  }
  const std::uint64_t budget = options.memoryBudgetBytes ? options.memoryBudgetBytes : physicalMemoryBytes() / 4 * 3;
  const std::uint64_t estimate = estimateVoxelizeBytes(surfaceArea(meshes), triangles, options);
  if (estimate > budget) {
    throw Error("voxel size " + std::to_string(options.voxelSizeM * 1e3) + " mm would need about " + gib(estimate) +
                " to voxelize (budget " + gib(budget) + "); choose a larger voxel size");
  }

  auto stage = [&](double begin, double end) -> ProgressFn {
    if (!progress) return {};
    return [&progress, begin, end](double f) { progress(begin + (end - begin) * f); };
  };
  const VoxelGrid grid = gridAround(bounds, options.voxelSizeM, options.encoding.rangeVoxels + 1);

  std::vector<FeatureGeometry> geometry;
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    geometry.push_back({meshes[i], options.buildFeatureFields && i < features.size() ? &features[i] : nullptr});
  }
  const HyperchunkBlocks<std::uint8_t> featureBits = rasterizeFeatures(grid, geometry, options.threads, stage(0.0, 0.3));
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
        if (!transform || transform->haloSize() != kHyperEdgeVoxels + 2 * options.encoding.rangeVoxels) {
          transform = std::make_unique<HyperchunkTransform>(options.encoding.rangeVoxels);
        }
        results[h] = voxelizer.build(hyperCoordinates(h, dims), *transform);
      },
      stage(0.5, 0.95));

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
    for (std::uint32_t entry : r.chunkEntries) chunks.push_back((entry & Voxmap::kUniform) ? entry : entry + firstBlock);
    voxelBytes.insert(voxelBytes.end(), r.blocks.begin(), r.blocks.end());
    r = HyperResult{};
  }
  chessboardChunkTransform(chunkDistances, dimsChunks);
  stats.triangles = triangles;
  for (const MeshFeatures& f : features) stats.polygonsAfterMerge += f.polygonCount;
  if (progress) progress(1.0);
  return {Voxmap(grid, options.encoding, std::move(hyper), std::move(chunks), std::move(voxelBytes),
                 std::move(chunkDistances)),
          stats};
}

}  // namespace voxhap
