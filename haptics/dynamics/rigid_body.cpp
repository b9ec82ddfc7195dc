#include "haptics/dynamics/rigid_body.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include <glm/gtc/quaternion.hpp>
#include <glm/matrix.hpp>

#include "haptics/core/error.h"

namespace voxhap {
namespace {

bool finite(const RigidBodyState& s) {
  return isFinite(s.comWorld) && isFinite(s.orientation) && isFinite(s.linearVelocityWorld) &&
         isFinite(s.angularVelocityWorld);
}

std::string formatNumber(double v) {
  std::ostringstream s;
  s.precision(4);
  s << v;
  return s.str();
}

/// R·M·Rᵀ·v without forming the product matrix.
glm::dvec3 rotated(const glm::dmat3& r, const glm::dmat3& bodyMatrix, const glm::dvec3& vWorld) {
  return r * (bodyMatrix * (glm::transpose(r) * vWorld));
}

}  // namespace

bool isFiniteWithUnitOrientation(const RigidBodyState& s) noexcept {
  return finite(s) && std::abs(glm::length(s.orientation) - 1.0) < 1e-6;
}

glm::dvec3 symmetricEigenvalues(const glm::dmat3& a) noexcept {
  // closed form for a symmetric 3×3 matrix (O. K. Smith, CACM 4(4), 1961)
  const double a00 = a[0][0], a11 = a[1][1], a22 = a[2][2];
  const double a01 = 0.5 * (a[1][0] + a[0][1]);
  const double a02 = 0.5 * (a[2][0] + a[0][2]);
  const double a12 = 0.5 * (a[2][1] + a[1][2]);
  const double p1 = a01 * a01 + a02 * a02 + a12 * a12;
  glm::dvec3 e;
  if (p1 == 0.0) {
    e = glm::dvec3(a00, a11, a22);
  } else {
    const double q = (a00 + a11 + a22) / 3.0;
    const double d0 = a00 - q, d1 = a11 - q, d2 = a22 - q;
    const double p = std::sqrt((d0 * d0 + d1 * d1 + d2 * d2 + 2.0 * p1) / 6.0);
    // r = det((A − qI)/p) / 2, clamped into acos's domain against rounding
    const double b00 = d0 / p, b11 = d1 / p, b22 = d2 / p;
    const double b01 = a01 / p, b02 = a02 / p, b12 = a12 / p;
    const double det =
        b00 * (b11 * b22 - b12 * b12) - b01 * (b01 * b22 - b12 * b02) + b02 * (b01 * b12 - b11 * b02);
    const double r = std::clamp(0.5 * det, -1.0, 1.0);
    const double phi = std::acos(r) / 3.0;
    const double largest = q + 2.0 * p * std::cos(phi);
    const double smallest = q + 2.0 * p * std::cos(phi + 2.0 * std::numbers::pi / 3.0);
    e = glm::dvec3(smallest, 3.0 * q - largest - smallest, largest);
  }
  if (e.x > e.y) std::swap(e.x, e.y);
  if (e.y > e.z) std::swap(e.y, e.z);
  if (e.x > e.y) std::swap(e.x, e.y);
  return e;
}

RigidBodyModel makeRigidBodyModel(const MassProperties& mass, const std::string& name) {
  if (!(mass.massKg > 0.0) || !std::isfinite(mass.massKg)) {
    throw Error(name + ": mass must be a positive number of kg, got " + formatNumber(mass.massKg));
  }
  if (!isFinite(mass.comLocal)) throw Error(name + ": centre of mass is not finite");
  const glm::dmat3 inertia = 0.5 * (mass.inertiaAboutComKgM2 + glm::transpose(mass.inertiaAboutComKgM2));
  const glm::dvec3 moments = symmetricEigenvalues(inertia);
  if (!(moments.x > 0.0) || !std::isfinite(moments.z)) {
    throw Error(name + ": inertia tensor is not positive definite (principal moments " +
                formatNumber(moments.x) + ", " + formatNumber(moments.y) + ", " + formatNumber(moments.z) +
                " kg·m²)");
  }
  RigidBodyModel model;
  model.massKg = mass.massKg;
  model.inverseMassPerKg = 1.0 / mass.massKg;
  model.comLocal = mass.comLocal;
  model.inertiaBody = inertia;
  model.inverseInertiaBody = glm::inverse(inertia);
  model.principalInertiaKgM2 = moments;
  return model;
}

Pose RigidBodyState::pose(const RigidBodyModel& model) const noexcept {
  return Pose{comWorld - orientation * model.comLocal, orientation};
}

RigidBodyState restingState(const RigidBodyModel& model, const Pose& poseWorld) noexcept {
  RigidBodyState state;
  state.orientation = glm::normalize(poseWorld.orientation);
  state.comWorld = apply(Pose{poseWorld.position, state.orientation}, model.comLocal);
  return state;
}

glm::dmat3 inverseInertiaWorld(const RigidBodyModel& model, const glm::dquat& orientation) noexcept {
  const glm::dmat3 r = glm::mat3_cast(orientation);
  return r * model.inverseInertiaBody * glm::transpose(r);
}

glm::dvec3 angularMomentumWorld(const RigidBodyModel& model, const RigidBodyState& state) noexcept {
  return rotated(glm::mat3_cast(state.orientation), model.inertiaBody, state.angularVelocityWorld);
}

double kineticEnergyJ(const RigidBodyModel& model, const RigidBodyState& state) noexcept {
  const glm::dvec3& v = state.linearVelocityWorld;
  return 0.5 * model.massKg * glm::dot(v, v) +
         0.5 * glm::dot(state.angularVelocityWorld, angularMomentumWorld(model, state));
}

glm::dvec3 pointVelocityWorld(const RigidBodyModel& model, const RigidBodyState& state,
                              const glm::dvec3& pointLocal) noexcept {
  const glm::dvec3 leverWorld = state.orientation * (pointLocal - model.comLocal);
  return state.linearVelocityWorld + glm::cross(state.angularVelocityWorld, leverWorld);
}

// The angular step. Torque-free rotation keeps the world angular momentum L fixed while
// the world inertia turns with the body, so ω = R·I⁻¹·Rᵀ·L changes within the step. Using
// ω at the start of the step (plain Lie–Euler) gains energy every step: for the body-frame
// momentum the step is a rotation about the frozen ω, which raises E = ½·Lᵀ·I⁻¹·L by
// ½·h²·uᵀ·I⁻¹·u (u = ω × L) to second order, a secular drift of about ½·h·|ω|²·t relative
// (measured: 1.0e-3 in 10 s at 1 rad/s, 1.7e-1 at 10 rad/s). Evaluating ω at the
// half-step orientation R(exp(ω·h/2)) makes the update second order and nearly
// time-symmetric: the energy error then stays bounded, an oscillation of at most about
// (|ω|·h)²/24 relative, with no drift (measured over 10 s of tumbling near the intermediate
// axis, principal moments 1 : 2 : 3: 2.9e-8 at 1 rad/s, 2.9e-6 at 10 rad/s; rigid_body_test).
// L itself is exact (only τ·h changes it), so angular momentum is conserved to rounding.
void integrate(const RigidBodyModel& model, RigidBodyState& state, const glm::dvec3& forceWorld,
               const glm::dvec3& torqueWorldAboutCom, double dtS) noexcept {
  if (!isFinite(forceWorld) || !isFinite(torqueWorldAboutCom) || !(dtS >= 0.0) || !std::isfinite(dtS)) {
    ++state.skippedSteps;
    return;
  }
  RigidBodyState next = state;

  // velocities first, then positions from the new velocities
  next.linearVelocityWorld += forceWorld * (model.inverseMassPerKg * dtS);
  next.comWorld += next.linearVelocityWorld * dtS;

  const glm::dmat3 r0 = glm::mat3_cast(state.orientation);
  const glm::dvec3 momentum =
      rotated(r0, model.inertiaBody, state.angularVelocityWorld) + torqueWorldAboutCom * dtS;
  const glm::dvec3 omegaStart = rotated(r0, model.inverseInertiaBody, momentum);
  const glm::dquat halfway =
      glm::normalize(quatFromRotationVector(0.5 * dtS * omegaStart) * state.orientation);
  const glm::dvec3 omegaMid = rotated(glm::mat3_cast(halfway), model.inverseInertiaBody, momentum);
  next.orientation = glm::normalize(quatFromRotationVector(dtS * omegaMid) * state.orientation);
  next.angularVelocityWorld = rotated(glm::mat3_cast(next.orientation), model.inverseInertiaBody, momentum);

  if (!finite(next)) {
    ++state.skippedSteps;
    return;
  }
  state = next;
}

}  // namespace voxhap
