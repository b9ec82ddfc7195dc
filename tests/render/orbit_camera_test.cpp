#include "render/orbit_camera.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

namespace voxhap::render {
namespace {

constexpr glm::ivec2 kViewport{640, 480};

Bounds boxBounds(const glm::dvec3& min, const glm::dvec3& max) {
  Bounds b;
  b.add(min);
  b.add(max);
  return b;
}

TEST(OrbitCamera, FramePutsTheBoxCentreInTheMiddleAndEveryCornerInView) {
  const Bounds box = boxBounds({1.0, 2.0, 3.0}, {1.4, 2.1, 3.9});
  for (double yaw : {-2.0, 0.0, 0.7, 3.0}) {
    OrbitCamera camera;
    camera.setAngles(yaw, 0.4);
    camera.frame(box, double(kViewport.x) / kViewport.y);
    const ScreenPoint centre = camera.project(0.5 * (box.min + box.max), kViewport);
    EXPECT_NEAR(centre.pixelPx.x, kViewport.x / 2.0, 1e-6);
    EXPECT_NEAR(centre.pixelPx.y, kViewport.y / 2.0, 1e-6);
    for (int corner = 0; corner < 8; ++corner) {
      const glm::dvec3 p((corner & 1) ? box.max.x : box.min.x, (corner & 2) ? box.max.y : box.min.y,
                         (corner & 4) ? box.max.z : box.min.z);
      const ScreenPoint s = camera.project(p, kViewport);
      EXPECT_TRUE(s.inFront);
      EXPECT_GT(s.pixelPx.x, 0.0);
      EXPECT_LT(s.pixelPx.x, kViewport.x);
      EXPECT_GT(s.pixelPx.y, 0.0);
      EXPECT_LT(s.pixelPx.y, kViewport.y);
      // between the near and far planes
      EXPECT_GT(s.depthNdc, -1.0);
      EXPECT_LT(s.depthNdc, 1.0);
    }
  }
}

TEST(OrbitCamera, UpInTheWorldIsUpOnTheScreen) {
  OrbitCamera camera;
  camera.setAngles(0.3, 0.2);
  camera.frame(boxBounds({-1, -1, -1}, {1, 1, 1}));
  const ScreenPoint low = camera.project({0, 0, -0.5}, kViewport);
  const ScreenPoint high = camera.project({0, 0, 0.5}, kViewport);
  EXPECT_LT(high.pixelPx.y, low.pixelPx.y);  // rows grow downward
  // the eye's right is on the right of the screen
  const ScreenPoint right = camera.project(camera.targetWorld() + 0.3 * camera.rightWorld(), kViewport);
  EXPECT_GT(right.pixelPx.x, kViewport.x / 2.0);
}

TEST(OrbitCamera, RayThroughAProjectedPixelPassesThroughThePoint) {
  OrbitCamera camera;
  camera.setAngles(1.1, -0.3);
  camera.frame(boxBounds({0, 0, 0}, {2, 1, 1}), 4.0 / 3.0);
  const glm::dvec3 point{1.7, 0.2, 0.9};
  const ScreenPoint s = camera.project(point, kViewport);
  const RayWorld ray = camera.rayThroughPixel(s.pixelPx, kViewport);
  EXPECT_NEAR(glm::length(ray.directionWorld), 1.0, 1e-12);
  const glm::dvec3 toPoint = point - ray.originWorld;
  const double along = glm::dot(toPoint, ray.directionWorld);
  EXPECT_GT(along, 0.0);
  EXPECT_NEAR(glm::length(toPoint - along * ray.directionWorld), 0.0, 1e-9);
  // the centre pixel's ray is the view direction
  const RayWorld centre = camera.rayThroughPixel(glm::dvec2(kViewport) * 0.5, kViewport);
  EXPECT_NEAR(glm::dot(centre.directionWorld, camera.forwardWorld()), 1.0, 1e-12);
}

TEST(OrbitCamera, OrbitKeepsTheTargetAndDistanceAndTurnsTheEye) {
  OrbitCamera camera;
  camera.setTarget({1, 2, 3});
  camera.setDistance(2.0);
  const glm::dvec3 eyeBefore = camera.eyeWorld();
  camera.orbit(100.0, 40.0);
  EXPECT_NEAR(glm::length(camera.eyeWorld() - camera.targetWorld()), 2.0, 1e-12);
  EXPECT_GT(glm::length(camera.eyeWorld() - eyeBefore), 0.1);
  EXPECT_EQ(camera.targetWorld(), glm::dvec3(1, 2, 3));
  camera.orbit(0.0, 1e6);  // pitch is clamped short of straight down
  EXPECT_LE(camera.pitchRad(), OrbitCamera::kPitchLimitRad);
  EXPECT_TRUE(std::isfinite(camera.viewMatrix()[0][0]));
}

TEST(OrbitCamera, PanMovesTheTargetWithTheCursorAndZoomScalesTheDistance) {
  OrbitCamera camera;
  camera.frame(boxBounds({-1, -1, -1}, {1, 1, 1}));
  const glm::dvec3 anchor = camera.targetWorld();
  const ScreenPoint before = camera.project(anchor, kViewport);
  camera.pan(30.0, -20.0, kViewport);
  const ScreenPoint after = camera.project(anchor, kViewport);
  // the point under the cursor follows it
  EXPECT_NEAR(after.pixelPx.x - before.pixelPx.x, 30.0, 1e-6);
  EXPECT_NEAR(after.pixelPx.y - before.pixelPx.y, -20.0, 1e-6);
  const double d = camera.distanceM();
  camera.zoom(0.5);
  EXPECT_DOUBLE_EQ(camera.distanceM(), 0.5 * d);
  camera.zoom(0.0);  // ignored
  EXPECT_DOUBLE_EQ(camera.distanceM(), 0.5 * d);
}

TEST(OrbitCamera, EveryChangeOfTheEyeBumpsTheRevision) {
  OrbitCamera camera;
  std::uint64_t last = camera.revision();
  const auto bumped = [&] {
    const bool b = camera.revision() > last;
    last = camera.revision();
    return b;
  };
  camera.orbit(1, 0);
  EXPECT_TRUE(bumped());
  camera.pan(1, 1, kViewport);
  EXPECT_TRUE(bumped());
  camera.zoom(1.1);
  EXPECT_TRUE(bumped());
  camera.frame(boxBounds({0, 0, 0}, {1, 1, 1}));
  EXPECT_TRUE(bumped());
  (void)camera.viewProjection(kViewport);
  EXPECT_FALSE(bumped());
}

}  // namespace
}  // namespace voxhap::render
