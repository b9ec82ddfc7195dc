#pragma once
/// Haptic devices as the 1 kHz loop sees them, and the scripted device that plays a
/// motion script (tests, benchmarks, demos without hardware).
///
/// The haptic thread alone calls a device, once per frame: read the handle, run the
/// dynamics, write the feedback. Every call is noexcept and allocation-free; set-up
/// (opening, validating) happens in constructors, which may throw voxhap::Error.

#include <cstdint>

#include <glm/vec3.hpp>

#include "haptics/device/motion_script.h"
#include "haptics/dynamics/pose.h"
#include "haptics/dynamics/virtual_coupling.h"

namespace voxhap {

/// Linear and angular velocity of the handle, world frame.
struct HandleVelocity {
  glm::dvec3 linearWorld{0.0};   ///< velocity of the handle's origin, m/s
  glm::dvec3 angularWorld{0.0};  ///< rad/s
};

/// A 6-DOF input device with (optional) force feedback.
class HapticDevice {
public:
  virtual ~HapticDevice() = default;

  /// Handle pose at time `tS` (s since the simulation started), read as the target
  /// local→world pose of the grabbed object.
  virtual Pose handlePose(double tS) noexcept = 0;

  /// Handle velocity at time `tS`, world frame.
  virtual HandleVelocity handleVelocity(double tS) noexcept = 0;

  /// The wrench to render now, world frame (N, N·m about the grasp point), already
  /// clamped to limits() by deviceFeedback.
  virtual void setFeedback(const CouplingWrench& feedbackWorld) noexcept = 0;

  /// What the device can render.
  virtual const DeviceLimits& limits() const noexcept = 0;

  /// Haptic thread: the device has just grabbed an object at `objectWorld`; a device
  /// whose handle is integrated (rate control) starts it there, at rest.
  virtual void grabbed(const Pose& objectWorld) noexcept { (void)objectWorld; }
};

/// A device that plays a motion script: the handle pose at time t is the script's pose
/// at t (script poses are relative to the scene-file placement, which is the object's
/// local frame, so they are world poses of that frame). The velocity is the backward
/// difference of the script over one device period, as a real device's encoders give
/// it. Feedback is recorded, not rendered.
class ScriptedDevice final : public HapticDevice {
public:
  /// Plays `script`; `periodS` (s, > 0) is the finite-difference step for velocities.
  /// Throws voxhap::Error on a bad period or bad limits.
  explicit ScriptedDevice(MotionScript script, const DeviceLimits& limits = {}, double periodS = 1e-3);

  Pose handlePose(double tS) noexcept override;
  HandleVelocity handleVelocity(double tS) noexcept override;
  void setFeedback(const CouplingWrench& feedbackWorld) noexcept override;
  const DeviceLimits& limits() const noexcept override { return limits_; }

  /// The script being played.
  const MotionScript& script() const noexcept { return script_; }
  /// The last wrench passed to setFeedback (zero before the first).
  const CouplingWrench& lastFeedback() const noexcept { return lastFeedback_; }
  /// How many times setFeedback was called.
  std::uint64_t feedbackCount() const noexcept { return feedbackCount_; }

private:
  MotionScript script_;
  DeviceLimits limits_;
  double periodS_;
  CouplingWrench lastFeedback_;
  std::uint64_t feedbackCount_ = 0;
};

}  // namespace voxhap
