#pragma once
/// An orbiting camera for a Z-up world (no GL): it looks at a target from a distance,
/// turned by yaw about world +z and pitched above the xy plane.
///
/// Pixels are window pixels: origin at the top-left corner, x right, y down (like GLFW's
/// cursor and the rows of a screenshot); the centre of pixel (i, j) is (i + 0.5, j + 0.5).
/// Every change of the eye or the lens bumps `revision()`, so a caller (the static cache,
/// a redraw-on-demand loop) knows when the view moved.

#include <cstdint>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "haptics/scene/scene.h"

namespace voxhap::render {

/// A half-line in the world frame: originWorld + t · directionWorld, t ≥ 0.
struct RayWorld {
  glm::dvec3 originWorld{0.0};
  glm::dvec3 directionWorld{0.0, 0.0, -1.0};  ///< unit
};

/// Where a world point lands on the screen.
struct ScreenPoint {
  glm::dvec2 pixelPx{0.0};  ///< window pixels, y down
  double depthNdc = 0.0;    ///< -1 at the near plane, +1 at the far plane
  bool inFront = false;     ///< the point is in front of the eye
};

/// Orbit, pan and zoom around a target; view and perspective matrices for GL.
class OrbitCamera {
public:
  /// Vertical field of view, rad.
  static constexpr double kFovYRad = 0.7853981633974483;  // 45°
  /// Orbit per pixel of mouse motion, rad.
  static constexpr double kOrbitRadPerPx = 0.005;
  /// Pitch stays this far from straight up or down, rad, so that "up" stays defined.
  static constexpr double kPitchLimitRad = 1.55;

  glm::dvec3 targetWorld() const { return targetWorld_; }
  double yawRad() const { return yawRad_; }
  double pitchRad() const { return pitchRad_; }
  double distanceM() const { return distanceM_; }
  /// The eye's position, world frame, m.
  glm::dvec3 eyeWorld() const;
  /// Unit vectors of the view: forward (eye → target), right and up, world frame.
  glm::dvec3 forwardWorld() const;
  glm::dvec3 rightWorld() const;
  glm::dvec3 upWorld() const;

  void setTarget(const glm::dvec3& targetWorld);
  /// Sets yaw (about +z; 0 puts the eye on the target's +x side) and pitch (above the xy
  /// plane, clamped to ±kPitchLimitRad).
  void setAngles(double yawRad, double pitchRad);
  void setDistance(double distanceM);
  /// Bounds that near and far planes must enclose (the whole scene); `frame` sets them too.
  void setSceneBounds(const Bounds& boundsWorld);

  /// Mouse drag of (dxPx, dyPx): right turns the eye to the left of the target, down
  /// raises it (the scene follows the cursor).
  void orbit(double dxPx, double dyPx);
  /// Moves target and eye so that the point under the cursor follows it, in a viewport of
  /// `viewportPx` at the target's depth.
  void pan(double dxPx, double dyPx, const glm::ivec2& viewportPx);
  /// Multiplies the distance by `factor` (< 1 moves closer).
  void zoom(double factor);
  /// Aims at the box's centre and backs off until its bounding sphere fits the view
  /// (either axis) for any aspect ≥ `minAspect`; sets the scene bounds. Keeps yaw and pitch.
  void frame(const Bounds& boundsWorld, double minAspect = 1.0);

  /// World → eye (right-handed, looking down -z), for GL.
  glm::dmat4 viewMatrix() const;
  /// Eye → clip, perspective with near/far enclosing the scene bounds (or the target's
  /// neighbourhood when none are set), for a viewport of that aspect (width / height).
  glm::dmat4 projectionMatrix(double aspect) const;
  /// projection · view for that viewport.
  glm::dmat4 viewProjection(const glm::ivec2& viewportPx) const;
  double nearM() const;
  double farM() const;

  /// The ray from the eye through a window pixel position (e.g. the cursor), for picking.
  RayWorld rayThroughPixel(const glm::dvec2& pixelPx, const glm::ivec2& viewportPx) const;
  /// Where a world point lands in a viewport.
  ScreenPoint project(const glm::dvec3& pointWorld, const glm::ivec2& viewportPx) const;

  /// Bumped by every change of the eye, target, distance or scene bounds.
  std::uint64_t revision() const { return revision_; }

private:
  void changed() { ++revision_; }

  glm::dvec3 targetWorld_{0.0};
  double yawRad_ = 0.6;
  double pitchRad_ = 0.45;
  double distanceM_ = 1.0;
  Bounds sceneBoundsWorld_;
  std::uint64_t revision_ = 0;
};

}  // namespace voxhap::render
