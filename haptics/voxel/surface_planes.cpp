#include "haptics/voxel/surface_planes.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "haptics/core/parallel.h"
#include "haptics/geometry/pseudo_normals.h"

namespace voxhap {

SurfacePlane SurfacePlane::make(double distanceVoxels, const glm::dvec3& outwardUnit) {
  const double limit = std::numeric_limits<std::int16_t>::max() / kDistanceStepsPerVoxel;
  SurfacePlane plane;
  plane.distance = static_cast<std::int16_t>(
      std::lround(std::clamp(distanceVoxels, -limit, limit) * kDistanceStepsPerVoxel));
  for (int k = 0; k < 3; ++k)
    plane.outward[k] =
        static_cast<std::int16_t>(std::lround(std::clamp(outwardUnit[k], -1.0, 1.0) * kDirectionSteps));
  return plane;
}

namespace {

/// Mixed chunks whose planes are computed together before they are packed: 16 MiB of
/// planes at a time.
constexpr std::size_t kChunksPerBatch = 4096;

}  // namespace

SparseSurfacePlanes computeSurfacePlanes(const Voxmap& voxmap, std::span<const TriangleMesh* const> meshes,
                                         const EmbreeScene& scene, int threads, const ProgressFn& progress) {
  const std::vector<glm::ivec3> chunkOf = voxmap.chunkOfEachBlock();
  SparseSurfacePlanes planes;
  std::vector<SurfacePlane> batch;
  const PseudoNormals pseudoNormals(meshes);
  const VoxelGrid& grid = voxmap.grid();
  const double s = grid.voxelSizeM;
  const std::uint8_t outermost = distanceValue(kSurfacePlaneLayers);
  for (std::size_t begin = 0; begin < chunkOf.size(); begin += kChunksPerBatch) {
    const std::size_t count = std::min(kChunksPerBatch, chunkOf.size() - begin);
    batch.assign(count * kVoxelsPerChunk, SurfacePlane{});
    parallelFor(count, threads, [&](std::size_t m) {
      const glm::ivec3 first = chunkOf[begin + m] * kChunkEdgeVoxels;
      SurfacePlane* block = batch.data() + m * kVoxelsPerChunk;
      for (std::uint32_t i = 0; i < kVoxelsPerChunk; ++i) {
        const glm::ivec3 ijk = first + cellOfIndex(i);
        const std::uint8_t value = voxmap.value(ijk, Field::Surface);
        if (value == kValueFar || value > outermost) continue;
        const glm::dvec3 c = grid.voxelCentre(ijk);
        // a surface or free voxel k layers out (chessboard) has surface within k + ½
        // voxel diagonals of its centre; the query's radius bounds the triangles it visits
        const double reachVoxels = value == kValueInterior
                                       ? kSurfacePlaneReachVoxels
                                       : (value - kValueFeature + 0.5) * std::sqrt(3.0) + 1e-3;
        const auto q = scene.closestPoint(c, reachVoxels * s);
        if (!q) continue;
        const glm::dvec3 normal = pseudoNormals.normalAt(*q, 1e-9 * s);
        const bool inside =
            value == kValueInterior || (value == kValueFeature && glm::dot(c - q->point, normal) < 0.0);
        const double onSurfaceM = 1e-6 * s;
        const glm::dvec3 away = q->distanceM > onSurfaceM ? (c - q->point) / q->distanceM : normal;
        const glm::dvec3 outward = q->distanceM > onSurfaceM && inside ? -away : away;
        block[i] = SurfacePlane::make((inside ? -q->distanceM : q->distanceM) / s, outward);
      }
    });
    for (std::size_t m = 0; m < count; ++m)
      planes.appendChunk(std::span(batch).subspan(m * kVoxelsPerChunk, kVoxelsPerChunk));
    if (progress) progress(static_cast<double>(begin + count) / static_cast<double>(chunkOf.size()));
  }
  return planes;
}

}  // namespace voxhap
