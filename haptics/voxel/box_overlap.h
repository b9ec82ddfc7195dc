#pragma once
/// Exact overlap tests of triangles and segments with axis-aligned boxes, used to
/// find the voxels a surface or a feature edge passes through.

#include <glm/vec3.hpp>

namespace voxhap {

/// True when the closed triangle (a, b, c) and the closed box centred at `boxCentre`
/// with half-size `boxHalf` share a point. Separating-axis test over the box's three
/// axes, the triangle's normal and the nine edge-cross-axis directions
/// (Akenine-Möller, "Fast 3D Triangle-Box Overlap Testing", 2001). Degenerate
/// triangles are tested as their segments.
bool triangleOverlapsBox(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                         const glm::dvec3& boxCentre, const glm::dvec3& boxHalf);

/// True when the closed segment (a, b) and the closed box share a point (slab test).
bool segmentOverlapsBox(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& boxCentre,
                        const glm::dvec3& boxHalf);

}  // namespace voxhap
