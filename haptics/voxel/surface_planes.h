#pragma once
/// Surface planes of a voxmap (surface_plane.h), computed at voxelization from the
/// meshes the voxmap was made of.
///
/// For every voxel of a mixed chunk whose surface field reads interior, surface or free
/// within kSurfacePlaneLayers voxels, the nearest point q of the meshes to the voxel's
/// centre c (Embree, over every part) gives φ_c = ±|c − q| and n_c: (c − q)/|c − q| outside,
/// the reverse inside, the angle-weighted pseudo-normal at q where c lies on the surface.
/// Inside or outside comes from the voxel's field (interior, or free); a surface voxel's
/// centre takes the side of q's pseudo-normal. Interior voxels further than
/// kSurfacePlaneReachVoxels from every triangle, and all others, get none.
///
/// How well φ(p) ≈ φ_c + (p − c)·n_c holds for a point p of the voxel (|p − c| ≤ 0.87
/// voxel): exactly where the nearest feature is a face on both sides of the plane; the
/// distance outside a convex part is a convex function, so near its edges and corners the
/// plane gives less than the truth (the parts kept further apart, never closer); only
/// near a concave edge or corner (an inside corner of a bracket), where the nearest face
/// changes within the voxel, may it give more, by at most |p − c| times the change of n.
///
/// Load time only: parallel over blocks, the same bits whatever the thread count.

#include <span>
#include <vector>

#include "haptics/core/progress.h"
#include "haptics/geometry/embree_scene.h"
#include "haptics/scene/scene.h"
#include "haptics/voxel/surface_plane.h"
#include "haptics/voxel/voxmap.h"

namespace voxhap {

/// Free-space layers (beyond the surface voxels) that get planes: enough for contact at
/// up to a voxel and the layer beyond it (pre-contact damping).
inline constexpr int kSurfacePlaneLayers = 2;
/// How far from the surface, in voxels, an interior voxel may lie and still get a plane:
/// a point deeper than that is held by its voxel's tangent plane (tangent_plane_force.h).
/// The queries of deeper voxels took most of the planes' time: the landing gear at 2.5 mm,
/// first voxelization, 61 s with 6 voxels, 37 s with 2 (voxel planes alone: 10 s).
inline constexpr double kSurfacePlaneReachVoxels = 2.0;

/// The planes of `voxmap` (unpaged, voxelized from `meshes`, its local frame), in the
/// order Voxmap::setSurfacePlanes takes; `scene` is an EmbreeScene of the same meshes.
SparseSurfacePlanes computeSurfacePlanes(const Voxmap& voxmap, std::span<const TriangleMesh* const> meshes,
                                         const EmbreeScene& scene, int threads,
                                         const ProgressFn& progress = {});

}  // namespace voxhap
