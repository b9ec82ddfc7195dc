#include "app/view/handle_drag.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/quaternion.hpp>

namespace voxhap::view {
namespace {

/// A drag across the whole height of the view turns the object half a turn.
constexpr double kRadiansPerViewHeight = 3.141592653589793;
/// The plane is never taken nearer the eye than this, m (a point behind or at the eye).
constexpr double kMinDepthM = 1e-3;

}  // namespace

HandleDrag::HandleDrag(const DragView& view, const Pose& startWorld, const glm::dvec3& anchorWorld,
                       const glm::dvec2& startPx)
    : start_(startWorld), anchorWorld_(anchorWorld), startPx_(startPx) {
  // the rows of the view's rotation are the camera's axes in world coordinates
  const glm::dmat4& v = view.viewFromWorld;
  rightWorld_ = glm::dvec3(v[0][0], v[1][0], v[2][0]);
  upWorld_ = glm::dvec3(v[0][1], v[1][1], v[2][1]);
  forwardWorld_ = -glm::dvec3(v[0][2], v[1][2], v[2][2]);
  const double depthM = std::max(kMinDepthM, -(v * glm::dvec4(anchorWorld, 1.0)).z);
  metresPerPixel_ = 2.0 * depthM * std::tan(0.5 * view.verticalFovRad) / view.viewportHeightPx;
  radiansPerPixel_ = kRadiansPerViewHeight / view.viewportHeightPx;
}

Pose HandleDrag::at(const glm::dvec2& cursorPx, DragMode mode) const {
  const glm::dvec2 d = cursorPx - startPx_;  // pixels, y down
  Pose pose = start_;
  switch (mode) {
    case DragMode::Plane:
      pose.position += metresPerPixel_ * (d.x * rightWorld_ - d.y * upWorld_);
      break;
    case DragMode::Depth:
      pose.position += metresPerPixel_ * (-d.y) * forwardWorld_;
      break;
    case DragMode::Rotate: {
      // the axis perpendicular to the drag in the view plane, as on a trackball
      const glm::dvec3 axis = d.x * upWorld_ + d.y * rightWorld_;
      const double length = glm::length(axis);
      if (length == 0.0) break;
      const glm::dquat turn = glm::angleAxis(radiansPerPixel_ * glm::length(d), axis / length);
      pose.orientation = glm::normalize(turn * start_.orientation);
      pose.position = anchorWorld_ + turn * (start_.position - anchorWorld_);
      break;
    }
  }
  return pose;
}

}  // namespace voxhap::view
