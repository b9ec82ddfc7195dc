#pragma once
/// Proximity from the distance fields (paper §3.1): how far parts of a moving object
/// are from another object, read off the other's surface distance field. Used for
/// proximity colouring, a quick minimum-distance estimate and the "shadow" of static
/// surface voxels near the moving object. Outside the fields' range nothing is known
/// but that the distance exceeds it.
///
/// A chessboard value v = 2 + d means the voxel's centre is d voxels (L∞) from the
/// nearest surface voxel's centre; the exact surface passes through that surface voxel,
/// so the Euclidean distance from the centre to the surface lies between (d − ½)·s and
/// √3·(d + ½)·s. The estimates here take d·s: within about a voxel of the truth in front
/// of a flat face, looser along diagonals. Load or UI thread only (the
/// outputs are vectors the caller may reuse).

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "haptics/dynamics/pose.h"
#include "haptics/pointshell/pointshell.h"
#include "haptics/voxel/voxmap.h"

namespace voxhap {

/// Distance returned beyond the field's range: infinity.
inline constexpr float kBeyondRange = std::numeric_limits<float>::infinity();

/// Estimated distance, m, from the point `pointVoxmap` (voxmap-local frame) to the
/// voxmap object's surface: 0 in surface and interior voxels, d·s at chessboard distance
/// d, kBeyondRange beyond the field.
float surfaceDistanceM(const Voxmap& voxmap, const glm::dvec3& pointVoxmap);

/// Per vertex of `verticesLocal` (moving object's local frame, m), at `objectToVoxmap`:
/// the estimated distance to the voxmap object, m, written to `out` (resized).
void vertexDistancesM(std::span<const glm::vec3> verticesLocal, const Pose& objectToVoxmap,
                      const Voxmap& voxmap, std::vector<float>& out);

/// Smallest estimated distance of any pointshell point to the voxmap object, m
/// (kBeyondRange when every point is beyond the field).
float minimumDistanceM(const Pointshell& shell, const Pose& shellToVoxmap, const Voxmap& voxmap);

/// The surface voxels of `staticVoxmap` whose centres lie within `distanceM` of the
/// moving object, as judged by the moving object's own surface field (`movingVoxmap`, in
/// the moving object's local frame, at `movingToStatic`). Written to `out` (cleared).
void surfaceVoxelsNear(const Voxmap& staticVoxmap, const Voxmap& movingVoxmap, const Pose& movingToStatic,
                       double distanceM, std::vector<glm::ivec3>& out);

}  // namespace voxhap
