#include "haptics/pointshell/pointshell.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <unordered_map>

#include <glm/geometric.hpp>

#include "haptics/core/error.h"
#include "haptics/core/parallel.h"
#include "haptics/geometry/embree_scene.h"
#include "haptics/geometry/pseudo_normals.h"
#include "haptics/voxel/feature_rasterizer.h"
#include "haptics/voxel/voxelizer.h"

namespace voxhap {
namespace {

/// A closest point this close to an edge or vertex (in voxels) takes its pseudo-normal.
constexpr double kFeatureTolerance = 1e-6;

/// Normals and points of the feature vertices and feature edges, by the voxels they pass
/// through: a vertex or edge point pushes along its feature's normal, the same at every
/// corner of a box whatever the lattice, rather than along the normal of whichever face
/// lies nearest to its voxel's centre; a point on the surface lies on its voxel's feature.
class FeatureVoxels {
public:
  FeatureVoxels(const VoxelGrid& grid, std::span<const MeshFeatures> features, const PseudoNormals& normals)
      : grid_(grid) {
    for (std::size_t part = 0; part < features.size(); ++part) {
      for (const glm::vec3& vertex : features[part].featureVertices) {
        const glm::dvec3 v(vertex);
        const auto n = normals.vertexNormal(part, vertex);
        forVoxelsHolding(v, [&](const glm::ivec3& voxel) {
          if (n) vertices_[key(voxel)] += *n;
          keepNearest(vertexPoints_, voxel, v);
        });
      }
      for (const auto& [a, b] : features[part].featureEdges) {
        const auto n = normals.edgeNormal(part, a, b);
        if (!n) continue;
        const glm::dvec3 from(a);
        const glm::dvec3 along = glm::dvec3(b) - from;
        // samples a quarter voxel apart: each voxel's sum weighs its edges by length inside
        const int steps = 1 + static_cast<int>(std::ceil(4.0 * glm::length(along) / grid.voxelSizeM));
        for (int k = 0; k <= steps; ++k) {
          forVoxelsHolding(from + along * (static_cast<double>(k) / steps), [&](const glm::ivec3& voxel) {
            edges_[key(voxel)] += *n;
            const double lengthSq = glm::dot(along, along);
            const double t =
                std::clamp(glm::dot(grid_.voxelCentre(voxel) - from, along) / lengthSq, 0.0, 1.0);
            keepNearest(edgePoints_, voxel, from + t * along);
          });
        }
      }
    }
  }

  /// The normal of the point of voxel `v` labelled `feature`, if its feature was found.
  std::optional<glm::dvec3> normalOf(const glm::ivec3& v, PointFeature feature) const {
    const auto* found = find(feature == PointFeature::Vertex ? vertices_ : edges_, v, feature);
    if (!found || glm::length(*found) == 0.0) return std::nullopt;
    return glm::normalize(*found);
  }

  /// The point of the feature of voxel `v` labelled `feature` nearest its centre (the
  /// vertex, or the nearest point of its edges), if its feature was found.
  std::optional<glm::dvec3> pointOf(const glm::ivec3& v, PointFeature feature) const {
    const auto* found = find(feature == PointFeature::Vertex ? vertexPoints_ : edgePoints_, v, feature);
    if (!found) return std::nullopt;
    return *found;
  }

private:
  using Map = std::unordered_map<std::uint64_t, glm::dvec3>;
  static std::uint64_t key(const glm::ivec3& v) {
    return (static_cast<std::uint64_t>(v.x) << 42) | (static_cast<std::uint64_t>(v.y) << 21) |
           static_cast<std::uint64_t>(v.z);
  }
  const glm::dvec3* find(const Map& map, const glm::ivec3& v, PointFeature feature) const {
    if (feature == PointFeature::Surface || !grid_.containsVoxel(v)) return nullptr;
    const auto it = map.find(key(v));
    return it == map.end() ? nullptr : &it->second;
  }
  /// Calls `visit` with every voxel whose closed box holds `pointLocal`: a feature on a
  /// voxel boundary belongs to the voxels on both sides, as the rasterizer marks both.
  template <typename Visit>
  void forVoxelsHolding(const glm::dvec3& pointLocal, Visit&& visit) const {
    const double eps = 1e-6 * grid_.voxelSizeM;
    const glm::ivec3 lo = grid_.voxelOf(pointLocal - eps);
    const glm::ivec3 hi = grid_.voxelOf(pointLocal + eps);
    for (int z = lo.z; z <= hi.z; ++z) {
      for (int y = lo.y; y <= hi.y; ++y) {
        for (int x = lo.x; x <= hi.x; ++x) {
          if (grid_.containsVoxel({x, y, z})) visit(glm::ivec3(x, y, z));
        }
      }
    }
  }
  /// Keeps `q` as voxel `v`'s point if it is nearer the voxel's centre than the one kept.
  void keepNearest(Map& map, const glm::ivec3& v, const glm::dvec3& q) const {
    const auto [it, added] = map.try_emplace(key(v), q);
    const glm::dvec3 centre = grid_.voxelCentre(v);
    if (!added && glm::length(q - centre) < glm::length(it->second - centre)) it->second = q;
  }

