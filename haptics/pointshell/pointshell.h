#pragma once
/// The pointshell of a moving object (DESIGN §4.3, paper §2.1, §3.2, §4): the centres
/// of its surface voxels at the point spacing, each with a unit outward normal (from
/// the nearest triangle) and a feature label (vertex > edge > surface).
///
/// Points of one chunk of the object's voxel tree have contiguous indices, so chunk-
/// level coherence can move a chunk's points in one run. Hot data (position, normal,
/// label) are separate arrays, read in that order by the point tests.

#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "haptics/core/progress.h"
#include "haptics/geometry/quasi_planar.h"
#include "haptics/scene/scene.h"

namespace voxhap {

/// Which feature a point's voxel inherited; decides the field it samples.
enum class PointFeature : std::uint8_t { Surface = 0, Edge = 1, Vertex = 2 };

struct PointshellOptions {
  double pointSpacingM = 0.0;  ///< voxel size of the object's own voxelization, > 0
  /// Signed displacement of every point along its normal, m: negative moves points
  /// inward (mating surfaces, e.g. half a voxel for the ball in its socket).
  double displacementM = 0.0;
  /// 0: points at the surface voxels. k in 1 … kMaxFreeLayer: points at the free-space
  /// voxels k voxels (chessboard) outside the surface, for a collision offset beyond
  /// what moving the force layer gives (paper §3.2); their normals point away from the
  /// nearest surface point, their labels those of the surface voxel it lies in.
  int freeLayer = 0;
  /// Points on the surface: each surface voxel's point at the surface point nearest its
  /// centre (then displaced), not at the centre, which may lie 0.87 voxel off it; an edge
  /// or vertex voxel's at the point of its feature edges nearest its centre, or its feature
  /// vertex, so that an edge is sampled along its length wherever the lattice falls (the
  /// nearest surface point lies on the edge only where the centre is in the edge's wedge,
  /// and another part's edge crossing it passed between the points). For contact finer
  /// than a voxel (surface planes); not with a free layer.
  bool onSurface = false;
  int threads = 0;  ///< 0: all cores
};

/// The outermost free-space layer a pointshell may be taken from (the 4-bit field range).
inline constexpr int kMaxFreeLayer = 8;

struct Pointshell {
  double pointSpacingM = 0.0;
  std::vector<glm::vec3> positionsLocal;  ///< object-local frame, m
  std::vector<glm::vec3> normalsLocal;    ///< unit, outward, object-local frame
  std::vector<PointFeature> features;
  std::vector<std::uint32_t> chunkBegin;       ///< points of chunk c: [chunkBegin[c], chunkBegin[c + 1])
  std::vector<glm::vec3> chunkCentroidsLocal;  ///< mean position of each chunk's points, m

  std::size_t size() const { return positionsLocal.size(); }
  std::size_t chunkCount() const { return chunkCentroidsLocal.size(); }
  std::size_t count(PointFeature feature) const;
  /// Largest distance of a point from `centreLocal`, m (the lever arm of rotations).
  double radiusAbout(const glm::dvec3& centreLocal) const;
};

/// Throws voxhap::Error when the point spacing is not a positive number of metres or the
/// free layer is outside 0 … kMaxFreeLayer.
void checkPointshellOptions(const PointshellOptions& options);

/// Builds the pointshell of `meshes` (object-local frame); `features[i]` belongs to
/// `meshes[i]`. Deterministic whatever the thread count. Throws voxhap::Error on bad
/// options.
Pointshell buildPointshell(std::span<const TriangleMesh* const> meshes,
                           std::span<const MeshFeatures> features, const PointshellOptions& options,
                           const ProgressFn& progress = {});

}  // namespace voxhap
