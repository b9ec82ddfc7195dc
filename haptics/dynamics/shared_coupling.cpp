#include "haptics/dynamics/shared_coupling.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "haptics/dynamics/pose.h"

namespace voxhap {
namespace {

/// `state` carried `aheadS` forward along its velocities.
RigidBodyState predicted(const RigidBodyState& state, double aheadS) noexcept {
  RigidBodyState out = state;
  out.comWorld += state.linearVelocityWorld * aheadS;
  out.orientation =
      glm::normalize(quatFromRotationVector(state.angularVelocityWorld * aheadS) * state.orientation);
  return out;
}

}  // namespace

double delayWeight(double delayS) noexcept {
  if (std::isnan(delayS)) return 0.0;
  return std::clamp(1.0 - delayS / kSharedCouplingFadeDelayS, 0.0, 1.0);
}

double ageWeight(double ageS, double omegaRadS) noexcept {
  if (std::isnan(ageS) || std::isnan(omegaRadS)) return 0.0;
  const double omegaAge = omegaRadS * ageS;
  if (omegaAge <= kSharedCouplingOmegaAge) return 1.0;
  const double allowed = kSharedCouplingOmegaAge / omegaAge;
  return allowed * allowed;
}

SharedCoupling sharedCouplingWrench(const CouplingGains& stiffest, const RigidBodyModel& model,
                                    const RigidBodyState& local, std::span<const RemoteInstance> remotes,
                                    const DivergenceBound& bound, bool wasDivergent) noexcept {
  SharedCoupling out;
  double weightSum = 0.0;
  double squareSum = 0.0;
  glm::dvec3 com{0.0}, linear{0.0}, angular{0.0};
  glm::dquat orientation(0.0, 0.0, 0.0, 0.0);
  const double omegaRadS = std::sqrt(stiffest.linearStiffnessNPerM / model.massKg);
  for (const RemoteInstance& remote : remotes) {
    const double w = delayWeight(remote.delayS) * ageWeight(remote.ageS, omegaRadS);
    if (w == 0.0 || !isFiniteWithUnitOrientation(remote.state)) continue;
    const RigidBodyState r =
        predicted(remote.state, std::clamp(remote.leadS, 0.0, std::max(remote.ageS, 0.0)));
    weightSum += w;
    squareSum += w * w;
    com += w * r.comWorld;
    linear += w * r.linearVelocityWorld;
    angular += w * r.angularVelocityWorld;
    // q and −q are one orientation: take the one on the local instance's side
    const double side = glm::dot(r.orientation, local.orientation) < 0.0 ? -w : w;
    orientation = orientation + side * r.orientation;
  }
  const double orientationLength = glm::length(orientation);
  if (weightSum == 0.0 || !(orientationLength > 0.0)) return out;  // (opposite turns cancel)

  out.stiffnessShare = squareSum / weightSum;
  out.target.comWorld = com / weightSum;
  out.target.orientation = orientation / orientationLength;
  out.target.linearVelocityWorld = linear / weightSum;
  out.target.angularVelocityWorld = angular / weightSum;

  const glm::dvec3 apartM = out.target.comWorld - local.comWorld;
  const glm::dvec3 apartRad = rotationVector(out.target.orientation * glm::conjugate(local.orientation));
  out.apartM = glm::length(apartM);
  out.apartRad = glm::length(apartRad);
  const double share = wasDivergent ? 0.5 : 1.0;  // hysteresis
  out.divergent = out.apartM > share * bound.distanceM || out.apartRad > share * bound.angleRad;
  // the spring's target, no further from the local instance than the bound
  RigidBodyState spring = out.target;
  if (out.apartM > bound.distanceM)
    spring.comWorld = local.comWorld + apartM * (bound.distanceM / out.apartM);
  if (out.apartRad > bound.angleRad) {
    spring.orientation =
        quatFromRotationVector(apartRad * (bound.angleRad / out.apartRad)) * local.orientation;
  }

  const double s = out.stiffnessShare;
  const double d = std::sqrt(s);
  const CouplingGains gains{s * stiffest.linearStiffnessNPerM, d * stiffest.linearDampingNsPerM,
                            s * stiffest.angularStiffnessNmPerRad, d * stiffest.angularDampingNmsPerRad};
  // couplingWrench takes the target's local origin and its velocity
  const glm::dvec3 leverWorld = spring.orientation * model.comLocal;
  const glm::dvec3 originVelocityWorld =
      spring.linearVelocityWorld - glm::cross(spring.angularVelocityWorld, leverWorld);
  out.onLocal = couplingWrench(gains, spring.pose(model), originVelocityWorld, spring.angularVelocityWorld,
                               model, local);
  return out;
}

}  // namespace voxhap
