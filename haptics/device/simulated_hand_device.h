#pragma once
/// A simulated force-feedback device for tests: the device's handle held by a user's hand,
/// so that the feedback the engine renders pushes the handle back, as on a real arm.
///
/// Model. The handle is a rigid body (mass m, scalar rotational inertia I: a handle and
/// the fingers around it have no preferred axis worth modelling) gripped at `graspLocal`,
/// which is its centre of mass and the point the hand holds. The hand is a 6-DOF
/// spring-damper (k, b; k_r, b_r) from the handle's grasp point to the hand's target,
/// the grasp point of the motion script's pose (a target local→world pose of the grabbed
/// object, as ScriptedDevice plays it); the damper acts on the velocity relative to the
/// target's. The feedback wrench (the force the device renders on the user, the negated
/// coupling wrench: it pushes the handle away from contact) acts at the grasp point
/// together with the hand. Gravity is not modelled: desktop arms balance their links and
/// the user's arm holds its own weight. At rest the hand balances the feedback, so the
/// handle sits at target + F/k (and θ = τ/k_r): the user is held back by the contact.
///
/// Integration. handlePose(t) and handleVelocity(t) integrate from the previous call's
/// time to t by semi-implicit Euler in equal substeps no longer than maxSubstepS, with the
/// latest feedback held over the interval (a real device's zero-order hold). An interval
/// longer than maxIntervalS (a stall) is cut to its last maxIntervalS: the hand's target
/// jumps, the handle only moves as far as that much time allows, and the work per call is
/// bounded. Time comes only from the arguments (no clock), so runs are deterministic.
///
/// Threads: the haptic thread alone calls a device (scripted_device.h); the per-frame
/// calls are noexcept and allocation-free; the constructor validates and may throw.

#include <cstdint>
#include <string>

#include <glm/vec3.hpp>

#include "haptics/device/motion_script.h"
#include "haptics/device/scripted_device.h"
#include "haptics/dynamics/pose.h"
#include "haptics/dynamics/virtual_coupling.h"

namespace voxhap {

/// The handle and the hand holding it. Defaults are round assumptions, not measurements,
/// for a hand holding the stylus of a desktop arm in a firm pen grip: 0.2 kg moving with
/// the handle, 500 N/m, critically damped (b = 2·√(k·m)); 2·10⁻⁴ kg·m² and 2 N·m/rad,
/// critically damped, in rotation.
struct SimulatedHandParams {
  double handleMassKg = 0.2;                  ///< m: handle plus the hand's moving mass, kg, > 0
  double handleInertiaKgM2 = 2e-4;            ///< I: about the grasp point, kg·m², > 0
  double handStiffnessNPerM = 500.0;          ///< k, N/m, > 0
  double handDampingNsPerM = 20.0;            ///< b, N·s/m, > 0 (20: critical with the defaults)
  double handAngularStiffnessNmPerRad = 2.0;  ///< k_r, N·m/rad, > 0
  double handAngularDampingNmsPerRad = 0.04;  ///< b_r, N·m·s/rad, > 0 (0.04: critical)
  /// Where the hand holds the handle, object local frame, m: set it to the object's centre
  /// of mass (RigidBodyModel::comLocal), the point deviceFeedback takes torques about.
  glm::dvec3 graspLocal{0.0};
  /// Longest integration substep, s, > 0; must keep the hand's spring well inside
  /// semi-implicit Euler's stable region (see validateSimulatedHandParams).
  double maxSubstepS = 5e-4;
  /// Longest interval one call integrates, s, ≥ maxSubstepS and ≤ 1000 substeps; a longer
  /// gap between calls is skipped but for its end.
  double maxIntervalS = 0.01;
};

/// Throws voxhap::Error "OWNER: simulated hand FIELD must be …, got V" when a parameter is
/// not finite, not positive, or out of range; also, naming maxSubstepS, when a substep is
/// too long for the hand's spring and damper: with a = k·h²/m and c = b·h/m (the same with
/// k_r, b_r, I), semi-implicit Euler is stable iff a + 2c < 4 (virtual_coupling.cpp); we
/// ask a + 2c ≤ 1, for accuracy as well.
void validateSimulatedHandParams(const SimulatedHandParams& params, const std::string& owner);

/// A HapticDevice whose handle is pushed by the feedback and pulled by a simulated hand.
class SimulatedHandDevice final : public HapticDevice {
public:
  /// The hand follows `handTarget`; the handle starts at rest at the target's grasp point
  /// at t = 0, the device's clock at 0. Throws voxhap::Error on bad parameters or limits.
  explicit SimulatedHandDevice(MotionScript handTarget, const SimulatedHandParams& params = {},
                               const DeviceLimits& limits = {});

