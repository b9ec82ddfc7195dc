// The mouse drag's geometry against hand-worked cases: a camera at z = 1 m looking down
// −z at the origin, 90° vertical field of view, 1000 pixels high, so one pixel is 2 mm in
// the plane z = 0.

#include "app/view/handle_drag.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

namespace voxhap::view {
namespace {

constexpr double kPi = 3.141592653589793;

DragView lookingDown() {
  DragView v;
  v.viewFromWorld = glm::lookAt(glm::dvec3(0.0, 0.0, 1.0), glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.0));
  v.verticalFovRad = 0.5 * kPi;
  v.viewportHeightPx = 1000.0;
  return v;
}

void expectNear(const glm::dvec3& a, const glm::dvec3& b) {
  EXPECT_NEAR(a.x, b.x, 1e-12);
  EXPECT_NEAR(a.y, b.y, 1e-12);
  EXPECT_NEAR(a.z, b.z, 1e-12);
}

TEST(HandleDrag, APlaneDragFollowsTheCursorInThePlaneOfTheGrabbedPoint) {
  Pose start;
  start.position = glm::dvec3(0.1, 0.0, 0.0);
  const HandleDrag drag(lookingDown(), start, glm::dvec3(0.0), glm::dvec2(500.0, 500.0));
  EXPECT_NEAR(drag.metresPerPixel(), 0.002, 1e-15);
  // 100 px right and 50 px down on the screen: +0.2 m in x, −0.1 m in y
  expectNear(drag.at({600.0, 550.0}, DragMode::Plane).position, glm::dvec3(0.3, -0.1, 0.0));
  expectNear(drag.at({500.0, 500.0}, DragMode::Plane).position, start.position);
}

TEST(HandleDrag, AFartherPointMovesFartherPerPixel) {
  const HandleDrag near(lookingDown(), Pose{}, glm::dvec3(0.0), glm::dvec2(0.0));
  const HandleDrag far(lookingDown(), Pose{}, glm::dvec3(0.0, 0.0, -1.0), glm::dvec2(0.0));
  EXPECT_NEAR(far.metresPerPixel(), 2.0 * near.metresPerPixel(), 1e-15);
}

TEST(HandleDrag, DraggingUpInDepthMovesAwayFromTheEye) {
  const HandleDrag drag(lookingDown(), Pose{}, glm::dvec3(0.0), glm::dvec2(500.0, 500.0));
  expectNear(drag.at({500.0, 400.0}, DragMode::Depth).position, glm::dvec3(0.0, 0.0, -0.2));
  expectNear(drag.at({700.0, 500.0}, DragMode::Depth).position, glm::dvec3(0.0));  // sideways: nothing
}

TEST(HandleDrag, ARotationTurnsAboutTheGrabbedPointWhichStaysPut) {
  Pose start;
  start.position = glm::dvec3(0.05, 0.0, 0.0);
  const glm::dvec3 anchor(0.05, 0.02, 0.0);
  const HandleDrag drag(lookingDown(), start, anchor, glm::dvec2(500.0, 500.0));
  // 500 px right, half the view height: a quarter turn (half a turn per view height) about the view's up, +y
  const Pose turned = drag.at({1000.0, 500.0}, DragMode::Rotate);
  const glm::dquat expected = glm::angleAxis(0.5 * kPi, glm::dvec3(0.0, 1.0, 0.0));
  EXPECT_NEAR(std::abs(glm::dot(turned.orientation, expected)), 1.0, 1e-12);
  // the grabbed point, fixed to the object, is where it was
  const glm::dvec3 anchorLocal = glm::conjugate(start.orientation) * (anchor - start.position);
  expectNear(turned.position + turned.orientation * anchorLocal, anchor);
}

}  // namespace
}  // namespace voxhap::view
