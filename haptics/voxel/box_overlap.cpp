#include "haptics/voxel/box_overlap.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace voxhap {
namespace {

/// Whether `axis` separates the triangle (vertices relative to the box centre) from the box.
bool separates(const glm::dvec3& axis, const glm::dvec3& v0, const glm::dvec3& v1, const glm::dvec3& v2,
               const glm::dvec3& half) {
  const double p0 = glm::dot(axis, v0);
  const double p1 = glm::dot(axis, v1);
  const double p2 = glm::dot(axis, v2);
  const double radius = half.x * std::abs(axis.x) + half.y * std::abs(axis.y) + half.z * std::abs(axis.z);
  return std::min({p0, p1, p2}) > radius || std::max({p0, p1, p2}) < -radius;
}

}  // namespace

bool segmentOverlapsBox(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& boxCentre,
                        const glm::dvec3& boxHalf) {
  double t0 = 0.0;
  double t1 = 1.0;
  const glm::dvec3 d = b - a;
  for (int k = 0; k < 3; ++k) {
    const double lo = boxCentre[k] - boxHalf[k];
    const double hi = boxCentre[k] + boxHalf[k];
    if (d[k] == 0.0) {
      if (a[k] < lo || a[k] > hi) return false;
      continue;
    }
    double ta = (lo - a[k]) / d[k];
    double tb = (hi - a[k]) / d[k];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  return true;
}

bool triangleOverlapsBox(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                         const glm::dvec3& boxCentre, const glm::dvec3& boxHalf) {
  const glm::dvec3 v0 = a - boxCentre;
  const glm::dvec3 v1 = b - boxCentre;
  const glm::dvec3 v2 = c - boxCentre;
  const glm::dvec3 e[3] = {v1 - v0, v2 - v1, v0 - v2};
  const glm::dvec3 normal = glm::cross(e[0], e[1]);
  if (normal == glm::dvec3(0.0)) {
    return segmentOverlapsBox(a, b, boxCentre, boxHalf) || segmentOverlapsBox(b, c, boxCentre, boxHalf) ||
           segmentOverlapsBox(c, a, boxCentre, boxHalf);
  }
  // the box's face normals: the triangle's bounding box against the box
  for (int k = 0; k < 3; ++k) {
    if (std::min({v0[k], v1[k], v2[k]}) > boxHalf[k] || std::max({v0[k], v1[k], v2[k]}) < -boxHalf[k]) {
      return false;
    }
  }
  // the triangle's plane
  const double planeDistance = glm::dot(normal, v0);
  const double planeRadius =
      boxHalf.x * std::abs(normal.x) + boxHalf.y * std::abs(normal.y) + boxHalf.z * std::abs(normal.z);
  if (std::abs(planeDistance) > planeRadius) return false;
  // the nine cross products of triangle edges and box axes
  const glm::dvec3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (const glm::dvec3& edge : e) {
    for (const glm::dvec3& axis : axes) {
      const glm::dvec3 direction = glm::cross(edge, axis);
      if (direction != glm::dvec3(0.0) && separates(direction, v0, v1, v2, boxHalf)) return false;
    }
  }
  return true;
}

}  // namespace voxhap
