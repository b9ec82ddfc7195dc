#pragma once
/// Edge topology of triangle meshes: closed? consistently oriented? where open?
///
/// Vertices are welded by exact position first, because exporters split vertices
/// along normal and texture seams; a mesh that is closed as a surface is then
/// closed here too.

#include "haptics/scene/scene.h"

namespace voxhap {

/// Counts boundary, non-manifold and misoriented edges of `mesh` after welding
/// vertices with bit-identical positions (+0 and -0 are equal). Deterministic.
MeshTopology computeTopology(const TriangleMesh& mesh);

/// Signed volume enclosed by `mesh`, m³: positive when a closed mesh faces outward.
double signedVolume(const TriangleMesh& mesh);

}  // namespace voxhap
