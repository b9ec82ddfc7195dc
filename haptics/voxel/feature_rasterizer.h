#pragma once
/// First step of voxelization: which voxels the surface, the feature edges and the
/// feature vertices of the parts pass through (DESIGN §4.2 step 2). Work is split
/// by hyperchunk; each voxel gets a byte of feature bits.

#include <cstdint>
#include <span>

#include "haptics/core/progress.h"
#include "haptics/geometry/quasi_planar.h"
#include "haptics/scene/scene.h"
#include "haptics/voxel/hyperchunk_blocks.h"
#include "haptics/voxel/voxel_grid.h"

namespace voxhap {

/// Bits of a voxel's feature byte.
inline constexpr std::uint8_t kSurfaceBit = 1;  ///< a triangle overlaps the voxel
inline constexpr std::uint8_t kEdgeBit = 2;     ///< a feature edge overlaps the voxel
inline constexpr std::uint8_t kVertexBit = 4;   ///< a feature vertex lies in the voxel

/// One part to rasterize: its triangles and their features, in the grid's frame (m).
struct FeatureGeometry {
  const TriangleMesh* mesh = nullptr;
  const MeshFeatures* features = nullptr;
};

/// Marks every voxel that a triangle overlaps (exact triangle/box test, boxes closed),
/// that a feature edge overlaps, or that holds a feature vertex. Chunks with no mark
/// get no block. Uses `threads` threads (0: all cores); deterministic.
HyperchunkBlocks<std::uint8_t> rasterizeFeatures(const VoxelGrid& grid,
                                                 std::span<const FeatureGeometry> parts, int threads,
                                                 const ProgressFn& progress = {});

}  // namespace voxhap
