#include "render/scene_renderer.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "haptics/core/error.h"
#include "haptics/scene/builtin/builtin_scenes.h"
#include "render/screenshot.h"
#include "tests/render/render_test_support.h"

namespace voxhap::render {
namespace {

using test::describe;
using test::kViewportPx;
using test::Pixel;

/// The wall-and-slider scene drawn by a renderer with the slider moving.
class WallAndSlider : public testing::Test {
protected:
  WallAndSlider() {
    test::glTestContext();
    renderer = std::make_unique<SceneRenderer>(scene, std::vector<std::string>{"slider"});
    camera = test::cameraFraming(renderer->sceneBounds());
  }

  RgbImage frame(bool useStaticCache) {
    renderer->draw(camera, kViewportPx, useStaticCache);
    return readFramebuffer(kViewportPx);
  }
  Pixel at(const RgbImage& image, const glm::dvec3& pointWorld) const {
    return test::pixelAt(image, camera, pointWorld);
  }
  /// The pose that puts the slider's body centre at `centreWorld`, unrotated.
  static Pose sliderAt(const glm::dvec3& centreWorld) {
    return Pose{centreWorld - test::kSliderCentre, identityQuat()};
  }
  /// Unit direction from the eye to a point.
  glm::dvec3 viewDirectionTo(const glm::dvec3& p) const { return glm::normalize(p - camera.eyeWorld()); }

