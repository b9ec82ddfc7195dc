#pragma once
/// Probe points on the surface of a triangle mesh, for exact penetration measurements
/// (exact_penetration.h): every triangle sampled at a given spacing, its vertices, its
/// edges and its interior, so that a measurement sees faces, not only vertices.
///
/// The sampling is a fixed function of the triangle's three vertices and the spacing h:
///   * each edge: ceil(length / h) equal steps from its lexicographically smaller end,
///     both ends included, so that the two triangles sharing an edge make the same
///     points bit for bit (exact duplicates, dropped by whoever collects them);
///   * the interior: rows parallel to the longest edge (the base), ceil(height / h)
///     equal steps from the base to the opposite vertex, each row (the base and the
///     vertex excepted) split into ceil(row length / h) equal steps, its two ends (on
///     the other edges) excepted.
/// Neighbouring probes are at most h apart along an edge or a row, rows at most h apart:
/// every surface point lies within about h of a probe. A sliver triangle gets about
/// area / h² + perimeter / h probes, not (longest edge / h)².
///
/// A clip box restricts the output to the probes inside it (and does so cheaply for a
/// large triangle): the probes of a box are exactly those of the whole triangle that lie
/// in it, so that a surface can be probed region by region on demand.

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace voxhap {

/// One probe point.
struct SurfaceProbe {
  glm::vec3 pointLocal;  ///< on the triangle, the mesh's frame, m
  bool onEdge;           ///< on an edge or at a vertex (else inside the triangle)
};

/// An axis-aligned box, closed, the mesh's frame, m.
struct ProbeClipBox {
  glm::dvec3 min;
  glm::dvec3 max;
};

/// Appends the probes of triangle (a, b, c) (the mesh's frame, m) at spacing `spacingM`
/// (> 0) to `out`, only those in `clip` when it is given. Edge probes come out once per
/// triangle, so shared edges and vertices appear once per triangle that has them.
void appendTriangleProbes(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, double spacingM,
                          const ProbeClipBox* clip, std::vector<SurfaceProbe>& out);

/// How many probes appendTriangleProbes makes for the whole triangle, about (for
/// deciding, before sampling, whether a surface is small enough to probe whole).
double estimateTriangleProbes(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, double spacingM);

}  // namespace voxhap
