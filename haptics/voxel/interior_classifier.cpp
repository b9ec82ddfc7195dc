#include "haptics/voxel/interior_classifier.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "haptics/core/parallel.h"
#include "haptics/geometry/embree_scene.h"

namespace voxhap {
namespace {

// where inside its voxel a row's ray runs, as fractions of a voxel along the two
// other axes: off-centre and irrational-looking, so that rays miss round-number edges
constexpr double kRayOffsetFirst = 0.5 + 0.0731;
constexpr double kRayOffsetSecond = 0.5 - 0.0419;
// crossings of one part closer than this (voxels) are one crossing of a shared edge
constexpr double kSameCrossingVoxels = 1e-6;

}  // namespace

InteriorClassifier::InteriorClassifier(const VoxelGrid& grid, std::span<const TriangleMesh* const> meshes,
                                       const EmbreeScene& scene, int threads)
    : grid_(grid), partCount_(meshes.size()) {
  Bounds bounds;
  for (const TriangleMesh* mesh : meshes) {
    for (const glm::vec3& p : mesh->positionsWorld) bounds.add(glm::dvec3(p));
  }
  if (bounds.empty()) return;
  const glm::ivec3 last = grid.dimsVoxels() - 1;
  const glm::ivec3 lo = glm::clamp(grid.voxelOf(bounds.min), glm::ivec3(0), last);
  const glm::ivec3 hi = glm::clamp(grid.voxelOf(bounds.max), glm::ivec3(0), last);
  for (int axis = 0; axis < 3; ++axis) rows_[axis] = castRows(axis, meshes, scene, lo, hi, threads);
}

InteriorClassifier::AxisRows InteriorClassifier::castRows(int axis,
                                                          std::span<const TriangleMesh* const> meshes,
                                                          const EmbreeScene& scene,
                                                          const glm::ivec3& boundsLo,
                                                          const glm::ivec3& boundsHi, int threads) const {
  const int b = (axis + 1) % 3;
  const int c = (axis + 2) % 3;
  AxisRows rows;
  rows.axis = axis;
  rows.lo = {boundsLo[b], boundsLo[c]};
  rows.size = {boundsHi[b] - boundsLo[b] + 1, boundsHi[c] - boundsLo[c] + 1};
  const double s = grid_.voxelSizeM;
  glm::dvec3 direction(0.0);
  direction[axis] = 1.0;
  const double startVoxels = boundsLo[axis] - 1.0;
  const double lengthM = (boundsHi[axis] - boundsLo[axis] + 3.0) * s;

  // one layer of rows (fixed coordinate along c) per task; layers joined in order
  std::vector<std::vector<Crossing>> layerCrossings(static_cast<std::size_t>(rows.size.y));
  std::vector<std::vector<std::uint32_t>> layerCounts(static_cast<std::size_t>(rows.size.y));
  parallelFor(static_cast<std::size_t>(rows.size.y), threads, [&](std::size_t layer) {
    std::vector<RayCrossing> hits;
    std::vector<Crossing>& out = layerCrossings[layer];
    std::vector<std::uint32_t>& counts = layerCounts[layer];
    counts.resize(static_cast<std::size_t>(rows.size.x));
    for (int i = 0; i < rows.size.x; ++i) {
      glm::dvec3 origin;
      origin[axis] = grid_.originLocal[axis] + startVoxels * s;
      origin[b] = grid_.originLocal[b] + (rows.lo.x + i + kRayOffsetFirst) * s;
      origin[c] = grid_.originLocal[c] + (rows.lo.y + static_cast<int>(layer) + kRayOffsetSecond) * s;
      hits.clear();
      scene.allCrossings(origin, direction, lengthM, hits);
      std::sort(hits.begin(), hits.end(), [](const RayCrossing& x, const RayCrossing& y) {
        return std::tie(x.t, x.part, x.triangle) < std::tie(y.t, y.part, y.triangle);
      });
      const std::size_t before = out.size();
      for (std::size_t h = 0; h < hits.size(); ++h) {
        // the ray through an edge shared by two triangles of a part: once when it passes
        // through the surface (both triangles face the same way along the ray), else twice
        bool duplicate = false;
        for (std::size_t k = h; k-- > 0 && (hits[h].t - hits[k].t) < kSameCrossingVoxels * s;) {
          if (hits[k].part != hits[h].part) continue;
          const TriangleMesh& mesh = *meshes[hits[h].part];
          auto facing = [&](std::uint32_t t) {
            const glm::uvec3& tri = mesh.triangles[t];
            const glm::dvec3 p0(mesh.positionsWorld[tri.x]);
            return glm::cross(glm::dvec3(mesh.positionsWorld[tri.y]) - p0,
                              glm::dvec3(mesh.positionsWorld[tri.z]) - p0)[axis] > 0.0;
          };
          duplicate = facing(hits[k].triangle) == facing(hits[h].triangle);
          break;
        }
        if (duplicate) continue;
        out.push_back({static_cast<float>(startVoxels + hits[h].t / s), hits[h].part});
      }
      counts[static_cast<std::size_t>(i)] = static_cast<std::uint32_t>(out.size() - before);
    }
  });

  std::size_t total = 0;
  for (const auto& layer : layerCrossings) total += layer.size();
  rows.crossings.reserve(total);
  rows.begin.reserve(static_cast<std::size_t>(rows.size.x) * static_cast<std::size_t>(rows.size.y) + 1);
  for (std::size_t layer = 0; layer < layerCrossings.size(); ++layer) {
    std::size_t rowBegin = rows.crossings.size();
    for (std::uint32_t count : layerCounts[layer]) {
      rows.begin.push_back(static_cast<std::uint32_t>(rowBegin));
      rowBegin += count;
    }
    rows.crossings.insert(rows.crossings.end(), layerCrossings[layer].begin(), layerCrossings[layer].end());
    std::vector<Crossing>().swap(layerCrossings[layer]);
  }
  rows.begin.push_back(static_cast<std::uint32_t>(rows.crossings.size()));
  return rows;
}

namespace {

/// The first voxel index along a row whose centre lies beyond a crossing at `tVoxels`: the
/// least j with float(j) + 0.5f > tVoxels, compared in float as the voxel walk would.
int firstVoxelAfter(float tVoxels) {
  int j = static_cast<int>(std::floor(tVoxels)) - 1;
  while (static_cast<float>(j) + 0.5f <= tVoxels) ++j;
  while (static_cast<float>(j - 1) + 0.5f > tVoxels) --j;
  return j;
}

}  // namespace

void InteriorClassifier::addVotes(const AxisRows& rows, const glm::ivec3& lo, const glm::ivec3& size,
                                  std::vector<std::uint8_t>& out) const {
  const int a = rows.axis;
  const int b = (a + 1) % 3;
  const int c = (a + 2) % 3;
  const std::size_t strides[3] = {1, static_cast<std::size_t>(size.x),
                                  static_cast<std::size_t>(size.x) * static_cast<std::size_t>(size.y)};
  const int first = lo[a];
  const int end = lo[a] + size[a];
  std::vector<std::uint8_t> partInside(partCount_, 0);
  for (int jc = lo[c]; jc < lo[c] + size[c]; ++jc) {
    for (int jb = lo[b]; jb < lo[b] + size[b]; ++jb) {
      const int rb = jb - rows.lo.x;
      const int rc = jc - rows.lo.y;
      if (rb < 0 || rc < 0 || rb >= rows.size.x || rc >= rows.size.y) continue;  // no surface on this row
      const std::size_t row =
          static_cast<std::size_t>(rb) + static_cast<std::size_t>(rows.size.x) * static_cast<std::size_t>(rc);
      const Crossing* next = rows.crossings.data() + rows.begin[row];
      const Crossing* last = rows.crossings.data() + rows.begin[row + 1];
      if (next == last) continue;
      std::uint8_t* line = out.data() + static_cast<std::size_t>(jb - lo[b]) * strides[b] +
                           static_cast<std::size_t>(jc - lo[c]) * strides[c];
      // runs of voxels between crossings: inside while any part is
      int partsInside = 0;
      int runStart = first;
      for (; next != last; ++next) {
        const int runEnd = std::min(firstVoxelAfter(next->tVoxels), end);
        if (partsInside > 0) {
          for (int ja = std::max(runStart, first); ja < runEnd; ++ja)
            ++line[static_cast<std::size_t>(ja - first) * strides[a]];
        }
        runStart = std::max(runStart, runEnd);
        std::uint8_t& state = partInside[next->part];
        state ^= 1u;
        partsInside += state ? 1 : -1;
        if (runStart >= end) break;
      }
      if (partsInside > 0) {
        for (int ja = runStart; ja < end; ++ja) ++line[static_cast<std::size_t>(ja - first) * strides[a]];
      }
      for (const Crossing* k = rows.crossings.data() + rows.begin[row]; k != next; ++k)
        partInside[k->part] = 0;
      if (next != last) partInside[next->part] = 0;
    }
  }
}

void InteriorClassifier::votes(const glm::ivec3& lo, const glm::ivec3& size,
                               std::vector<std::uint8_t>& out) const {
  out.assign(
      static_cast<std::size_t>(size.x) * static_cast<std::size_t>(size.y) * static_cast<std::size_t>(size.z),
      0);
  if (partCount_ == 0) return;
  for (const AxisRows& rows : rows_) {
    if (!rows.begin.empty()) addVotes(rows, lo, size, out);
  }
}

}  // namespace voxhap
