#pragma once
/// Ground-truth penetration of a moving object into static geometry, for demos,
/// benchmarks and tests (never the 1 kHz frame): how deep the moving object's mesh
/// vertices sit inside the static triangle meshes, measured exactly with Embree.
///
/// A vertex is inside when a ray from it crosses some static part an odd number of
/// times (parity per part, so overlapping parts are fine); three skewed rays vote, two
/// or more decide, so that a ray grazing an edge cannot flip the answer. Its depth is its
/// distance to the nearest static surface point.
///
/// Casting rays for every vertex every frame would cost far more than the frame itself,
/// so the static voxmap filters first: a vertex whose static voxel is free space (value
/// ≥ 3, or far) lies in a voxel no surface passes through and that the voxelizer found
/// outside, so it is outside; only vertices in surface or interior voxels are tested
/// exactly. The filter is exact as long as the voxelizer's inside/outside votes were
/// (it warns otherwise). Vertices a few voxels out get their exact clearance instead, so
/// that a run without penetration still says how close it came. Load time: the Embree scene (allocates, may
/// throw voxhap::Error); measure(): one thread at a time, reuses its buffers.

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "haptics/dynamics/pose.h"
#include "haptics/geometry/embree_scene.h"
#include "haptics/scene/scene.h"
#include "haptics/voxel/voxmap.h"

namespace voxhap {

/// What one measurement found.
struct PenetrationSample {
  double depthM = 0.0;           ///< deepest vertex below the static surface, m (0: none inside)
  glm::dvec3 deepestWorld{0.0};  ///< that vertex, world frame, m (meaningful when depthM > 0)
  std::uint32_t candidates = 0;  ///< vertices in static surface or interior voxels, tested exactly
  std::uint32_t inside = 0;      ///< of which inside a static part
  /// Least exact distance from a vertex outside to the static surface, m, among the
  /// vertices in static voxels at most kClearanceVoxels from a surface voxel (infinite
  /// when there are none: every vertex is further than about that many voxels away).
  double clearanceM = std::numeric_limits<double>::infinity();
};

/// Vertices whose static voxel is at most this many voxels (chessboard) from a surface
/// voxel get their clearance measured exactly.
inline constexpr int kClearanceVoxels = 4;

class ExactPenetration {
public:
  /// `staticMeshes` (world frame, closed; kept by reference, must outlive this) and the
  /// moving object's vertices in its local frame (copied; exact duplicates dropped).
  ExactPenetration(std::span<const TriangleMesh* const> staticMeshes,
                   std::span<const glm::vec3> verticesLocal);

  /// The vertices placed by `objectToWorld`, filtered by `staticVoxmap` (world frame,
  /// voxelized from the same meshes) and measured exactly.
  PenetrationSample measure(const Pose& objectToWorld, const Voxmap& staticVoxmap);

  /// Whether `pointWorld` lies inside a static part (three-ray parity vote).
  bool inside(const glm::dvec3& pointWorld);

  /// Distinct vertices measured.
  std::size_t vertexCount() const { return verticesLocal_.size(); }

private:
  std::vector<TriangleMesh const*> meshes_;
  EmbreeScene scene_;
  std::vector<glm::vec3> verticesLocal_;
  double rayLengthM_ = 0.0;  // longer than the static meshes' bounding box diagonal
  std::vector<RayCrossing> hits_;
  std::vector<std::uint32_t> parts_;
};

}  // namespace voxhap
