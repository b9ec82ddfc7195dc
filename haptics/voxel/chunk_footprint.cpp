#include "haptics/voxel/chunk_footprint.h"

#include <algorithm>
#include <vector>

#include <glm/common.hpp>

#include "haptics/voxel/box_overlap.h"
#include "haptics/voxel/tree_shape.h"

namespace voxhap {
namespace {

void sortUnique(std::vector<std::uint64_t>& keys) {
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
}

/// Bounds spanning more chunks than this are quartered first.
constexpr int kMostBoundsChunks = 64;

/// A set of chunks of the grid, as their indices (x fastest; a grid has at most about 2^21
/// chunks a side, voxelizer.cpp, so that the index fits 64 bits).
class ChunkSet {
public:
  explicit ChunkSet(const glm::ivec3& dims) : dims_(dims) {}

  std::uint64_t key(const glm::ivec3& c) const {
    return std::uint64_t(c.x) +
           std::uint64_t(dims_.x) * (std::uint64_t(c.y) + std::uint64_t(dims_.y) * std::uint64_t(c.z));
  }
  glm::ivec3 chunk(std::uint64_t k) const {
    const std::uint64_t nx = std::uint64_t(dims_.x), ny = std::uint64_t(dims_.y);
    return {static_cast<int>(k % nx), static_cast<int>(k / nx % ny), static_cast<int>(k / nx / ny)};
  }

  void add(const glm::ivec3& c) {
    keys_.push_back(key(c));
    // kept near its distinct count: many triangles share each chunk
    if (keys_.size() > 2 * distinct_ + (std::size_t{1} << 20)) compact();
  }
  std::size_t size() {
    compact();
    return distinct_;
  }
  /// Adds the chunks one step from a member along `axis`.
  void grow(int axis) {
    compact();
    for (std::size_t i = 0; i < distinct_; ++i) {
      const glm::ivec3 c = chunk(keys_[i]);
      for (const int step : {-1, 1}) {
        glm::ivec3 d = c;
        d[axis] += step;
        if (d[axis] >= 0 && d[axis] < dims_[axis]) keys_.push_back(key(d));
      }
    }
    compact();
  }
  std::size_t distinctSoFar() const { return distinct_; }

private:
  void compact() {
    sortUnique(keys_);
    distinct_ = keys_.size();
  }

  glm::ivec3 dims_;
  std::vector<std::uint64_t> keys_;
  std::size_t distinct_ = 0;  ///< keys_[0, distinct_) sorted and unique
};

class SurfaceChunks {
public:
  SurfaceChunks(const VoxelGrid& grid, ChunkSet& set, std::uint64_t most)
      : grid_(grid),
        chunkM_(grid.voxelSizeM * kChunkEdgeVoxels),
        last_(grid.dimsChunks() - 1),
        set_(set),
        most_(most) {}

  bool full() const { return set_.distinctSoFar() > most_; }

  void triangle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    if (full()) return;
    const glm::ivec3 lo = chunkOf(glm::min(a, glm::min(b, c)));
    const glm::ivec3 hi = chunkOf(glm::max(a, glm::max(b, c)));
    const glm::ivec3 span = hi - lo + 1;
    if (span.x * span.y * span.z > kMostBoundsChunks) {
      // four pieces at the edges' midpoints: together exactly the triangle
      const glm::dvec3 ab = 0.5 * (a + b), bc = 0.5 * (b + c), ca = 0.5 * (c + a);
      triangle(a, ab, ca);
      triangle(ab, b, bc);
      triangle(ca, bc, c);
      triangle(ab, bc, ca);
      return;
    }
    const glm::dvec3 half(0.5 * chunkM_);
    for (int z = lo.z; z <= hi.z; ++z) {
      for (int y = lo.y; y <= hi.y; ++y) {
        for (int x = lo.x; x <= hi.x; ++x) {
          const glm::ivec3 chunk(x, y, z);
          const glm::dvec3 centre = grid_.originLocal + (glm::dvec3(chunk) + 0.5) * chunkM_;
          if (span == glm::ivec3(1) || triangleOverlapsBox(a, b, c, centre, half)) set_.add(chunk);
        }
      }
    }
  }

private:
  glm::ivec3 chunkOf(const glm::dvec3& p) const {
    return glm::clamp(glm::ivec3(glm::floor((p - grid_.originLocal) / chunkM_)), glm::ivec3(0), last_);
  }

  const VoxelGrid& grid_;
  double chunkM_;
  glm::ivec3 last_;
  ChunkSet& set_;
  std::uint64_t most_;
};

}  // namespace

ChunkFootprint chunkFootprint(std::span<const TriangleMesh* const> meshes, const VoxelGrid& grid,
                              int reachChunks, std::uint64_t mostSurfaceChunks) {
  ChunkSet set(grid.dimsChunks());
  SurfaceChunks surface(grid, set, mostSurfaceChunks);
  for (const TriangleMesh* mesh : meshes) {
    for (const glm::uvec3& t : mesh->triangles) {
      surface.triangle(glm::dvec3(mesh->positionsWorld[t.x]), glm::dvec3(mesh->positionsWorld[t.y]),
                       glm::dvec3(mesh->positionsWorld[t.z]));
    }
  }
  ChunkFootprint footprint;
  footprint.surfaceChunks = set.size();
  footprint.complete = footprint.surfaceChunks <= mostSurfaceChunks;
  if (footprint.complete) {
    for (int axis = 0; axis < 3; ++axis) {
      for (int step = 0; step < reachChunks; ++step) set.grow(axis);
    }
  }
  footprint.mixedChunks = set.size();
  return footprint;
}

}  // namespace voxhap
