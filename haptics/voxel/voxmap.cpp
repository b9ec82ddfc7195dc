#include "haptics/voxel/voxmap.h"

#include <cassert>
#include <cmath>

#include "haptics/core/parallel.h"

namespace voxhap {
namespace {

/// Largest grid edge in hyperchunks a voxmap may have (2^24 voxels, as the voxelizer allows).
constexpr int kMaxDimsHyper = (1 << 24) / kHyperEdgeVoxels + 1;

/// Whether a tree entry is a uniform word that fits the encoding (or, for a chunk of a
/// paged voxmap, the missing word), or an index below `count`.
bool entryValid(std::uint32_t entry, std::size_t count, std::uint32_t uniformLimit, bool missingAllowed) {
  if (entry & Voxmap::kUniform) {
    const std::uint32_t word = entry & ~Voxmap::kUniform;
    return word < uniformLimit || (missingAllowed && word == Voxmap::kMissingWord);
  }
  return entry < count;
}

}  // namespace

Voxmap::Voxmap(VoxelGrid grid, VoxelEncoding encoding, std::vector<std::uint32_t> hyper,
               std::vector<std::uint32_t> chunks, std::vector<std::uint8_t> voxelBytes,
               std::vector<std::uint8_t> chunkDistances)
    : grid_(grid),
      encoding_(encoding),
      bytesPerWord_(static_cast<std::size_t>(encoding.bytesPerWord())),
      blockStrideBytes_(std::size_t{kVoxelsPerChunk} * bytesPerWord_),
      wordMask_(encoding.bytesPerWord() == 4 ? 0xFFFFFFFFu : (1u << (8 * encoding.bytesPerWord())) - 1u),
      hyper_(std::move(hyper)),
      chunks_(std::move(chunks)),
      voxelBytes_(std::move(voxelBytes)),
      chunkDistances_(std::move(chunkDistances)) {
  assert(validate(grid_, encoding_, hyper_, chunks_, voxelBytes_.size(), chunkDistances_.size()).empty());
  voxelBytes_.resize(voxelBytes_.size() + kPadBytes, 0);
}

Voxmap Voxmap::paged(VoxelGrid grid, VoxelEncoding encoding, std::vector<std::uint32_t> hyper,
                     std::vector<std::uint32_t> chunks, std::size_t slotCount,
                     std::vector<std::uint8_t> chunkDistances) {
  Voxmap v(grid, encoding, std::move(hyper), std::move(chunks), {}, std::move(chunkDistances));
  v.blockStrideBytes_ = v.blockBytes() + kPadBytes;
  v.voxelBytes_.assign(slotCount * v.blockStrideBytes_, 0);
  v.slotLastUse_.assign(slotCount, 0);
  v.useClock_.assign(kClockWords, 0);
  return v;
}

void Voxmap::setSurfacePlanes(SparseSurfacePlanes planes, int threads) {
  assert(!isPaged() && planes.chunkCount() == mixedChunkCount());
  planes_ = std::move(planes);
  if (planes_.convexSides().size() == planes_.planeCount()) return;
  const std::vector<glm::ivec3> chunkOf = chunkOfEachBlock();
  std::vector<std::uint8_t> sides(planes_.planeCount());
  parallelFor(chunkOf.size(), threads, [&](std::size_t block) {
    const auto b = static_cast<std::uint32_t>(block);
    std::size_t k = planes_.firstPlaneOf(b);
    for (std::uint32_t i = 0; i < kVoxelsPerChunk; ++i) {
      const SurfacePlane* plane = planes_.find(b, i);
      if (!plane) continue;
      sides[k++] = convexSidesOf_(chunkOf[block] * kChunkEdgeVoxels + cellOfIndex(i), *plane);
    }
  });
  planes_.setConvexSides(std::move(sides));
}

std::uint8_t Voxmap::convexSidesOf_(const glm::ivec3& ijkVoxel, const SurfacePlane& plane) const {
  std::uint8_t convex = 0;
  for (const int side : {-1, 1}) {
    const std::array<const SurfacePlane*, 3> beside = surfacePlanesBeside(ijkVoxel, glm::ivec3(side));
    for (int axis = 0; axis < 3; ++axis) {
      const SurfacePlane* other = beside[static_cast<std::size_t>(axis)];
      if (other && plane.convexWith(*other, axis, side)) convex |= SurfacePlane::sideBit(axis, side);
    }
  }
  return convex;
}

std::vector<glm::ivec3> Voxmap::chunkOfEachBlock() const {
  const glm::ivec3 dims = grid_.dimsHyper;
  std::vector<glm::ivec3> out(mixedChunkCount());
  for (int z = 0; z < dims.z; ++z)
    for (int y = 0; y < dims.y; ++y)
      for (int x = 0; x < dims.x; ++x) {
        const std::uint32_t entry = hyper_[static_cast<std::size_t>(x + dims.x * (y + dims.y * z))];
        if (entry & kUniform) continue;
        for (std::uint32_t c = 0; c < kChunksPerHyper; ++c) {
          const std::uint32_t chunk = chunks_[std::size_t{entry} * kChunksPerHyper + c];
          if (!(chunk & kUniform)) out[chunk] = glm::ivec3(x, y, z) * kHyperEdgeChunks + cellOfIndex(c);
        }
      }
  return out;
}

std::string Voxmap::validate(const VoxelGrid& grid, const VoxelEncoding& encoding,
                             std::span<const std::uint32_t> hyper, std::span<const std::uint32_t> chunks,
                             std::size_t voxelBytesSize, std::size_t chunkDistancesSize) {
  if (!encoding.valid()) return "invalid encoding (" + std::to_string(encoding.bitsPerField) + " bits)";
  if (!(grid.voxelSizeM > 0.0) || !std::isfinite(grid.voxelSizeM))
    return "voxel size is not a positive number";
  for (int k = 0; k < 3; ++k) {
    if (grid.dimsHyper[k] <= 0 || grid.dimsHyper[k] > kMaxDimsHyper) return "grid size out of range";
    if (!std::isfinite(grid.originLocal[k])) return "grid origin is not finite";
  }
  const glm::ivec3 dc = grid.dimsChunks();
  const std::size_t chunkCount =
      static_cast<std::size_t>(dc.x) * static_cast<std::size_t>(dc.y) * static_cast<std::size_t>(dc.z);
  if (hyper.size() * kChunksPerHyper != chunkCount) return "hyperchunk table does not match the grid";
  if (chunkDistancesSize != chunkCount) return "chunk-level field does not match the grid";
  if (chunks.size() % kChunksPerHyper != 0) return "chunk table is not whole hyperchunks";
  const std::size_t blockBytes =
      std::size_t{kVoxelsPerChunk} * static_cast<std::size_t>(encoding.bytesPerWord());
  if (voxelBytesSize % blockBytes != 0) return "voxel words are not whole chunks";
  const std::uint32_t uniformLimit = 1u << (kFieldCount * encoding.bitsPerField);
  for (std::uint32_t entry : hyper) {
    if (!entryValid(entry, chunks.size() / kChunksPerHyper, uniformLimit, false))
      return "hyperchunk entry out of range";
  }
  for (std::uint32_t entry : chunks) {
    if (!entryValid(entry, voxelBytesSize / blockBytes, uniformLimit, true))
      return "chunk entry out of range";
  }
  return {};
}

}  // namespace voxhap
