#include "haptics/device/simulated_hand_device.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include "haptics/core/error.h"

namespace voxhap {
namespace {

void require(bool ok, const std::string& owner, const char* field, double value, const char* range) {
  if (ok) return;
  std::ostringstream s;
  s << owner << ": simulated hand " << field << " must be " << range << ", got " << value;
  throw Error(s.str());
}

bool positiveFinite(double v) {
  return std::isfinite(v) && v > 0.0;
}

/// a + 2c of one degree of freedom (see validateSimulatedHandParams).
double stepLoad(double stiffness, double damping, double inertia, double hS) {
  return (stiffness * hS * hS + 2.0 * damping * hS) / inertia;
}

/// `v` scaled down to length `maxLength` if longer (finite `v`).
glm::dvec3 clampedTo(const glm::dvec3& v, double maxLength) noexcept {
  const double length = glm::length(v);
  return length > maxLength ? v * (maxLength / length) : v;
}

}  // namespace

void validateSimulatedHandParams(const SimulatedHandParams& p, const std::string& owner) {
  const char* positive = "a finite number > 0";
  require(positiveFinite(p.handleMassKg), owner, "handleMassKg", p.handleMassKg, positive);
  require(positiveFinite(p.handleInertiaKgM2), owner, "handleInertiaKgM2", p.handleInertiaKgM2, positive);
  require(positiveFinite(p.handStiffnessNPerM), owner, "handStiffnessNPerM", p.handStiffnessNPerM, positive);
  require(positiveFinite(p.handDampingNsPerM), owner, "handDampingNsPerM", p.handDampingNsPerM, positive);
  require(positiveFinite(p.handAngularStiffnessNmPerRad), owner, "handAngularStiffnessNmPerRad",
          p.handAngularStiffnessNmPerRad, positive);
  require(positiveFinite(p.handAngularDampingNmsPerRad), owner, "handAngularDampingNmsPerRad",
          p.handAngularDampingNmsPerRad, positive);
  require(std::isfinite(p.graspLocal.x), owner, "graspLocal.x", p.graspLocal.x, "finite");
  require(std::isfinite(p.graspLocal.y), owner, "graspLocal.y", p.graspLocal.y, "finite");
  require(std::isfinite(p.graspLocal.z), owner, "graspLocal.z", p.graspLocal.z, "finite");
  require(positiveFinite(p.maxSubstepS), owner, "maxSubstepS", p.maxSubstepS, positive);
  require(std::isfinite(p.maxIntervalS) && p.maxIntervalS >= p.maxSubstepS &&
              p.maxIntervalS <= 1000.0 * p.maxSubstepS,
          owner, "maxIntervalS", p.maxIntervalS, "finite, from maxSubstepS to 1000 maxSubstepS");
  const double linear = stepLoad(p.handStiffnessNPerM, p.handDampingNsPerM, p.handleMassKg, p.maxSubstepS);
  require(linear <= 1.0, owner,
          "maxSubstepS (a + 2c with handStiffnessNPerM, handDampingNsPerM, handleMassKg)", linear,
          "at most 1 (a shorter substep)");
  const double angular = stepLoad(p.handAngularStiffnessNmPerRad, p.handAngularDampingNmsPerRad,
                                  p.handleInertiaKgM2, p.maxSubstepS);
  require(angular <= 1.0, owner,
          "maxSubstepS (a + 2c with handAngularStiffnessNmPerRad, handAngularDampingNmsPerRad, "
          "handleInertiaKgM2)",
          angular, "at most 1 (a shorter substep)");
}

SimulatedHandDevice::SimulatedHandDevice(MotionScript handTarget, const SimulatedHandParams& params,
                                         const DeviceLimits& limits)
    : script_(std::move(handTarget)), params_(params), limits_(limits) {
  const std::string name = "simulated hand device (" + script_.sourceName() + ")";
  validateSimulatedHandParams(params_, name);
  validateDeviceLimits(limits_, name);
  restAt(script_.sample(0.0));
}

glm::dvec3 SimulatedHandDevice::handTargetGraspWorld(double tS) const noexcept {
  return apply(script_.sample(tS), params_.graspLocal);
}

void SimulatedHandDevice::restAt(const Pose& poseWorld) noexcept {
  graspWorld_ = apply(poseWorld, params_.graspLocal);
  orientation_ = poseWorld.orientation;
  velocityWorld_ = angularVelocityWorld_ = glm::dvec3(0.0);
  handForceWorld_ = handTorqueWorld_ = glm::dvec3(0.0);
  timeS_ = 0.0;
}

void SimulatedHandDevice::grabbed(const Pose& objectWorld) noexcept {
  if (isFinite(objectWorld)) restAt(objectWorld);
}

void SimulatedHandDevice::substep(double hS, const Pose& targetBefore, const Pose& targetAfter) noexcept {
  const SimulatedHandParams& p = params_;
  // the target's grasp point and its velocity over the substep
  const glm::dvec3 targetWorld = apply(targetAfter, p.graspLocal);
  const glm::dvec3 targetVelocityWorld = (targetWorld - apply(targetBefore, p.graspLocal)) / hS;
  const glm::dvec3 targetAngularWorld =
      rotationVector(targetAfter.orientation * glm::conjugate(targetBefore.orientation)) / hS;
  // the hand's spring-damper, then semi-implicit Euler: velocities first, then the pose
  handForceWorld_ = p.handStiffnessNPerM * (targetWorld - graspWorld_) +
                    p.handDampingNsPerM * (targetVelocityWorld - velocityWorld_);
  handTorqueWorld_ = p.handAngularStiffnessNmPerRad *
                         rotationVector(targetAfter.orientation * glm::conjugate(orientation_)) +
                     p.handAngularDampingNmsPerRad * (targetAngularWorld - angularVelocityWorld_);
  velocityWorld_ += (hS / p.handleMassKg) * (handForceWorld_ + feedbackForceWorld_);
  // scalar inertia: no gyroscopic term
  angularVelocityWorld_ += (hS / p.handleInertiaKgM2) * (handTorqueWorld_ + feedbackTorqueWorld_);
  graspWorld_ += hS * velocityWorld_;
  orientation_ = glm::normalize(quatFromRotationVector(hS * angularVelocityWorld_) * orientation_);
  ++steps_;
}

void SimulatedHandDevice::advanceTo(double tS) noexcept {
  if (!std::isfinite(tS)) return;
  if (tS < timeS_) {  // a new timeline (a run restarted without a grab): hold, restart the clock
    timeS_ = tS;
    return;
  }
  double fromS = timeS_;
  if (tS - fromS > params_.maxIntervalS) {
    fromS = tS - params_.maxIntervalS;
    ++clampedIntervals_;
  }
  const double intervalS = tS - fromS;
  if (!(intervalS > 0.0)) return;
  // equal substeps, no longer than maxSubstepS (the tolerance keeps 1 ms / 0.5 ms at 2)
  const int n = static_cast<int>(std::ceil(intervalS / params_.maxSubstepS * (1.0 - 1e-12)));
  const double hS = intervalS / n;
  Pose before = script_.sample(fromS);
  for (int k = 1; k <= n; ++k) {
    const double tK = k == n ? tS : fromS + k * hS;
    const Pose after = script_.sample(tK);
    substep(hS, before, after);
    before = after;
  }
  timeS_ = tS;
}

Pose SimulatedHandDevice::handlePose(double tS) noexcept {
  advanceTo(tS);
  return Pose{graspWorld_ - orientation_ * params_.graspLocal, orientation_};
}

HandleVelocity SimulatedHandDevice::handleVelocity(double tS) noexcept {
  advanceTo(tS);
  // the local origin moves with the grasp point and turns about it
  HandleVelocity v;
  v.linearWorld = velocityWorld_ - glm::cross(angularVelocityWorld_, orientation_ * params_.graspLocal);
  v.angularWorld = angularVelocityWorld_;
  return v;
}

void SimulatedHandDevice::setFeedback(const CouplingWrench& feedbackWorld) noexcept {
  lastFeedback_ = feedbackWorld;
  ++feedbackCount_;
  if (!isFinite(feedbackWorld.forceWorld) || !isFinite(feedbackWorld.torqueWorld)) {
    ++nonFiniteFeedback_;
    feedbackForceWorld_ = feedbackTorqueWorld_ = glm::dvec3(0.0);
    return;
  }
  maxFeedbackForceN_ = std::max(maxFeedbackForceN_, glm::length(feedbackWorld.forceWorld));
  feedbackForceWorld_ = clampedTo(feedbackWorld.forceWorld, limits_.maxForceN);
  feedbackTorqueWorld_ = clampedTo(feedbackWorld.torqueWorld, limits_.maxTorqueNm);
}

}  // namespace voxhap
