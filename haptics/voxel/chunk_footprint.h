#pragma once
/// How many chunks a voxelization will store voxel by voxel, counted from the meshes
/// before any voxel is allocated: for the memory estimate that lets voxelize refuse a
/// voxel size too fine for the machine (voxelizer.h).

#include <cstdint>
#include <span>

#include "haptics/scene/scene.h"
#include "haptics/voxel/voxel_grid.h"

namespace voxhap {

struct ChunkFootprint {
  std::uint64_t surfaceChunks = 0;  ///< chunks a triangle passes through
  std::uint64_t mixedChunks = 0;    ///< those and the chunks within the reach of one (chessboard)
  bool complete = true;             ///< false: counting stopped at the limit (both are lower bounds)
};

/// The chunks of `grid` that the triangles of `meshes` (inside the grid) pass through,
/// each counted once however many triangles share it: exact, by triangle-box tests (a
/// triangle whose bounds span many chunks is quartered until its pieces' do not). When
/// `reachChunks` chunks cover the distance field's range, the chunks a voxelization
/// stores voxel by voxel are among the mixed ones counted here. Counting stops, not
/// complete, once more than `mostSurfaceChunks` surface chunks are found (a voxel size far
/// too fine would otherwise take as long to count as to voxelize).
ChunkFootprint chunkFootprint(std::span<const TriangleMesh* const> meshes, const VoxelGrid& grid,
                              int reachChunks, std::uint64_t mostSurfaceChunks);

}  // namespace voxhap
