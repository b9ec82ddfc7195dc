#include "haptics/collide/surface_probes.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include <glm/geometric.hpp>

namespace voxhap {
namespace {

/// Steps of at most `spacingM` over `lengthM`: at least 1, capped so that a count fits.
std::int64_t stepsOver(double lengthM, double spacingM) {
  const double steps = std::ceil(lengthM / spacingM);
  return static_cast<std::int64_t>(std::clamp(steps, 1.0, 1e9));
}

bool lexLess(const glm::vec3& p, const glm::vec3& q) {
  return std::tie(p.x, p.y, p.z) < std::tie(q.x, q.y, q.z);
}

bool inBox(const glm::vec3& p, const ProbeClipBox& box) {
  return p.x >= box.min.x && p.y >= box.min.y && p.z >= box.min.z && p.x <= box.max.x && p.y <= box.max.y &&
         p.z <= box.max.z;
}

/// Indices j in [first, last] of the points from + (to − from)·j/steps that may lie in
/// `box` (slab clipping, widened a little: the caller tests each point exactly). Empty
/// when first > last on return.
void clipIndices(const glm::dvec3& from, const glm::dvec3& to, std::int64_t steps, const ProbeClipBox* box,
                 std::int64_t& first, std::int64_t& last) {
  if (!box) return;
  double t0 = 0.0;
  double t1 = 1.0;
  const glm::dvec3 d = to - from;
  for (int axis = 0; axis < 3; ++axis) {
    const double margin = 1e-9 * (std::abs(box->max[axis]) + std::abs(box->min[axis]) + 1.0);
    const double lo = box->min[axis] - margin;
    const double hi = box->max[axis] + margin;
    if (d[axis] == 0.0) {
      if (from[axis] < lo || from[axis] > hi) {
        first = last + 1;
        return;
      }
      continue;
    }
    double a = (lo - from[axis]) / d[axis];
    double b = (hi - from[axis]) / d[axis];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
  }
  if (t0 > t1) {
    first = last + 1;
    return;
  }
  const double n = static_cast<double>(steps);
  first = std::max(first, static_cast<std::int64_t>(std::floor(t0 * n)));
  last = std::min(last, static_cast<std::int64_t>(std::ceil(t1 * n)));
}

/// The point j of `steps` from `from` to `to`, ends exact.
glm::vec3 stepPoint(const glm::dvec3& from, const glm::dvec3& to, std::int64_t j, std::int64_t steps) {
  if (j == 0) return glm::vec3(from);
  if (j == steps) return glm::vec3(to);
  return glm::vec3(from + (to - from) * (static_cast<double>(j) / static_cast<double>(steps)));
}

void appendEdge(glm::vec3 p, glm::vec3 q, double spacingM, const ProbeClipBox* clip,
                std::vector<SurfaceProbe>& out) {
  if (lexLess(q, p)) std::swap(p, q);
  const glm::dvec3 from(p);
  const glm::dvec3 to(q);
  const std::int64_t steps = stepsOver(glm::length(to - from), spacingM);
  std::int64_t first = 0;
  std::int64_t last = steps;
  clipIndices(from, to, steps, clip, first, last);
  for (std::int64_t j = first; j <= last; ++j) {
    const glm::vec3 point = stepPoint(from, to, j, steps);
    if (!clip || inBox(point, *clip)) out.push_back({point, true});
  }
}

}  // namespace

void appendTriangleProbes(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, double spacingM,
                          const ProbeClipBox* clip, std::vector<SurfaceProbe>& out) {
  appendEdge(a, b, spacingM, clip, out);
  appendEdge(b, c, spacingM, clip, out);
  appendEdge(c, a, spacingM, clip, out);

  // the base: the longest edge, the first of (ab, bc, ca) on a tie
  const glm::dvec3 v[3] = {glm::dvec3(a), glm::dvec3(b), glm::dvec3(c)};
  int base = 0;
  double baseLength = -1.0;
  for (int e = 0; e < 3; ++e) {
    const double length = glm::length(v[(e + 1) % 3] - v[e]);
    if (length > baseLength) {
      baseLength = length;
      base = e;
    }
  }
  const glm::dvec3& p0 = v[base];
  const glm::dvec3& p1 = v[(base + 1) % 3];
  const glm::dvec3& apex = v[(base + 2) % 3];
  if (!(baseLength > 0.0)) return;
  const double heightM = glm::length(glm::cross(p1 - p0, apex - p0)) / baseLength;
  if (!(heightM > 0.0)) return;
  const std::int64_t rows = stepsOver(heightM, spacingM);
  for (std::int64_t k = 1; k < rows; ++k) {
    const double t = static_cast<double>(k) / static_cast<double>(rows);
    const glm::dvec3 left = p0 + (apex - p0) * t;
    const glm::dvec3 right = p1 + (apex - p1) * t;
    const std::int64_t steps = stepsOver((1.0 - t) * baseLength, spacingM);
    std::int64_t first = 1;
    std::int64_t last = steps - 1;
    if (first > last) continue;
    clipIndices(left, right, steps, clip, first, last);
    for (std::int64_t j = first; j <= last; ++j) {
      const glm::vec3 point = stepPoint(left, right, j, steps);
      if (!clip || inBox(point, *clip)) out.push_back({point, false});
    }
  }
}

double estimateTriangleProbes(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, double spacingM) {
  const glm::dvec3 pa(a);
  const glm::dvec3 pb(b);
  const glm::dvec3 pc(c);
  const double areaM2 = 0.5 * glm::length(glm::cross(pb - pa, pc - pa));
  const double perimeterM = glm::length(pb - pa) + glm::length(pc - pb) + glm::length(pa - pc);
  return areaM2 / (spacingM * spacingM) + perimeterM / spacingM + 3.0;
}

}  // namespace voxhap
