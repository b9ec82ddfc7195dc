#pragma once
/// A free rigid body integrated at the haptic rate (DESIGN §4.7), split MuJoCo-style
/// into a read-only `RigidBodyModel` (mass and inertia, built at load time) and a
/// copyable `RigidBodyState` (pose and velocities, changed every frame).
///
/// Frames: the body's local frame is the world frame at load time (scene.h), so the
/// local origin is where the scene file puts the object, not its centre of mass. The
/// state tracks the centre of mass; `RigidBodyState::pose` gives the local→world pose.
///
/// `integrate` is one step of semi-implicit (symplectic) Euler: velocities (linear and
/// angular momentum) first from the forces, then positions from the new velocities.
/// It is noexcept, allocation-free and deterministic (same inputs, same bits).

#include <cstdint>
#include <string>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "haptics/dynamics/mass_properties.h"
#include "haptics/dynamics/pose.h"

namespace voxhap {

/// Read-only mass data of a rigid body.
struct RigidBodyModel {
  double massKg = 0.0;                 ///< kg, > 0
  double inverseMassPerKg = 0.0;       ///< 1 / massKg, 1/kg
  glm::dvec3 comLocal{0.0};            ///< centre of mass, object-local frame, m
  glm::dmat3 inertiaBody{0.0};         ///< inertia about the centre of mass, local axes, kg·m²
  glm::dmat3 inverseInertiaBody{0.0};  ///< inverse of inertiaBody, local axes, 1/(kg·m²)
  /// Principal moments of inertiaBody, ascending, kg·m² (x is the smallest).
  glm::dvec3 principalInertiaKgM2{0.0};
};

/// Builds the model from mass properties. Throws voxhap::Error naming `name` when the
/// mass is not a positive finite number or the inertia is not symmetric positive definite.
RigidBodyModel makeRigidBodyModel(const MassProperties& mass, const std::string& name = "rigid body");

/// Eigenvalues of a symmetric 3×3 matrix, ascending (closed form; deterministic).
glm::dvec3 symmetricEigenvalues(const glm::dmat3& symmetric) noexcept;

/// Everything about a rigid body that changes from frame to frame.
struct RigidBodyState {
  glm::dvec3 comWorld{0.0};                 ///< centre of mass, world frame, m
  glm::dquat orientation = identityQuat();  ///< unit; local axes → world axes
  glm::dvec3 linearVelocityWorld{0.0};      ///< velocity of the centre of mass, world, m/s
  glm::dvec3 angularVelocityWorld{0.0};     ///< world frame, rad/s
  /// Steps that `integrate` skipped (holding pose and velocities) because a force,
  /// torque or the time step was not finite, or the result would not have been.
  std::uint64_t skippedSteps = 0;

  /// The object's local→world pose; its position is the world position of the local
  /// origin (the scene-file placement), m.
  Pose pose(const RigidBodyModel& model) const noexcept;
};

/// Whether every component of `s` is finite and its orientation a unit quaternion (within
/// 1e-6): a state a body may be put in from outside (a remote peer's stream).
bool isFiniteWithUnitOrientation(const RigidBodyState& s) noexcept;

/// A body at rest whose local→world pose is `poseWorld` (identity: as loaded).
RigidBodyState restingState(const RigidBodyModel& model, const Pose& poseWorld = {}) noexcept;

/// World-frame inverse inertia R·I⁻¹·Rᵀ for `orientation`, 1/(kg·m²).
glm::dmat3 inverseInertiaWorld(const RigidBodyModel& model, const glm::dquat& orientation) noexcept;

/// Angular momentum about the centre of mass, world frame, kg·m²/s.
glm::dvec3 angularMomentumWorld(const RigidBodyModel& model, const RigidBodyState& state) noexcept;

/// Kinetic energy (translation + rotation), J.
double kineticEnergyJ(const RigidBodyModel& model, const RigidBodyState& state) noexcept;

/// World velocity of the body point at `pointLocal` (object-local frame, m), m/s.
glm::dvec3 pointVelocityWorld(const RigidBodyModel& model, const RigidBodyState& state,
                              const glm::dvec3& pointLocal) noexcept;

/// Advances `state` by `dtS` seconds (≥ 0) under a constant force (world, N, through
/// the centre of mass) and torque (world, N·m, about the centre of mass).
///
/// Semi-implicit Euler: v += F/m·dt, then x += v·dt; L = I_w·ω + τ·dt (world angular
/// momentum, I_w = R·I·Rᵀ), then the orientation turns by the exponential map of ω·dt and
/// is renormalized, with ω = R·I⁻¹·Rᵀ·L evaluated at the half-step orientation (a
/// midpoint refinement of the position update; see rigid_body.cpp). Finally ω is
/// recomputed from L at the new orientation. Non-finite inputs or results skip the step
/// and count it in `skippedSteps`.
void integrate(const RigidBodyModel& model, RigidBodyState& state, const glm::dvec3& forceWorld,
               const glm::dvec3& torqueWorldAboutCom, double dtS) noexcept;

}  // namespace voxhap
