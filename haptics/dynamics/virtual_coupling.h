#pragma once
/// The 6-DOF virtual coupling between the device handle and the moving body (paper
/// §2.1, Fig. 1c; DESIGN §4.7): a translational and a rotational spring-damper. The
/// body feels the coupling wrench (plus contact forces) and is integrated as a free
/// rigid body; the device renders the negated wrench, clamped to its limits.
///
/// Attachment: the handle pose is a target pose for the body's local frame (a handle pose
/// equal to the body's pose means zero wrench). The translational spring joins the
/// body's centre of mass to the point that would be its centre of mass were the body at
/// the handle pose. That is the same as attaching at the local origin when the poses
/// agree, but keeps the spring's line of action through the centre of mass: the local
/// origin is the scene-file origin, which can lie metres away from a small part, and a
/// spring acting there would couple rotation to translation through that lever arm and
/// raise the effective stiffness far beyond what the gains were chosen for (a 10 cm box
/// 0.37 m from its origin, coupled there at the default gains, diverges within 0.2 s).
///
/// Everything is in the world frame; torques on the body are about its centre of mass.
/// The per-frame functions are noexcept and allocation-free.

#include <limits>
#include <string>

#include <glm/vec3.hpp>

#include "haptics/dynamics/pose.h"
#include "haptics/dynamics/rigid_body.h"

namespace voxhap {

/// Spring and damper constants of the coupling.
struct CouplingGains {
  double linearStiffnessNPerM = 0.0;      ///< N/m
  double linearDampingNsPerM = 0.0;       ///< N·s/m
  double angularStiffnessNmPerRad = 0.0;  ///< N·m/rad
  double angularDampingNmsPerRad = 0.0;   ///< N·m·s/rad
};

/// What a haptic device can render; always finite. The defaults are those of the
/// "scripted" device profile (device_profile.h): a motion script through a rigid handle.
struct DeviceLimits {
  double maxForceN = 100.0;   ///< N, ≥ 0
  double maxTorqueNm = 10.0;  ///< N·m, ≥ 0
  /// Highest coupling stiffness the device renders stably, N/m, > 0.
  double maxLinearStiffnessNPerM = 1e7;
  /// Highest rotational coupling stiffness the device renders stably, N·m/rad, > 0.
  double maxAngularStiffnessNmPerRad = 1e5;
};

/// Throws voxhap::Error naming `deviceName` and the field when a limit is NaN, infinite
/// or negative (or a stiffness limit is zero).
void validateDeviceLimits(const DeviceLimits& limits, const std::string& deviceName);

/// Natural frequency of the default coupling times the frame period, ω_n·dt (rad).
inline constexpr double kCouplingFrequencyTimesDt = 0.25;
/// Damping ratio of the default coupling (critical).
inline constexpr double kCouplingDampingRatio = 1.0;

/// Default gains for `model` integrated with frame period `dtS` (s, > 0 and finite):
/// ω_n = kCouplingFrequencyTimesDt / dtS for translation (with the mass) and for
/// rotation (with the smallest principal moment), damping ratio kCouplingDampingRatio.
/// The derivation and the stability margin are in virtual_coupling.cpp. Throws
/// voxhap::Error when `dtS` is not a positive finite number.
CouplingGains defaultCouplingGains(const RigidBodyModel& model, double dtS);

/// As above, then each stiffness lowered to what `limits` allows, its damping
/// recomputed to keep the damping ratio. Throws as validateDeviceLimits does.
CouplingGains defaultCouplingGains(const RigidBodyModel& model, double dtS, const DeviceLimits& limits);

/// Damping ratios a coupling may be given (scaledCouplingGains): below, the object rings
/// on its handle; above, c = b·h/m leaves the stable region's margin (virtual_coupling.cpp).
inline constexpr double kMinCouplingDampingRatio = 0.1;
inline constexpr double kMaxCouplingDampingRatio = 2.0;

/// `stiffest` (the gains defaultCouplingGains gives `model`) softened: each stiffness times
/// `stiffnessShare` (0 < share ≤ 1), each damping recomputed for `dampingRatio`
/// (kMinCouplingDampingRatio … kMaxCouplingDampingRatio) with the mass and the smallest
/// principal moment, as the defaults are. Within those ranges every gain stays inside the
/// stable region the defaults were derived in. Throws voxhap::Error naming the argument
/// outside its range.
CouplingGains scaledCouplingGains(const CouplingGains& stiffest, const RigidBodyModel& model,
                                  double stiffnessShare, double dampingRatio);

/// A force and a torque, world frame.
struct CouplingWrench {
  glm::dvec3 forceWorld{0.0};    ///< N
  glm::dvec3 torqueWorld{0.0};   ///< N·m; on a body: about its centre of mass
  bool forceClamped = false;     ///< set by deviceFeedback: the force was scaled down
  bool torqueClamped = false;    ///< set by deviceFeedback: the torque was scaled down
  bool nonFiniteZeroed = false;  ///< set by deviceFeedback: NaN or Inf replaced by zero
};

/// Wrench of the coupling on the body. `handleWorld`: the handle's pose, read as a target
/// local→world pose for the body; `handleLinearVelocityWorld`: velocity of the handle's
/// origin (m/s); `handleAngularVelocityWorld`: rad/s. Force = k·Δx + b·Δv at the centre
/// of mass (see the file comment); torque = k_r·θ + b_r·Δω with θ the rotation vector
/// (shortest way, |θ| ≤ π) from the body's orientation to the handle's.
CouplingWrench couplingWrench(const CouplingGains& gains, const Pose& handleWorld,
                              const glm::dvec3& handleLinearVelocityWorld,
                              const glm::dvec3& handleAngularVelocityWorld, const RigidBodyModel& model,
                              const RigidBodyState& state) noexcept;

/// What the device renders: the negated coupling wrench, each vector scaled down to its
/// limit if longer (direction kept). The torque is about the handle's grasp point, the
/// handle-side twin of the body's centre of mass (handle pose applied to comLocal); a
/// driver whose torque reference is elsewhere adds (grasp − reference) × force. A NaN or
/// infinite component zeroes the whole wrench and sets `nonFiniteZeroed`.
CouplingWrench deviceFeedback(const CouplingWrench& onBody, const DeviceLimits& limits) noexcept;

}  // namespace voxhap
