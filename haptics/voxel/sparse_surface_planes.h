#pragma once
/// A voxmap's surface planes (surface_plane.h), kept only for the voxels that have one.
///
/// Planes exist within about two voxels of the surface: a quarter of the voxels of the
/// mixed chunks (landing gear, 1 mm voxels: 199 M of 728 M), but in most chunks some.
/// So per run of 64 voxels of a mixed chunk (x fastest, as the chunk's words) the store
/// keeps a bit per voxel that has a plane and the index of the run's first plane; the
/// planes follow packed, in voxel order, in segments of 2^20 that are never moved (so
/// that building the store never holds two copies of it). A lookup is three dependent
/// loads and a popcount; 12 bytes per 64 voxels beside 8 per plane, against 8 per voxel
/// dense. Each plane's convex sides (PlaneWithSides), a byte, follow in one array.

#include <bit>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "haptics/voxel/surface_plane.h"
#include "haptics/voxel/tree_shape.h"

namespace voxhap {

/// A voxel's plane and the set of its face neighbours (SurfacePlane::sideBit) whose planes
/// it is convex with (SurfacePlane::convexWith): the neighbours worth reading at a point.
struct PlaneWithSides {
  const SurfacePlane* plane = nullptr;
  std::uint8_t convexSides = 0;
};

class SparseSurfacePlanes {
public:
  static constexpr std::uint32_t kVoxelsPerMask = 64;
  static constexpr std::uint32_t kMasksPerChunk = kVoxelsPerChunk / kVoxelsPerMask;
  static constexpr int kSegmentLog2 = 20;

  /// Appends the planes of the next mixed chunk: kVoxelsPerChunk, invalid where a voxel
  /// has none. Throws voxhap::Error past 2^32 planes.
  void appendChunk(std::span<const SurfacePlane> chunkPlanes);

  /// Empties the store and sizes it for `occupancy` (an occupancy() array): "" when that
  /// is whole chunks of masks with fewer than 2^32 bits set. Its planes are then to be
  /// filled through segment(); complete() checks them.
  std::string resetTo(std::vector<std::uint64_t> occupancy);
  /// Whether every stored plane is a plane.
  bool complete() const noexcept;

  /// The plane of voxel `voxelInChunk` of the `block`-th mixed chunk, or null.
  const SurfacePlane* find(std::uint32_t block, std::uint32_t voxelInChunk) const noexcept {
    const std::size_t k = indexOf(block, voxelInChunk);
    return k == kNoPlane ? nullptr : &planeAt(k);
  }
  /// The index of the first plane of the `block`-th mixed chunk: its planes follow in voxel order.
  std::size_t firstPlaneOf(std::uint32_t block) const noexcept {
    return first_[std::size_t{block} * kMasksPerChunk];
  }
  /// The same, with the sides on which its face neighbours' planes are convex with it
  /// (setConvexSides).
  PlaneWithSides findWithSides(std::uint32_t block, std::uint32_t voxelInChunk) const noexcept {
    const std::size_t k = indexOf(block, voxelInChunk);
    if (k == kNoPlane) return {};
    return {&planeAt(k), convexSides_[k]};
  }

  bool empty() const noexcept { return occupancy_.empty(); }
  std::size_t chunkCount() const noexcept { return occupancy_.size() / kMasksPerChunk; }
  /// A bit per voxel of the mixed chunks: whether it has a plane.
  std::span<const std::uint64_t> occupancy() const noexcept { return occupancy_; }
  std::size_t planeCount() const noexcept {
    return segments_.empty() ? 0 : ((segments_.size() - 1) << kSegmentLog2) + segments_.back().size();
  }
  /// The planes of the voxels whose bit is set, in their order, a segment at a time.
  std::size_t segmentCount() const noexcept { return segments_.size(); }
  std::span<const SurfacePlane> segment(std::size_t k) const noexcept { return segments_[k]; }
  std::span<SurfacePlane> segment(std::size_t k) noexcept { return segments_[k]; }
  std::size_t memoryBytes() const noexcept;

  /// Every plane's convex sides, in the planes' order (Voxmap::setSurfacePlanes computes
  /// them): planeCount() of them.
  void setConvexSides(std::vector<std::uint8_t> sides);
  std::span<const std::uint8_t> convexSides() const noexcept { return convexSides_; }

  bool operator==(const SparseSurfacePlanes& other) const {
    return occupancy_ == other.occupancy_ && segments_ == other.segments_ &&
           convexSides_ == other.convexSides_;
  }

private:
  static constexpr std::size_t kNoPlane = ~std::size_t{0};

  /// The index of the plane of voxel `voxelInChunk` of the `block`-th mixed chunk, or kNoPlane.
  std::size_t indexOf(std::uint32_t block, std::uint32_t voxelInChunk) const noexcept {
    const std::size_t m = std::size_t{block} * kMasksPerChunk + voxelInChunk / kVoxelsPerMask;
    const std::uint32_t bit = voxelInChunk % kVoxelsPerMask;
    const std::uint64_t mask = occupancy_[m];
    if (!((mask >> bit) & 1u)) return kNoPlane;
    return std::size_t{first_[m]} + bitsSet(mask & ((std::uint64_t{1} << bit) - 1));
  }
  const SurfacePlane& planeAt(std::size_t k) const noexcept {
    return segments_[k >> kSegmentLog2][k & ((std::size_t{1} << kSegmentLog2) - 1)];
  }

  /// std::popcount inline: on the x86-64 baseline (no POPCNT) std::popcount calls
  /// libgcc's __popcountdi2, 5 % of the surface-contact wrench (perf).
  static constexpr std::size_t bitsSet(std::uint64_t x) noexcept {
    x -= (x >> 1) & 0x5555555555555555u;
    x = (x & 0x3333333333333333u) + ((x >> 2) & 0x3333333333333333u);
    x = (x + (x >> 4)) & 0x0f0f0f0f0f0f0f0fu;
    return static_cast<std::size_t>((x * 0x0101010101010101u) >> 56);
  }

  std::vector<std::uint64_t> occupancy_;
  std::vector<std::uint32_t> first_;                 // per mask: the index of its first plane
  std::vector<std::vector<SurfacePlane>> segments_;  // all full but the last
  std::vector<std::uint8_t> convexSides_;            // per plane
};

}  // namespace voxhap