  Scene scene = test::wallAndSlider();
  std::unique_ptr<SceneRenderer> renderer;
  OrbitCamera camera;
};

TEST_F(WallAndSlider, StaticPartShowsItsColourWhereItsCentreProjects) {
  const RgbImage image = frame(false);
  const Pixel wall = at(image, test::kWallCentre);
  EXPECT_TRUE(test::reddish(wall)) << describe(wall);
}

TEST_F(WallAndSlider, BackgroundWhereNothingIs) {
  const RgbImage image = frame(true);
  const glm::vec3 bg = renderer->options().backgroundDisplay;
  for (const auto& [x, y] : {std::pair{1, 1}, {kViewportPx.x - 2, 1}, {1, kViewportPx.y - 2}}) {
    const Pixel p = image.at(x, y);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(p[c], std::lround(255.0f * bg[c]), 1) << describe(p);
  }
}

TEST_F(WallAndSlider, MovingObjectAtTheIdentityPoseIsWhereTheScenePutsIt) {
  const RgbImage image = frame(true);
  const Pixel body = at(image, test::kSliderCentre);
  EXPECT_TRUE(test::bluish(body)) << describe(body);
  const Pixel cap = at(image, test::kSliderCentre + glm::dvec3(0.0, 0.0, 0.03));
  EXPECT_TRUE(test::greenish(cap)) << describe(cap);
}

TEST_F(WallAndSlider, MovingObjectDrawnAtANewPoseMovesInTheImage) {
  (void)frame(true);
  const glm::dvec3 moved = test::kSliderCentre + glm::dvec3(0.0, -0.04, 0.08);
  renderer->setPose(0, sliderAt(moved));
  const RgbImage image = frame(true);
  const Pixel there = at(image, moved);
  EXPECT_TRUE(test::bluish(there)) << describe(there);
  const Pixel before = at(image, test::kSliderCentre);
  EXPECT_FALSE(test::bluish(before)) << describe(before);
  // moving an object does not redraw the static cache
  EXPECT_EQ(renderer->stats().cache.redraws, 1u);
  EXPECT_EQ(renderer->stats().cache.reuses, 1u);
}

TEST_F(WallAndSlider, RotatedPoseMapsScenePointsAsOrientationTimesPointPlusPosition) {
  // a quarter turn about +z through the origin takes the body centre (0.12, 0, 0) to (0, -0.12, 0)
  const double half = -0.25 * std::numbers::pi;
  renderer->setPose(0, Pose{glm::dvec3(0.0), quatWxyz(std::cos(half), 0.0, 0.0, std::sin(half))});
  const RgbImage image = frame(true);
  const Pixel there = at(image, {0.0, -0.12, 0.0});
  EXPECT_TRUE(test::bluish(there)) << describe(there);
  const Pixel cap = at(image, {0.0, -0.12, 0.03});
  EXPECT_TRUE(test::greenish(cap)) << describe(cap);
}

TEST_F(WallAndSlider, CachedFrameEqualsAFullRedraw) {
  renderer->setPose(0, sliderAt(test::kSliderCentre + glm::dvec3(0.0, -0.03, 0.02)));
  const std::vector<glm::vec3> voxels = {{0.0f, -0.05f, 0.0f}, {0.02f, -0.05f, 0.0f}, {0.0f, -0.05f, 0.02f}};
  renderer->setShadowVoxels(voxels, 0.01f);
  const std::vector<glm::vec3> contacts = {{0.05f, -0.02f, 0.03f}};
  renderer->setContactPoints(contacts, 0.006f);
  renderer->setForceArrow(ForceArrow{{0.12, -0.03, 0.05}, {0.0, 0.0, 8.0}, 0.01});
  const RgbImage full = frame(false);
  const RgbImage cachedFirst = frame(true);   // redraws the cache
  const RgbImage cachedSecond = frame(true);  // reuses it
  test::keepScreenshot(full, "wall_and_slider_full");
  test::keepScreenshot(cachedSecond, "wall_and_slider_cached");
  for (const RgbImage* cached : {&cachedFirst, &cachedSecond}) {
    const test::ImageDifference d = test::compareImages(full, *cached, 2);
    EXPECT_EQ(d.pixelsOverTolerance, 0u) << "max channel difference " << d.maxChannelDifference;
  }
  EXPECT_EQ(renderer->stats().cache.redraws, 1u);
  EXPECT_EQ(renderer->stats().cache.reuses, 1u);
}

TEST_F(WallAndSlider, CacheIsReusedWhileTheEyeIsStillAndRedrawnWhenItMovesOrTheSizeChanges) {
  for (int i = 0; i < 4; ++i) {
    renderer->setPose(0, sliderAt(test::kSliderCentre + glm::dvec3(0.0, -0.01 * i, 0.0)));
    (void)frame(true);
  }
  EXPECT_EQ(renderer->stats().cache.redraws, 1u);
  EXPECT_EQ(renderer->stats().cache.reuses, 3u);
  EXPECT_EQ(renderer->stats().staticFramesDrawn, 1u);

  camera.orbit(40.0, 10.0);
  const RgbImage afterOrbit = frame(true);
  EXPECT_EQ(renderer->stats().cache.redraws, 2u);
  // what it redrew is the new view, not the old image
  const RgbImage fullAfterOrbit = frame(false);
  EXPECT_EQ(test::compareImages(afterOrbit, fullAfterOrbit, 2).pixelsOverTolerance, 0u);

  (void)frame(true);
  EXPECT_EQ(renderer->stats().cache.redraws, 2u);
  renderer->draw(camera, kViewportPx / 2, true);  // a smaller viewport
  EXPECT_EQ(renderer->stats().cache.redraws, 3u);
  EXPECT_EQ(renderer->stats().framesDrawn, 8u);
}

TEST_F(WallAndSlider, ProximityZeroIsWarmAndInfinityIsThePartsOwnColour) {
  const std::uint32_t vertices = renderer->movingVertexCount(0);
  EXPECT_EQ(vertices, 16u);  // two boxes of 8
  const glm::dvec3 cap = test::kSliderCentre + glm::dvec3(0.0, 0.0, 0.03);

  std::vector<float> touching(vertices, 0.0f);
  renderer->setProximity(0, touching);
  RgbImage image = frame(true);
  EXPECT_TRUE(test::warmRed(at(image, test::kSliderCentre))) << describe(at(image, test::kSliderCentre));
  EXPECT_TRUE(test::warmRed(at(image, cap))) << describe(at(image, cap));

  // the body (vertices 0-7) far, the cap (8-15) at a third of the range: orange
  std::vector<float> mixed(vertices, std::numeric_limits<float>::infinity());
  for (std::uint32_t v = 8; v < vertices; ++v) mixed[v] = renderer->options().proximityRangeM / 3.0f;
  renderer->setProximity(0, mixed);
  image = frame(true);
  EXPECT_TRUE(test::bluish(at(image, test::kSliderCentre))) << describe(at(image, test::kSliderCentre));
  const Pixel orange = at(image, cap);
  EXPECT_GT(orange[0], 150) << describe(orange);
  EXPECT_GT(orange[1], 60) << describe(orange);
  EXPECT_LT(orange[1], orange[0]) << describe(orange);
  EXPECT_LT(orange[2], 60) << describe(orange);

  renderer->clearProximity(0);
  image = frame(true);
  EXPECT_TRUE(test::greenish(at(image, cap))) << describe(at(image, cap));

  EXPECT_THROW(renderer->setProximity(0, std::vector<float>(vertices - 1, 0.0f)), Error);
  EXPECT_THROW(renderer->setPose(1, Pose{}), Error);
}

TEST_F(WallAndSlider, ShadowVoxelsTintTheStaticSurface) {
  // the wall's -y face, which the eye sees
  const glm::dvec3 onFace{0.0, -test::kWallHalfM, 0.0};
  const Pixel plain = at(frame(true), onFace);
  std::vector<glm::vec3> voxels;
  for (int i = -2; i <= 2; ++i) {
    for (int k = -2; k <= 2; ++k) voxels.emplace_back(0.01f * float(i), float(onFace.y), 0.01f * float(k));
  }
  renderer->setShadowVoxels(voxels, 0.01f);
  const Pixel shadowed = at(frame(true), onFace);
  EXPECT_TRUE(test::reddish(plain)) << describe(plain);
  EXPECT_GT(int(shadowed[2]), int(plain[2]) + 50) << describe(plain) << " → " << describe(shadowed);
  EXPECT_EQ(renderer->stats().cache.redraws, 1u);  // overlays are not part of the cache

  renderer->setShadowVoxels({}, 0.01f);
  const Pixel cleared = at(frame(true), onFace);
  EXPECT_EQ(cleared, plain);
}

TEST_F(WallAndSlider, MovingObjectBehindAStaticOneIsHiddenByTheCachedDepth) {
  const glm::dvec3 direction = viewDirectionTo(test::kWallCentre);
  (void)frame(true);  // the cache holds the wall
  renderer->setPose(0, sliderAt(test::kWallCentre + 0.1 * direction));
  const Pixel behind = at(frame(true), test::kWallCentre);
  EXPECT_TRUE(test::reddish(behind)) << describe(behind);
  renderer->setPose(0, sliderAt(test::kWallCentre - 0.1 * direction));
  const Pixel inFront = at(frame(true), test::kWallCentre);
  EXPECT_TRUE(test::bluish(inFront)) << describe(inFront);
  EXPECT_EQ(renderer->stats().cache.redraws, 1u);
}

TEST_F(WallAndSlider, ForceArrowAndContactPointsAppear) {
  const glm::dvec3 origin{0.12, -0.06, 0.0};
  renderer->setPose(0, sliderAt(test::kSliderCentre + glm::dvec3(0.0, 0.1, 0.0)));  // out of the way
  renderer->setForceArrow(ForceArrow{origin, {0.0, 0.0, 10.0}, 0.01});              // 10 cm up
  const glm::dvec3 contact{0.0, -0.05, -0.03};
  const std::vector<glm::vec3> contacts = {glm::vec3(contact)};
  renderer->setContactPoints(contacts, 0.008f);
  const RgbImage image = frame(true);
  const Pixel cone = at(image, origin + glm::dvec3(0.0, 0.0, 0.08));
  EXPECT_TRUE(test::greenish(cone)) << describe(cone);
  const Pixel point = at(image, contact);
  EXPECT_GT(std::min({point[0], point[1], point[2]}), 200) << describe(point);

  renderer->setForceArrow(std::nullopt);
  const Pixel gone = at(frame(true), origin + glm::dvec3(0.0, 0.0, 0.08));
  EXPECT_FALSE(test::greenish(gone)) << describe(gone);
}

TEST_F(WallAndSlider, AnotherInstanceShowsInItsOwnColourOverWhatLiesBehindIt) {
  // in front of the wall's seen face, where it hides part of it
  const glm::dvec3 there = test::kWallCentre - 0.1 * viewDirectionTo(test::kWallCentre);
  const Pixel plain = at(frame(true), test::kWallCentre);
  renderer->setOtherInstance(0, sliderAt(there));
  const RgbImage image = frame(true);
  const Pixel marked = at(image, test::kWallCentre);
  // the otherInstanceColour (orange-red) blended over the red wall: more green than the
  // wall alone, still reddish, not the slider's blue
  EXPECT_TRUE(test::reddish(plain)) << describe(plain);
  EXPECT_GT(int(marked[1]), int(plain[1]) + 20) << describe(plain) << " → " << describe(marked);
  EXPECT_FALSE(test::bluish(marked)) << describe(marked);
  // the object's own instance is still where its pose says
  EXPECT_TRUE(test::bluish(at(image, test::kSliderCentre))) << describe(at(image, test::kSliderCentre));
  EXPECT_EQ(renderer->stats().cache.redraws, 1u);

  renderer->setOtherInstance(0, std::nullopt);
  EXPECT_EQ(at(frame(true), test::kWallCentre), plain);
  EXPECT_THROW(renderer->setOtherInstance(1, Pose{}), Error);
}

TEST(SceneRenderer, UnknownMovingObjectIsAClearError) {
  test::glTestContext();
  const Scene scene = test::wallAndSlider();
  try {
    SceneRenderer renderer(scene, std::vector<std::string>{"actuator"});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no object named actuator"), std::string::npos) << e.what();
  }
}

/// Which of two colours (display values) a pixel is nearer to in direction (hue and
/// saturation, not brightness, which the lighting changes).
bool nearerInHue(const Pixel& p, const glm::vec3& a, const glm::vec3& b) {
  const glm::vec3 v = glm::normalize(glm::vec3(p[0], p[1], p[2]) + 1e-3f);
  return glm::dot(v, glm::normalize(a)) > glm::dot(v, glm::normalize(b));
}

glm::vec3 displayOf(const glm::vec4& linear) {
  const auto encode = [](float c) {
    return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
  };
  return {encode(linear.r), encode(linear.g), encode(linear.b)};
}

TEST(SceneRenderer, BuiltInBallAndSocketShowsTheBallInItsColourAndWarmWhenTouching) {
  test::glTestContext();
  const Scene scene = makeBallAndSocket();
  const SceneObject& ball = *scene.find("ball");
  const SceneObject& socket = *scene.find("socket");
  SceneRenderer renderer(scene, std::vector<std::string>{"ball"});
  OrbitCamera camera;
  camera.setAngles(0.4, 1.0);  // from above: the socket's rim does not hide the ball's centre
  camera.frame(renderer.sceneBounds(), double(kViewportPx.x) / kViewportPx.y);
  const Bounds ballBounds = ball.bounds();
  const glm::dvec3 ballCentre = 0.5 * (ballBounds.min + ballBounds.max);
  const Bounds socketBounds = socket.bounds();
  // a point on the socket's outer wall, on the eye's side, a little below the rim
  const glm::dvec3 socketSide =
      glm::dvec3(ballCentre.x, ballCentre.y,
                 socketBounds.min.z + 0.3 * (socketBounds.max.z - socketBounds.min.z)) -
      0.98 * (0.5 * (socketBounds.max.x - socketBounds.min.x)) *
          glm::normalize(glm::dvec3(camera.forwardWorld().x, camera.forwardWorld().y, 0.0));

  renderer.draw(camera, kViewportPx, false);
  const RgbImage full = readFramebuffer(kViewportPx);
  renderer.draw(camera, kViewportPx, true);
  const RgbImage cached = readFramebuffer(kViewportPx);
  EXPECT_EQ(test::compareImages(full, cached, 2).pixelsOverTolerance, 0u);

  test::keepScreenshot(cached, "ball_and_socket");
  const Pixel ballPixel = test::pixelAt(cached, camera, ballCentre);
  const Pixel socketPixel = test::pixelAt(cached, camera, socketSide);
  const glm::vec3 ballDisplay = displayOf(ball.parts[0].baseColor);
  const glm::vec3 socketDisplay = displayOf(socket.parts[0].baseColor);
  EXPECT_TRUE(nearerInHue(ballPixel, ballDisplay, socketDisplay)) << describe(ballPixel);
  EXPECT_TRUE(nearerInHue(socketPixel, socketDisplay, ballDisplay)) << describe(socketPixel);

  renderer.setProximity(0, std::vector<float>(renderer.movingVertexCount(0), 0.0f));
  renderer.draw(camera, kViewportPx, true);
  const Pixel touching = test::pixelAt(readFramebuffer(kViewportPx), camera, ballCentre);
  EXPECT_TRUE(test::warmRed(touching)) << describe(touching);
  EXPECT_EQ(renderer.stats().cache.redraws, 1u);
  EXPECT_EQ(renderer.stats().cache.reuses, 1u);
}

}  // namespace
}  // namespace voxhap::render