  /// Handle pose at `tS` (s), integrated from the previous call's time. A time not after
  /// the previous one (or NaN) integrates nothing; an earlier time restarts the clock there.
  Pose handlePose(double tS) noexcept override;
  /// Handle velocity at `tS`, integrating as handlePose does: of the local origin (as
  /// HapticDevice reports it) and angular, world frame.
  HandleVelocity handleVelocity(double tS) noexcept override;
  /// The wrench to render, held until the next call (world frame; torque about the grasp
  /// point). Applied to the handle scaled down to limits() (an amplifier saturates) and
  /// as zero when not finite; recorded as given.
  void setFeedback(const CouplingWrench& feedbackWorld) noexcept override;
  const DeviceLimits& limits() const noexcept override { return limits_; }
  /// Starts the handle at `objectWorld`, at rest, and the clock at 0: the haptic loop
  /// counts a device's time from its grab (app/controller/haptic_loop.h).
  void grabbed(const Pose& objectWorld) noexcept override;

  /// The hand's target pose at `tS` (the script's pose), local → world.
  Pose handTarget(double tS) const noexcept { return script_.sample(tS); }
  /// World position of the hand's target grasp point at `tS`, m.
  glm::dvec3 handTargetGraspWorld(double tS) const noexcept;
  /// World position of the handle's grasp point now, m.
  const glm::dvec3& graspWorld() const noexcept { return graspWorld_; }
  /// Velocity of the grasp point now, world, m/s.
  const glm::dvec3& graspVelocityWorld() const noexcept { return velocityWorld_; }
  /// The hand's force on the handle in the last substep, world, N (at rest: −feedback).
  const glm::dvec3& handForceWorld() const noexcept { return handForceWorld_; }
  /// The hand's torque on the handle in the last substep, world, N·m.
  const glm::dvec3& handTorqueWorld() const noexcept { return handTorqueWorld_; }
  /// Time up to which the handle is integrated, s (device clock).
  double timeS() const noexcept { return timeS_; }

  const MotionScript& script() const noexcept { return script_; }
  const SimulatedHandParams& params() const noexcept { return params_; }
  /// The last wrench passed to setFeedback, as given (zero before the first).
  const CouplingWrench& lastFeedback() const noexcept { return lastFeedback_; }
  /// Largest |force| passed to setFeedback so far, N (non-finite ones not counted).
  double maxFeedbackForceN() const noexcept { return maxFeedbackForceN_; }
  /// How many times setFeedback was called.
  std::uint64_t feedbackCount() const noexcept { return feedbackCount_; }
  /// Feedback wrenches that were not finite (applied as zero).
  std::uint64_t nonFiniteFeedback() const noexcept { return nonFiniteFeedback_; }
  /// Substeps integrated so far.
  std::uint64_t steps() const noexcept { return steps_; }
  /// Calls whose interval was cut to maxIntervalS (stalls).
  std::uint64_t clampedIntervals() const noexcept { return clampedIntervals_; }

private:
  void advanceTo(double tS) noexcept;
  void substep(double hS, const Pose& targetBefore, const Pose& targetAfter) noexcept;
  void restAt(const Pose& poseWorld) noexcept;

  MotionScript script_;
  SimulatedHandParams params_;
  DeviceLimits limits_;
  // state: grasp point and orientation, their velocities, the clock
  glm::dvec3 graspWorld_{0.0};
  glm::dquat orientation_ = identityQuat();
  glm::dvec3 velocityWorld_{0.0};
  glm::dvec3 angularVelocityWorld_{0.0};
  double timeS_ = 0.0;
  // feedback held over the interval, as applied (clamped, finite)
  glm::dvec3 feedbackForceWorld_{0.0};
  glm::dvec3 feedbackTorqueWorld_{0.0};
  // counters
  glm::dvec3 handForceWorld_{0.0};
  glm::dvec3 handTorqueWorld_{0.0};
  CouplingWrench lastFeedback_;
  double maxFeedbackForceN_ = 0.0;
  std::uint64_t feedbackCount_ = 0;
  std::uint64_t nonFiniteFeedback_ = 0;
  std::uint64_t steps_ = 0;
  std::uint64_t clampedIntervals_ = 0;
};

}  // namespace voxhap
