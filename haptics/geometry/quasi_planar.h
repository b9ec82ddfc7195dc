#pragma once
/// Mesh preparation for the voxelizer (DESIGN §4.2 step 1, paper §4.1): adjacent
/// triangles are merged into quasi-planar polygons at the voxel's accuracy, and the
/// polygons' edges and corners become the feature edges and feature vertices from
/// which the edge and vertex voxels are taken.
///
/// Vertices are welded by exact position first (exporters split vertices along
/// seams), then the triangles go into an OpenMesh half-edge mesh. Triangles that
/// OpenMesh cannot hold (a third triangle on an edge, a triangle walked against its
/// neighbours, a second fan closing on a vertex) stay out of it: each is a polygon of
/// its own and all its edges are feature edges. Runs at load time on one thread;
/// different meshes may be processed from different threads at once.

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "haptics/scene/scene.h"

namespace voxhap {

/// Features of a part after quasi-planar merging, in the mesh's frame (world, m).
struct MeshFeatures {
  std::vector<std::uint32_t> polygonOfTriangle;  ///< quasi-planar polygon id per input triangle
  std::uint32_t polygonCount = 0;                ///< ids run from 0 to polygonCount - 1
  /// Segments between different polygons, plus boundary edges and every edge of a
  /// triangle the half-edge mesh refused (non-manifold or misoriented). Each
  /// undirected mesh edge appears once; a long crease is several collinear segments.
  std::vector<std::array<glm::vec3, 2>> featureEdges;
  /// Corners of the polygons: mesh vertices touching three or more polygons, ends and
  /// junctions of feature edges (not exactly two of them) and sharp turns of a
  /// feature-edge chain (the two edges meet at less than kFeatureCornerMaxAngleDeg).
  /// Each welded vertex appears once.
  std::vector<glm::vec3> featureVertices;
  std::uint64_t refusedTriangles = 0;  ///< triangles the half-edge mesh could not hold
};

/// Two feature edges meeting at a vertex at less than this angle (degrees; 180 is
/// straight on) make the vertex a polygon corner.
inline constexpr double kFeatureCornerMaxAngleDeg = 135.0;

/// Merges adjacent triangles into quasi-planar polygons (paper §4.1) for voxel size
/// `voxelSizeM` (m, > 0) and returns the feature edges and vertices. A triangle joins
/// a neighbouring polygon when its far vertex lies within half a voxel of the
/// polygon's plane and its normal turns by less than 90° both from the triangle it
/// is reached from and from the polygon's plane. Deterministic: the output depends
/// only on `mesh` and `voxelSizeM`, in a fixed order (edges in order of first use by a
/// triangle of `mesh.triangles`, then edges only refused triangles have; vertices in
/// order of first appearance in `positionsWorld`). Load time only; allocates.
MeshFeatures extractFeatures(const TriangleMesh& mesh, double voxelSizeM);

}  // namespace voxhap
