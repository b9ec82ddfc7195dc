#pragma once
/// The mouse as the paper's 2-DOF device (§2, Fig. 1): a drag moves the held object's
/// handle in the view plane through the point the user grabbed it by; with a modifier it
/// moves it in depth, with another it turns it about that point. Pure geometry, no GL: the
/// window sends the result to the controller as a handle pose (move_handle), and the
/// coupling pulls the object after it, so a user without a device feels MaxTravel's
/// viscosity as lag.

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

#include "haptics/dynamics/pose.h"

namespace voxhap::view {

/// The camera a drag is seen through.
struct DragView {
  glm::dmat4 viewFromWorld{1.0};  ///< rigid: world → camera (camera looks down its −z)
  double verticalFovRad = 0.8;    ///< full vertical field of view, rad
  double viewportHeightPx = 720;  ///< > 0
};

enum class DragMode {
  Plane,   ///< parallel to the view plane, through the grabbed point
  Depth,   ///< along the line of sight: dragging up moves away
  Rotate,  ///< about the grabbed point: horizontal motion about the view's up, vertical about its right
};

class HandleDrag {
public:
  /// Starts a drag of a handle at `startWorld`, grabbed by the point `anchorWorld` (on the
  /// object, under the cursor), with the cursor at `startPx` (window pixels, y down).
  HandleDrag(const DragView& view, const Pose& startWorld, const glm::dvec3& anchorWorld,
             const glm::dvec2& startPx);

  /// The handle pose for the cursor at `cursorPx`, moved from the start in `mode`. A new
  /// mode mid-drag starts a new drag from the pose reached (the window's job).
  Pose at(const glm::dvec2& cursorPx, DragMode mode) const;

  /// Metres the handle moves per pixel in the plane through the grabbed point.
  double metresPerPixel() const noexcept { return metresPerPixel_; }

private:
  Pose start_;
  glm::dvec3 anchorWorld_;
  glm::dvec2 startPx_;
  glm::dvec3 rightWorld_;    ///< the view's +x
  glm::dvec3 upWorld_;       ///< the view's +y
  glm::dvec3 forwardWorld_;  ///< the line of sight (the view's −z)
  double metresPerPixel_;
  double radiansPerPixel_;
};

}  // namespace voxhap::view
