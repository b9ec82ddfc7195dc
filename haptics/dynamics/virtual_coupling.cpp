#include "haptics/dynamics/virtual_coupling.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "haptics/core/error.h"

namespace voxhap {
namespace {

std::string formatNumber(double v) {
  std::ostringstream s;
  s.precision(4);
  s << v;
  return s.str();
}

/// Scales finite `v` down to length `maxLength` if longer; true when it did. Overflow-safe.
bool clampLength(glm::dvec3& v, double maxLength) {
  const double largest = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  if (largest == 0.0) return false;
  const glm::dvec3 unitScaled = v / largest;
  const double length = largest * glm::length(unitScaled);
  if (!(length > maxLength)) return false;
  v = unitScaled * (maxLength / glm::length(unitScaled));
  return true;
}

/// Spring–damper gains for one degree of freedom of inertia `inertia` (kg or kg·m²).
void gainsFor(double inertia, double omegaN, double& stiffness, double& damping) {
  stiffness = inertia * omegaN * omegaN;
  damping = 2.0 * kCouplingDampingRatio * inertia * omegaN;
}

}  // namespace

void validateDeviceLimits(const DeviceLimits& limits, const std::string& deviceName) {
  auto check = [&](double value, const char* field, bool zeroAllowed) {
    if (!std::isfinite(value) || value < 0.0 || (!zeroAllowed && value == 0.0)) {
      throw Error(deviceName + ": device limit " + field + " must be a finite number " +
                  (zeroAllowed ? "≥ 0" : "> 0") + ", got " + formatNumber(value));
    }
  };
  check(limits.maxForceN, "maxForceN", true);
  check(limits.maxTorqueNm, "maxTorqueNm", true);
  check(limits.maxLinearStiffnessNPerM, "maxLinearStiffnessNPerM", false);
  check(limits.maxAngularStiffnessNmPerRad, "maxAngularStiffnessNmPerRad", false);
}

// How the default gains are chosen.
//
// One translational degree of freedom of a body of mass m on a spring k and damper b to a
// fixed handle, integrated by semi-implicit Euler with step h (rigid_body.h):
//     v' = v + h·(−k·x − b·v)/m,    x' = x + h·v'.
// With a = k·h²/m = (ω_n·h)² and c = b·h/m = 2·ζ·ω_n·h the step matrix
//     [[1 − a, h·(1 − c)], [−a/h, 1 − c]]
// has trace 2 − a − c and determinant 1 − c, and Jury's test makes both eigenvalues lie
// inside the unit circle iff a > 0, 0 < c < 2 and a + 2·c < 4 (with b = 0 this is the
// familiar ω_n·h < 2). We take ω_n·h = 0.25 and ζ = 1: a = 0.0625, c = 0.5, so
// k = m·ω_n² and b = 2·ζ·m·ω_n with ω_n = 0.25/h (62.5 kN/m for 1 kg at 1 kHz). The
// discrete eigenvalues are then 0.848 and 0.590, real: the body closes on the handle
// without overshoot, the error shrinking by 15 % per frame. Raising k alone (b fixed)
// stays stable while a·s + 2·c < 4, i.e. up to s = (4 − 2·c)/a = 48 times the default.
// The full 6-DOF integrator shows the same bound: bisecting the stiffness multiple on an
// off-centre 10 × 5 × 2 cm box of 0.01, 1 or 1000 kg gives 47.99 (virtual_coupling_test
// checks 47× settles and 49× diverges). The wide margin is kept on purpose: contact
// stiffness adds to k while touching, the rotational spring is non-linear, and the user
// moves the handle.
//
// Rotation uses the same rule per principal axis with the moment of inertia in place of
// m. Sizing k_r and b_r with the smallest principal moment gives that axis a = 0.0625,
// c = 0.5; about the other axes both a and c are smaller (lower frequency, damping ratio
// ζ·√(I_min/I)), still stable and still damped.
//
// A device limit on stiffness lowers k to the limit and recomputes b = 2·ζ·√(k·m), which
// only moves a and c further inside the stable region.
CouplingGains defaultCouplingGains(const RigidBodyModel& model, double dtS) {
  if (!(dtS > 0.0) || !std::isfinite(dtS)) {
    throw Error("coupling gains: frame period must be a positive number of seconds, got " +
                formatNumber(dtS));
  }
  const double omegaN = kCouplingFrequencyTimesDt / dtS;
  CouplingGains gains;
  gainsFor(model.massKg, omegaN, gains.linearStiffnessNPerM, gains.linearDampingNsPerM);
  gainsFor(model.principalInertiaKgM2.x, omegaN, gains.angularStiffnessNmPerRad,
           gains.angularDampingNmsPerRad);
  return gains;
}

CouplingGains defaultCouplingGains(const RigidBodyModel& model, double dtS, const DeviceLimits& limits) {
  validateDeviceLimits(limits, "coupling gains");
  CouplingGains gains = defaultCouplingGains(model, dtS);
  if (gains.linearStiffnessNPerM > limits.maxLinearStiffnessNPerM) {
    gainsFor(model.massKg, std::sqrt(limits.maxLinearStiffnessNPerM / model.massKg),
             gains.linearStiffnessNPerM, gains.linearDampingNsPerM);
    gains.linearStiffnessNPerM = limits.maxLinearStiffnessNPerM;
  }
  if (gains.angularStiffnessNmPerRad > limits.maxAngularStiffnessNmPerRad) {
    const double inertia = model.principalInertiaKgM2.x;
    gainsFor(inertia, std::sqrt(limits.maxAngularStiffnessNmPerRad / inertia), gains.angularStiffnessNmPerRad,
             gains.angularDampingNmsPerRad);
    gains.angularStiffnessNmPerRad = limits.maxAngularStiffnessNmPerRad;
  }
  return gains;
}

// Softer and differently damped gains stay stable: with k = s·k₀ (0 < s ≤ 1) the default's
// a = 0.0625 becomes s·a ≤ 0.0625, and b = 2·ζ·√(k·m) gives c = 2·ζ·√(s·a) ≤ 2·2·0.25 = 1 at
// ζ ≤ 2, so a + 2·c ≤ 2.07 < 4 and c < 2 (Jury's conditions above). A device limit only
// lowers k₀, hence a, further.
CouplingGains scaledCouplingGains(const CouplingGains& stiffest, const RigidBodyModel& model,
                                  double stiffnessShare, double dampingRatio) {
  if (!(stiffnessShare > 0.0 && stiffnessShare <= 1.0)) {
    throw Error("coupling stiffness share must be above 0 and at most 1, got " +
                formatNumber(stiffnessShare));
  }
  if (!(dampingRatio >= kMinCouplingDampingRatio && dampingRatio <= kMaxCouplingDampingRatio)) {
    throw Error("coupling damping ratio must be " + formatNumber(kMinCouplingDampingRatio) + " to " +
                formatNumber(kMaxCouplingDampingRatio) + ", got " + formatNumber(dampingRatio));
  }
  CouplingGains gains;
  gains.linearStiffnessNPerM = stiffnessShare * stiffest.linearStiffnessNPerM;
  gains.linearDampingNsPerM = 2.0 * dampingRatio * std::sqrt(gains.linearStiffnessNPerM * model.massKg);
  gains.angularStiffnessNmPerRad = stiffnessShare * stiffest.angularStiffnessNmPerRad;
  gains.angularDampingNmsPerRad =
      2.0 * dampingRatio * std::sqrt(gains.angularStiffnessNmPerRad * model.principalInertiaKgM2.x);
  return gains;
}

CouplingWrench couplingWrench(const CouplingGains& gains, const Pose& handleWorld,
                              const glm::dvec3& handleLinearVelocityWorld,
                              const glm::dvec3& handleAngularVelocityWorld, const RigidBodyModel& model,
                              const RigidBodyState& state) noexcept {
  // the handle-side twin of the centre of mass and its velocity
  const glm::dvec3 leverWorld = handleWorld.orientation * model.comLocal;
  const glm::dvec3 targetComWorld = handleWorld.position + leverWorld;
  const glm::dvec3 targetComVelocityWorld =
      handleLinearVelocityWorld + glm::cross(handleAngularVelocityWorld, leverWorld);

  // rotation carrying the body's orientation onto the handle's, world frame
  const glm::dvec3 rotationWorld =
      rotationVector(handleWorld.orientation * glm::conjugate(state.orientation));

  CouplingWrench wrench;
  wrench.forceWorld = gains.linearStiffnessNPerM * (targetComWorld - state.comWorld) +
                      gains.linearDampingNsPerM * (targetComVelocityWorld - state.linearVelocityWorld);
  wrench.torqueWorld =
      gains.angularStiffnessNmPerRad * rotationWorld +
      gains.angularDampingNmsPerRad * (handleAngularVelocityWorld - state.angularVelocityWorld);
  return wrench;
}

CouplingWrench deviceFeedback(const CouplingWrench& onBody, const DeviceLimits& limits) noexcept {
  CouplingWrench feedback;
  if (!isFinite(onBody.forceWorld) || !isFinite(onBody.torqueWorld)) {
    feedback.nonFiniteZeroed = true;
    return feedback;
  }
  feedback.forceWorld = -onBody.forceWorld;
  feedback.torqueWorld = -onBody.torqueWorld;
  feedback.forceClamped = clampLength(feedback.forceWorld, limits.maxForceN);
  feedback.torqueClamped = clampLength(feedback.torqueWorld, limits.maxTorqueNm);
  return feedback;
}

}  // namespace voxhap
