#include "haptics/voxel/sparse_surface_planes.h"

#include <algorithm>
#include <cassert>
#include <limits>

#include "haptics/core/error.h"

namespace voxhap {

constexpr std::size_t kPlanesPerSegment = std::size_t{1} << SparseSurfacePlanes::kSegmentLog2;

void SparseSurfacePlanes::appendChunk(std::span<const SurfacePlane> chunkPlanes) {
  assert(chunkPlanes.size() == kVoxelsPerChunk);
  std::size_t count = planeCount();
  if (count > std::numeric_limits<std::uint32_t>::max() - kVoxelsPerChunk)
    throw Error("too many surface planes (over 2^32): choose a larger voxel size");
  for (std::uint32_t m = 0; m < kMasksPerChunk; ++m) {
    std::uint64_t mask = 0;
    first_.push_back(static_cast<std::uint32_t>(count));
    for (std::uint32_t i = 0; i < kVoxelsPerMask; ++i) {
      const SurfacePlane& plane = chunkPlanes[m * kVoxelsPerMask + i];
      if (!plane.valid()) continue;
      mask |= std::uint64_t{1} << i;
      if (count++ % kPlanesPerSegment == 0) segments_.emplace_back().reserve(kPlanesPerSegment);
      segments_.back().push_back(plane);
    }
    occupancy_.push_back(mask);
  }
}

std::string SparseSurfacePlanes::resetTo(std::vector<std::uint64_t> occupancy) {
  *this = {};
  if (occupancy.size() % kMasksPerChunk != 0) return "surface plane masks are not whole chunks";
  first_.reserve(occupancy.size());
  std::uint64_t count = 0;
  for (const std::uint64_t mask : occupancy) {
    if (count > std::numeric_limits<std::uint32_t>::max() - kVoxelsPerMask) {
      first_.clear();
      return "more than 2^32 surface planes";
    }
    first_.push_back(static_cast<std::uint32_t>(count));
    count += static_cast<std::uint64_t>(std::popcount(mask));
  }
  occupancy_ = std::move(occupancy);
  for (auto left = static_cast<std::size_t>(count); left > 0; left -= std::min(left, kPlanesPerSegment))
    segments_.emplace_back(std::min(left, kPlanesPerSegment));
  return "";
}

bool SparseSurfacePlanes::complete() const noexcept {
  return std::ranges::all_of(segments_, [](const std::vector<SurfacePlane>& s) {
    return std::ranges::all_of(s, [](const SurfacePlane& p) { return p.valid(); });
  });
}

void SparseSurfacePlanes::setConvexSides(std::vector<std::uint8_t> sides) {
  assert(sides.size() == planeCount());
  convexSides_ = std::move(sides);
}

std::size_t SparseSurfacePlanes::memoryBytes() const noexcept {
  std::size_t bytes =
      occupancy_.size() * sizeof(std::uint64_t) + first_.size() * sizeof(std::uint32_t) + convexSides_.size();
  for (const std::vector<SurfacePlane>& s : segments_) bytes += s.size() * sizeof(SurfacePlane);
  return bytes;
}

}  // namespace voxhap
