#pragma once
/// Rate control for a 6-DOF input without force (a SpaceMouse): the cap's deflection sets
/// the handle's velocity, and the handle pose is that velocity integrated frame by frame,
/// starting at the grabbed object's pose.
///
/// Per axis, deflection u in [−1, 1] → dead zone d: 0 when |u| ≤ d, else
/// sign(u)·(|u| − d)/(1 − d) (continuous, 1 at full deflection) → shaping
/// s = (1 − c)·u' + c·u'³ (c = 0: linear; c = 1: cubic, fine control near the centre) →
/// times the gain (m/s or rad/s at full deflection). Deflections are in the view frame and
/// turned into the world frame by viewToWorld. Rotation is about a pivot fixed in the
/// object (its grasp point or centre of mass), not the local origin, which may lie far off.
///
/// Everything per frame is noexcept, allocation-free and deterministic.

#include <array>
#include <string>

#include <glm/vec3.hpp>

#include "haptics/device/scripted_device.h"
#include "haptics/device/spacemouse_report.h"
#include "haptics/dynamics/pose.h"

namespace voxhap {

/// How deflection becomes velocity.
struct RateControlParams {
  double deadZone = 0.05;           ///< fraction of full deflection ignored, [0, 1)
  double linearGainMPerS = 0.1;     ///< m/s at full deflection, ≥ 0
  double angularGainRadPerS = 1.0;  ///< rad/s at full deflection, ≥ 0
  double cubicShaping = 0.0;        ///< c in [0, 1]: 0 linear, 1 cubic
  /// Rotates view-frame vectors to the world frame (the camera's orientation).
  glm::dquat viewToWorld = identityQuat();
};

/// Throws voxhap::Error naming `owner` and the field when a parameter is out of range.
void validateRateControlParams(const RateControlParams& params, const std::string& owner);

/// The shaped value of one axis, in [−1, 1] (dead zone, then shaping).
double shapeDeflection(double deflection, const RateControlParams& params) noexcept;

/// Velocity of the pivot (linear) and angular velocity, world frame, for a deflection
/// (view frame, SpaceMouseAxis order).
HandleVelocity pivotVelocityWorld(const std::array<double, kAxisCount>& deflectionView,
                                  const RateControlParams& params) noexcept;

/// Integrates a handle pose under rate control. Owned by one thread.
class RateController {
public:
  /// Starts at `startWorld`, rotating about `pivotLocal` (m, object local frame). Throws
  /// voxhap::Error on bad parameters.
  RateController(const RateControlParams& params, const Pose& startWorld,
                 const glm::dvec3& pivotLocal = glm::dvec3(0.0));

  /// Restarts at `startWorld` at rest (a new grab).
  void reset(const Pose& startWorld) noexcept;

  /// Advances by `dtS` (s, ≥ 0; others are taken as 0) at the velocity the deflection
  /// asks for: position of the pivot by v·dt, orientation by exp(ω·dt), renormalised.
  void step(const std::array<double, kAxisCount>& deflectionView, double dtS) noexcept;

  /// Sets the velocity to zero without moving (the device is gone).
  void stop() noexcept { velocity_ = {}; }

  /// The handle pose, local → world.
  const Pose& handleWorld() const noexcept { return handle_; }
  /// The handle's velocity of the last step: of the local origin (as HapticDevice
  /// reports it) and angular, world frame.
  const HandleVelocity& velocityWorld() const noexcept { return velocity_; }
  const RateControlParams& params() const noexcept { return params_; }

private:
  RateControlParams params_;
  glm::dvec3 pivotLocal_;
  Pose handle_;
  HandleVelocity velocity_;
};

}  // namespace voxhap
