#include "haptics/collide/probe_cells.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include <glm/geometric.hpp>

namespace voxhap {
namespace {

/// Block indices are packed as three 21-bit fields, offset so that negative ones fit.
constexpr int kKeyBits = 21;
constexpr std::int64_t kKeyOffset = std::int64_t{1} << (kKeyBits - 1);
constexpr std::uint64_t kKeyMask = (std::uint64_t{1} << kKeyBits) - 1;
constexpr int kCellsPerBlockLog2 = 3;
static_assert((1 << kCellsPerBlockLog2) == kCellsPerBlockEdge);

std::uint64_t packBlock(const glm::ivec3& ijk) {
  auto field = [](int i) {
    return static_cast<std::uint64_t>(std::clamp<std::int64_t>(i + kKeyOffset, 0, kKeyMask));
  };
  return (field(ijk.x) << (2 * kKeyBits)) | (field(ijk.y) << kKeyBits) | field(ijk.z);
}

glm::ivec3 unpackBlock(std::uint64_t key) {
  auto index = [](std::uint64_t f) {
    return static_cast<int>(static_cast<std::int64_t>(f & kKeyMask) - kKeyOffset);
  };
  return {index(key >> (2 * kKeyBits)), index(key >> kKeyBits), index(key)};
}

glm::ivec3 cellOf(const glm::dvec3& pointLocal, double cellSizeM) {
  const glm::dvec3 u = glm::floor(pointLocal / cellSizeM);
  const glm::dvec3 limit(static_cast<double>(kKeyOffset << kCellsPerBlockLog2) - 1.0);
  const glm::dvec3 c = glm::clamp(u, -limit, limit);
  return {static_cast<int>(c.x), static_cast<int>(c.y), static_cast<int>(c.z)};
}

}  // namespace

ProbeCells::ProbeCells(std::span<const TriangleMesh* const> meshes, const EmbreeScene& scene, double spacingM,
                       double cellSizeM, bool whole)
    : meshes_(meshes.begin(), meshes.end()),
      scene_(&scene),
      spacingM_(spacingM),
      cellSizeM_(cellSizeM),
      whole_(whole) {
  if (!whole_) return;
  std::vector<KeyedProbe> all;
  std::vector<SurfaceProbe> triangleProbes;
  for (const TriangleMesh* mesh : meshes_) {
    for (const glm::uvec3& t : mesh->triangles) {
      triangleProbes.clear();
      appendTriangleProbes(mesh->positionsWorld[t.x], mesh->positionsWorld[t.y], mesh->positionsWorld[t.z],
                           spacingM_, nullptr, triangleProbes);
      for (const SurfaceProbe& probe : triangleProbes) all.push_back(keyed(probe));
    }
  }
  std::sort(all.begin(), all.end(),
            [](const KeyedProbe& x, const KeyedProbe& y) { return x.block < y.block; });
  for (std::size_t i = 0; i < all.size();) {
    std::size_t j = i;
    while (j < all.size() && all[j].block == all[i].block) ++j;
    const std::uint64_t key = all[i].block;
    blockIndex_[key] = addBlock(std::span<KeyedProbe>(all.data() + i, j - i));
    i = j;
  }
}

ProbeCells::KeyedProbe ProbeCells::keyed(const SurfaceProbe& probe) const {
  const glm::ivec3 c = cellOf(glm::dvec3(probe.pointLocal), cellSizeM_);
  const glm::ivec3 b = c >> kCellsPerBlockLog2;  // arithmetic shift: floor division
  const glm::ivec3 in = c - (b << kCellsPerBlockLog2);
  return {
      packBlock(b),
      static_cast<std::uint32_t>(in.x | (in.y << kCellsPerBlockLog2) | (in.z << (2 * kCellsPerBlockLog2))),
      probe};
}

std::int64_t ProbeCells::addBlock(std::span<KeyedProbe> probes) {
  std::sort(probes.begin(), probes.end(), [](const KeyedProbe& x, const KeyedProbe& y) {
    const glm::vec3& p = x.probe.pointLocal;
    const glm::vec3& q = y.probe.pointLocal;
    return std::tie(x.cellInBlock, y.probe.onEdge, p.x, p.y, p.z) <
           std::tie(y.cellInBlock, x.probe.onEdge, q.x, q.y, q.z);
  });
  // exact duplicates are adjacent (an edge probe before an interior one at the same place)
  auto last = std::unique(probes.begin(), probes.end(), [](const KeyedProbe& x, const KeyedProbe& y) {
    return x.cellInBlock == y.cellInBlock && x.probe.pointLocal == y.probe.pointLocal;
  });
  const std::size_t n = static_cast<std::size_t>(last - probes.begin());
  if (n == 0) return -1;

  ProbeBlock block;
  block.firstCell = static_cast<std::uint32_t>(cells_.size());
  Bounds blockBounds;
  for (std::size_t i = 0; i < n;) {
    std::size_t j = i;
    while (j < n && probes[j].cellInBlock == probes[i].cellInBlock) ++j;
    ProbeCell cell;
    cell.first = static_cast<std::uint32_t>(probes_.size());
    Bounds bounds;
    for (std::size_t k = i; k < j; ++k) {
      probes_.push_back(probes[k].probe.pointLocal);
      bounds.add(glm::dvec3(probes[k].probe.pointLocal));
      cell.edgeCount += probes[k].probe.onEdge ? 1u : 0u;
    }
    cell.count = static_cast<std::uint32_t>(j - i);
    cell.centreLocal = 0.5 * (bounds.min + bounds.max);
    for (std::size_t k = i; k < j; ++k) {
      cell.radiusM =
          std::max(cell.radiusM, glm::length(glm::dvec3(probes[k].probe.pointLocal) - cell.centreLocal));
    }
    blockBounds.add(bounds);
    cells_.push_back(cell);
    i = j;
  }
  block.cellCount = static_cast<std::uint32_t>(cells_.size()) - block.firstCell;
  block.centreLocal = 0.5 * (blockBounds.min + blockBounds.max);
  for (std::uint32_t c = block.firstCell; c < block.firstCell + block.cellCount; ++c) {
    block.radiusM =
        std::max(block.radiusM, glm::length(cells_[c].centreLocal - block.centreLocal) + cells_[c].radiusM);
  }
  blocks_.push_back(block);
  return static_cast<std::int64_t>(blocks_.size() - 1);
}

std::uint64_t ProbeCells::blockKeyOf(const glm::dvec3& pointLocal) const {
  return packBlock(cellOf(pointLocal, cellSizeM_) >> kCellsPerBlockLog2);
}

void ProbeCells::blockKeysIn(const glm::dvec3& minLocal, const glm::dvec3& maxLocal,
                             std::vector<std::uint64_t>& out) const {
  const glm::ivec3 lo = cellOf(minLocal, cellSizeM_) >> kCellsPerBlockLog2;
  const glm::ivec3 hi = cellOf(maxLocal, cellSizeM_) >> kCellsPerBlockLog2;
  for (int z = lo.z; z <= hi.z; ++z) {
    for (int y = lo.y; y <= hi.y; ++y) {
      for (int x = lo.x; x <= hi.x; ++x) out.push_back(packBlock({x, y, z}));
    }
  }
}

std::optional<ProbeBlock> ProbeCells::block(std::uint64_t key) {
  if (const auto found = blockIndex_.find(key); found != blockIndex_.end()) {
    if (found->second < 0) return std::nullopt;
    return blocks_[static_cast<std::size_t>(found->second)];
  }
  if (whole_) return std::nullopt;
  const glm::dvec3 minLocal = glm::dvec3(unpackBlock(key)) * blockSizeM();
  const ProbeClipBox box{minLocal, minLocal + glm::dvec3(blockSizeM())};
  const glm::dvec3 centre = 0.5 * (box.min + box.max);
  triangles_.clear();
  scene_->trianglesWithin(centre, 0.5 * std::sqrt(3.0) * blockSizeM() * (1.0 + 1e-9), triangles_);
  std::vector<SurfaceProbe> clipped;
  for (const TriangleRef& t : triangles_) {
    const TriangleMesh& mesh = *meshes_[t.part];
    const glm::uvec3& v = mesh.triangles[t.triangle];
    appendTriangleProbes(mesh.positionsWorld[v.x], mesh.positionsWorld[v.y], mesh.positionsWorld[v.z],
                         spacingM_, &box, clipped);
  }
  std::vector<KeyedProbe> mine;
  mine.reserve(clipped.size());
  for (const SurfaceProbe& probe : clipped) {
    const KeyedProbe k = keyed(probe);
    if (k.block == key) mine.push_back(k);  // the box is closed; a probe on its far faces is the next block's
  }
  const std::int64_t index = addBlock(mine);
  blockIndex_[key] = index;
  if (index < 0) return std::nullopt;
  return blocks_[static_cast<std::size_t>(index)];
}

void ProbeCells::clear() {
  if (whole_) return;
  probes_.clear();
  cells_.clear();
  blocks_.clear();
  blockIndex_.clear();
}

}  // namespace voxhap
