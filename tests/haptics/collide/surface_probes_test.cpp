#include "haptics/collide/surface_probes.h"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

namespace voxhap {
namespace {

double nearestProbeM(const std::vector<SurfaceProbe>& probes, const glm::dvec3& p) {
  double best = 1e300;
  for (const SurfaceProbe& probe : probes)
    best = std::min(best, glm::length(glm::dvec3(probe.pointLocal) - p));
  return best;
}

bool lexLess(const glm::vec3& p, const glm::vec3& q) {
  return std::tie(p.x, p.y, p.z) < std::tie(q.x, q.y, q.z);
}

std::vector<glm::vec3> sortedPoints(const std::vector<SurfaceProbe>& probes) {
  std::vector<glm::vec3> points;
  for (const SurfaceProbe& probe : probes) points.push_back(probe.pointLocal);
  std::sort(points.begin(), points.end(), lexLess);
  points.erase(std::unique(points.begin(), points.end()), points.end());
  return points;
}

TEST(SurfaceProbes, EverySurfacePointIsWithinTheSpacingOfAProbe) {
  constexpr double kSpacing = 0.001;
  // a fat triangle and a sliver 40 mm long and 0.7 mm high
  const glm::vec3 triangles[][3] = {{{0.0f, 0.0f, 0.0f}, {0.013f, 0.002f, 0.001f}, {0.004f, 0.011f, -0.002f}},
                                    {{0.0f, 0.0f, 0.0f}, {0.04f, 0.0f, 0.0f}, {0.013f, 0.0007f, 0.0f}}};
  for (const auto& t : triangles) {
    std::vector<SurfaceProbe> probes;
    appendTriangleProbes(t[0], t[1], t[2], kSpacing, nullptr, probes);
    const glm::dvec3 a(t[0]), b(t[1]), c(t[2]);
    for (int i = 0; i <= 40; ++i) {
      for (int j = 0; i + j <= 40; ++j) {
        const double u = i / 40.0;
        const double v = j / 40.0;
        EXPECT_LE(nearestProbeM(probes, a + u * (b - a) + v * (c - a)), kSpacing) << u << " " << v;
      }
    }
    // vertices exactly, every probe on the triangle's plane
    for (const glm::vec3& vertex : t) EXPECT_EQ(nearestProbeM(probes, glm::dvec3(vertex)), 0.0);
    const glm::dvec3 n = glm::normalize(glm::cross(b - a, c - a));
    for (const SurfaceProbe& probe : probes)
      EXPECT_NEAR(glm::dot(glm::dvec3(probe.pointLocal) - a, n), 0.0, 1e-8);
    // a sliver takes about area / h² + perimeter / h, not (longest edge / h)²
    EXPECT_LT(static_cast<double>(probes.size()), 2.0 * estimateTriangleProbes(t[0], t[1], t[2], kSpacing));
  }
}

TEST(SurfaceProbes, TrianglesSharingAnEdgeMakeTheSameProbesOnIt) {
  const glm::vec3 p(0.001f, 0.002f, 0.0f);
  const glm::vec3 q(0.0173f, 0.0051f, 0.0003f);
  std::vector<SurfaceProbe> first;
  std::vector<SurfaceProbe> second;
  appendTriangleProbes(p, q, {0.004f, 0.013f, 0.0f}, 0.0007, nullptr, first);
  appendTriangleProbes(q, p, {0.009f, -0.011f, 0.001f}, 0.0007, nullptr, second);
  auto onEdge = [&](const std::vector<SurfaceProbe>& probes) {
    std::vector<SurfaceProbe> kept;
    const glm::dvec3 d = glm::normalize(glm::dvec3(q) - glm::dvec3(p));
    for (const SurfaceProbe& probe : probes) {
      const glm::dvec3 r = glm::dvec3(probe.pointLocal) - glm::dvec3(p);
      if (probe.onEdge && glm::length(r - glm::dot(r, d) * d) < 1e-9) kept.push_back(probe);
    }
    return sortedPoints(kept);
  };
  const std::vector<glm::vec3> a = onEdge(first);
  ASSERT_GT(a.size(), 20u);
  EXPECT_EQ(a, onEdge(second));  // bit for bit
}

TEST(SurfaceProbes, AClipBoxKeepsExactlyTheWholeTrianglesProbesInIt) {
  const glm::vec3 a(0.0f, 0.0f, 0.0f), b(0.05f, 0.01f, 0.0f), c(0.01f, 0.04f, 0.01f);
  std::vector<SurfaceProbe> whole;
  appendTriangleProbes(a, b, c, 0.0009, nullptr, whole);
  const ProbeClipBox box{{0.012, 0.007, -1.0}, {0.021, 0.019, 1.0}};
  std::vector<SurfaceProbe> clipped;
  appendTriangleProbes(a, b, c, 0.0009, &box, clipped);
  std::vector<SurfaceProbe> expected;
  for (const SurfaceProbe& probe : whole) {
    const glm::dvec3 p(probe.pointLocal);
    if (p.x >= box.min.x && p.y >= box.min.y && p.x <= box.max.x && p.y <= box.max.y)
      expected.push_back(probe);
  }
  ASSERT_GT(expected.size(), 50u);
  EXPECT_EQ(sortedPoints(clipped), sortedPoints(expected));
}

}  // namespace
}  // namespace voxhap