  const VoxelGrid& grid_;
  Map vertices_;      ///< per voxel, the sum of its feature vertices' normals
  Map edges_;         ///< per voxel, the sum of its feature edges' normals, by length
  Map vertexPoints_;  ///< per voxel, the feature vertex nearest its centre
  Map edgePoints_;    ///< per voxel, the point of its feature edges nearest its centre
};

/// The voxels of the free-space layer `layer` around `meshes` (surface field value
/// 2 + layer), marked with kSurfaceBit, on the grid of their voxmap.
HyperchunkBlocks<std::uint8_t> freeLayerBits(std::span<const TriangleMesh* const> meshes, double voxelSizeM,
                                             int layer, int threads, VoxelGrid& grid) {
  VoxelizeOptions options;
  options.voxelSizeM = voxelSizeM;
  options.buildFeatureFields = false;
  options.threads = threads;
  const Voxmap voxmap = voxelize(meshes, {}, options).voxmap;
  grid = voxmap.grid();
  HyperchunkBlocks<std::uint8_t> bits(grid.dimsHyper);
  const std::uint8_t wanted = distanceValue(layer);
  const glm::ivec3 chunks = grid.dimsChunks();
  for (int cz = 0; cz < chunks.z; ++cz) {
    for (int cy = 0; cy < chunks.y; ++cy) {
      for (int cx = 0; cx < chunks.x; ++cx) {
        if (voxmap.chunkDistance({cx, cy, cz}) != 0) continue;
        for (int i = 0; i < kVoxelsPerChunk; ++i) {
          const glm::ivec3 v =
              glm::ivec3(cx, cy, cz) * kChunkEdgeVoxels + cellOfIndex(static_cast<std::uint32_t>(i));
          if (voxmap.value(v, Field::Surface) == wanted)
            bits.findOrCreate({cx, cy, cz}, 0)[static_cast<std::size_t>(i)] = kSurfaceBit;
        }
      }
    }
  }
  return bits;
}

}  // namespace

std::size_t Pointshell::count(PointFeature feature) const {
  return static_cast<std::size_t>(std::count(features.begin(), features.end(), feature));
}

double Pointshell::radiusAbout(const glm::dvec3& centreLocal) const {
  double radius = 0.0;
  for (const glm::vec3& p : positionsLocal)
    radius = std::max(radius, glm::length(glm::dvec3(p) - centreLocal));
  return radius;
}

void checkPointshellOptions(const PointshellOptions& options) {
  const double s = options.pointSpacingM;
  if (!(s > 0.0) || !std::isfinite(s)) {
    throw Error("point spacing must be a positive number of metres, not " + std::to_string(s));
  }
  if (options.freeLayer < 0 || options.freeLayer > kMaxFreeLayer) {
    throw Error("pointshell free layer must be 0 (surface) to " + std::to_string(kMaxFreeLayer) + ", not " +
                std::to_string(options.freeLayer));
  }
  if (options.onSurface && options.freeLayer > 0)
    throw Error("pointshell points are on the surface or in a free layer, not both");
}

Pointshell buildPointshell(std::span<const TriangleMesh* const> meshes,
                           std::span<const MeshFeatures> features, const PointshellOptions& options,
                           const ProgressFn& progress) {
  checkPointshellOptions(options);
  const double s = options.pointSpacingM;
  Bounds bounds;
  for (const TriangleMesh* mesh : meshes) {
    for (const glm::vec3& p : mesh->positionsWorld) bounds.add(glm::dvec3(p));
  }
  if (bounds.empty()) throw Error("no triangles to make a pointshell of");
  VoxelGrid grid = gridAround(bounds, s, 1);
  std::vector<FeatureGeometry> geometry;
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    geometry.push_back({meshes[i], i < features.size() ? &features[i] : nullptr});
  }
  auto stage = [&](double begin, double end) -> ProgressFn {
    if (!progress) return {};
    return [&progress, begin, end](double f) { progress(begin + (end - begin) * f); };
  };
  const HyperchunkBlocks<std::uint8_t> layerBits =
      options.freeLayer == 0 ? HyperchunkBlocks<std::uint8_t>(glm::ivec3(0))
                             : freeLayerBits(meshes, s, options.freeLayer, options.threads, grid);
  const HyperchunkBlocks<std::uint8_t> featureBits =
      rasterizeFeatures(grid, geometry, options.threads, stage(0.0, 0.3));
  const HyperchunkBlocks<std::uint8_t>& bits = options.freeLayer == 0 ? featureBits : layerBits;

