#pragma once
/// Voxelization of an object's parts into a Voxmap (DESIGN §4.2):
///   1. quasi-planar merging gives feature edges and vertices (geometry/quasi_planar.h)
///   2. surface, edge and vertex voxels by exact overlap (feature_rasterizer.h)
///   3. inside/outside of the other voxels by ray parity with a vote (interior_classifier.h)
///   4. three chessboard distance transforms, hyperchunk by hyperchunk, with a halo of
///      the field's range, as three separable passes (x, y, z) of a min–max filter
///   5. chunks whose voxels are all equal stored as one word
///   6. the chunk-level distance field over the whole grid (chunk_distance.h)
///   7. optionally, the surface planes of the voxels near the surface (surface_planes.h)
/// Hyperchunks are independent in steps 2 and 4, so they run in parallel; the voxmap
/// is the same bit for bit whatever the thread count.

#include <cstdint>
#include <optional>
#include <span>

#include "haptics/core/progress.h"
#include "haptics/geometry/quasi_planar.h"
#include "haptics/scene/scene.h"
#include "haptics/voxel/voxmap.h"

namespace voxhap {

struct VoxelizeOptions {
  double voxelSizeM = 0.0;  ///< > 0
  VoxelEncoding encoding = VoxelEncoding::forBits(4);
  bool buildFeatureFields = true;       ///< edge and vertex fields (geometrical awareness); else left far
  bool surfacePlanes = false;           ///< the voxels' surface planes too (surface_planes.h)
  int threads = 0;                      ///< 0: all cores
  std::uint64_t memoryBudgetBytes = 0;  ///< refuse before allocating beyond this; 0: 3/4 of RAM
};

/// Voxel counts as in the paper's Table 1, and what the vote found.
struct VoxelizeStats {
  std::uint64_t interiorVoxels = 0;  ///< surface field value 1 (uniform chunks included)
  std::uint64_t surfaceVoxels = 0;   ///< surface field value 2
  std::uint64_t distanceVoxels = 0;  ///< surface field values 3 … 2 + range
  std::uint64_t edgeVoxels = 0;      ///< voxels a feature edge passes through
  std::uint64_t vertexVoxels = 0;    ///< voxels holding a feature vertex
  /// Surface voxels by the feature they inherit (vertex > edge > surface): the labels
  /// of a pointshell taken at this voxel size, which has one point per surface voxel.
  std::uint64_t vertexPoints = 0;
  std::uint64_t edgePoints = 0;     ///< surface voxels meeting a feature edge, holding no feature vertex
  std::uint64_t surfacePoints = 0;  ///< the other surface voxels
  std::uint64_t triangles = 0;
  std::uint64_t polygonsAfterMerge = 0;
  std::uint64_t voteDisagreements = 0;               ///< free voxels whose three votes differ
  std::optional<glm::dvec3> firstDisagreementLocal;  ///< centre of one such voxel, m
  std::uint64_t totalVoxels() const { return interiorVoxels + surfaceVoxels + distanceVoxels; }
};

struct VoxelizedObject {
  Voxmap voxmap;
  VoxelizeStats stats;
};

struct VoxelizeEstimate {
  std::uint64_t bytes = 0;
  bool lowerBound = false;  ///< counting stopped at the budget: it would take more
};

/// Peak memory of voxelizing `meshes` into `grid`, a little above what it takes: from the
/// chunks their triangles pass through (chunk_footprint.h) and their area. Counting stops
/// once the estimate is sure to exceed `budgetBytes`: then it is a lower bound above it.
VoxelizeEstimate estimateVoxelizeBytes(std::span<const TriangleMesh* const> meshes, const VoxelGrid& grid,
                                       const VoxelizeOptions& options, std::uint64_t budgetBytes);

/// Throws voxhap::Error when `options` are invalid (voxel size not a positive number,
/// unsupported bit width or range).
void checkVoxelizeOptions(const VoxelizeOptions& options);

/// Voxelizes the union of `meshes` (object-local frame, m); `features[i]` belongs to
/// `meshes[i]`. Throws voxhap::Error, before allocating, when the options are invalid
/// or the estimate exceeds the memory budget (the message states the estimate).
VoxelizedObject voxelize(std::span<const TriangleMesh* const> meshes, std::span<const MeshFeatures> features,
                         const VoxelizeOptions& options, const ProgressFn& progress = {});

/// The grid voxelize() uses: the meshes' bounds padded by the field range plus one voxel,
/// on a lattice anchored at the frame's origin, rounded up to whole hyperchunks.
VoxelGrid gridAround(const Bounds& boundsLocal, double voxelSizeM, int paddingVoxels);

}  // namespace voxhap
