#include "haptics/voxel/box_overlap.h"

#include <gtest/gtest.h>

namespace voxhap {
namespace {

const glm::dvec3 kCentre(0.0);
const glm::dvec3 kHalf(0.5);

TEST(BoxOverlap, TriangleInsideOrAroundTheBoxOverlaps) {
  EXPECT_TRUE(triangleOverlapsBox({-0.1, -0.1, 0}, {0.1, -0.1, 0}, {0, 0.1, 0}, kCentre, kHalf));
  // a huge triangle whose plane cuts the box, no vertex inside
  EXPECT_TRUE(triangleOverlapsBox({-10, -10, 0.2}, {10, -10, 0.2}, {0, 10, 0.2}, kCentre, kHalf));
}

TEST(BoxOverlap, TouchingCountsAsOverlap) {
  // lies in the box's face plane z = 0.5
  EXPECT_TRUE(triangleOverlapsBox({-1, -1, 0.5}, {1, -1, 0.5}, {0, 1, 0.5}, kCentre, kHalf));
  EXPECT_FALSE(triangleOverlapsBox({-1, -1, 0.5001}, {1, -1, 0.5001}, {0, 1, 0.5001}, kCentre, kHalf));
}

TEST(BoxOverlap, PlaneJustMissingTheCornerIsSeparated) {
  // the plane x + y + z = d meets the corner (0.5, 0.5, 0.5) at d = 1.5
  const double d = 1.5 + 1e-9;
  EXPECT_FALSE(triangleOverlapsBox({d, 0, 0}, {0, d, 0}, {0, 0, d}, kCentre, kHalf));
  const double e = 1.5 - 1e-9;
  EXPECT_TRUE(triangleOverlapsBox({e, 0, 0}, {0, e, 0}, {0, 0, e}, kCentre, kHalf));
}

TEST(BoxOverlap, EdgeAxisSeparatesATriangleWhoseBoundsAndPlaneOverlap) {
  // a thin triangle passing diagonally past the box's (x+, y+) edge: bounding boxes
  // overlap, the plane (z-containing) cuts the box, only an edge × axis direction separates
  const glm::dvec3 a(1.2, 0.2, -1), b(0.2, 1.2, -1), c(0.2, 1.2, 1);
  EXPECT_FALSE(triangleOverlapsBox(a, b, c, kCentre, kHalf));
  const glm::dvec3 a2(0.9, 0.0, -1), b2(0.0, 0.9, -1), c2(0.0, 0.9, 1);
  EXPECT_TRUE(triangleOverlapsBox(a2, b2, c2, kCentre, kHalf));
}

TEST(BoxOverlap, DegenerateTriangleIsTestedAsSegments) {
  EXPECT_TRUE(triangleOverlapsBox({-2, 0, 0}, {2, 0, 0}, {0, 0, 0}, kCentre, kHalf));
  EXPECT_FALSE(triangleOverlapsBox({-2, 0.6, 0}, {2, 0.6, 0}, {0, 0.6, 0}, kCentre, kHalf));
}

TEST(BoxOverlap, SegmentsThroughPastAndTouching) {
  EXPECT_TRUE(segmentOverlapsBox({-2, 0, 0}, {2, 0.1, 0}, kCentre, kHalf));
  EXPECT_FALSE(segmentOverlapsBox({0.6, -2, 0}, {0.6, 2, 0}, kCentre, kHalf));
  EXPECT_TRUE(segmentOverlapsBox({0.5, -2, 0}, {0.5, 2, 0}, kCentre, kHalf));
  EXPECT_FALSE(segmentOverlapsBox({1, 0, 0}, {2, 0, 0}, kCentre, kHalf));             // stops short
  EXPECT_TRUE(segmentOverlapsBox({0.1, 0.1, 0.1}, {0.1, 0.1, 0.1}, kCentre, kHalf));  // a point inside
}

}  // namespace
}  // namespace voxhap