  // the chunks holding surface voxels, in tree order (hyperchunk, then chunk in hyperchunk)
  struct ChunkRef {
    glm::ivec3 ijkChunk;
    const std::uint8_t* bits;
    std::uint32_t points;
  };
  std::vector<ChunkRef> chunks;
  const glm::ivec3 dims = grid.dimsHyper;
  for (int hz = 0; hz < dims.z; ++hz) {
    for (int hy = 0; hy < dims.y; ++hy) {
      for (int hx = 0; hx < dims.x; ++hx) {
        if (!bits.hyperHasBlocks({hx, hy, hz})) continue;
        for (std::uint32_t c = 0; c < kChunksPerHyper; ++c) {
          const glm::ivec3 ijkChunk = glm::ivec3(hx, hy, hz) * kHyperEdgeChunks + cellOfIndex(c);
          const auto* block = bits.find(ijkChunk);
          if (!block) continue;
          const auto points = static_cast<std::uint32_t>(std::count_if(
              block->begin(), block->end(), [](std::uint8_t b) { return (b & kSurfaceBit) != 0; }));
          if (points > 0) chunks.push_back({ijkChunk, block->data(), points});
        }
      }
    }
  }

  Pointshell shell;
  shell.pointSpacingM = s;
  shell.chunkBegin.push_back(0);
  for (const ChunkRef& chunk : chunks) shell.chunkBegin.push_back(shell.chunkBegin.back() + chunk.points);
  const std::size_t total = shell.chunkBegin.back();
  shell.positionsLocal.resize(total);
  shell.normalsLocal.resize(total);
  shell.features.resize(total);
  shell.chunkCentroidsLocal.resize(chunks.size());

  const EmbreeScene scene(meshes);
  const PseudoNormals pseudoNormals(meshes);
  const FeatureVoxels featureVoxels(grid, features, pseudoNormals);
  // a free-layer voxel's centre lies within (layer + 1) voxel diagonals of the surface
  const double searchM = (options.freeLayer + 1) * s * std::sqrt(3.0);
  parallelFor(
      chunks.size(), options.threads,
      [&](std::size_t c) {
        std::uint32_t at = shell.chunkBegin[c];
        glm::dvec3 sum(0.0);
        for (int i = 0; i < kVoxelsPerChunk; ++i) {
          const std::uint8_t b = chunks[c].bits[i];
          if (!(b & kSurfaceBit)) continue;
          const glm::ivec3 v =
              chunks[c].ijkChunk * kChunkEdgeVoxels + cellOfIndex(static_cast<std::uint32_t>(i));
          const glm::dvec3 centre = grid.voxelCentre(v);
          PointFeature feature = (b & kVertexBit) ? PointFeature::Vertex
                                 : (b & kEdgeBit) ? PointFeature::Edge
                                                  : PointFeature::Surface;
          glm::dvec3 normal(0.0, 0.0, 1.0);
          glm::dvec3 base = centre;
          if (options.onSurface) {
            // an edge or vertex voxel's point on its feature, so that a feature edge is
            // sampled along its length however the lattice falls; a surface voxel's centre
            // is within half its diagonal of the surface
            const auto onFeature = featureVoxels.pointOf(v, feature);
            const auto featureNormal = featureVoxels.normalOf(v, feature);
            if (onFeature && featureNormal) {
              base = *onFeature;
              normal = *featureNormal;
            } else if (const auto nearest = scene.closestPoint(centre, s)) {
              base = nearest->point;
              normal = pseudoNormals.normalAt(*nearest, kFeatureTolerance * s);
            }
          } else if (options.freeLayer > 0) {
            if (const auto nearest = scene.closestPoint(centre, searchM);
                nearest && nearest->distanceM > 0.0) {
              normal = (centre - nearest->point) / nearest->distanceM;
              // the label of the surface voxel the nearest surface point lies in
              const glm::ivec3 surfaceVoxel = grid.voxelOf(nearest->point);
              const auto* block = featureBits.find(surfaceVoxel >> kChunkEdgeLog2);
              const std::uint8_t inherited = block ? (*block)[voxelInChunk(surfaceVoxel)] : 0;
              feature = (inherited & kVertexBit) ? PointFeature::Vertex
                        : (inherited & kEdgeBit) ? PointFeature::Edge
                                                 : PointFeature::Surface;
            }
          } else if (const auto n = featureVoxels.normalOf(v, feature)) {
            normal = *n;
          } else if (const auto nearest = scene.closestPoint(centre, s)) {
            // a surface voxel's centre is within half its diagonal of the surface
            normal = pseudoNormals.normalAt(*nearest, kFeatureTolerance * s);
          }
          const glm::dvec3 position = base + options.displacementM * normal;
          shell.positionsLocal[at] = glm::vec3(position);
          shell.normalsLocal[at] = glm::vec3(normal);
          shell.features[at] = feature;
          sum += position;
          ++at;
        }
        shell.chunkCentroidsLocal[c] = glm::vec3(sum / static_cast<double>(chunks[c].points));
      },
      stage(0.3, 1.0));
  return shell;
}

}  // namespace voxhap
