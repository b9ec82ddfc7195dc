#pragma once
/// Rigid transforms for the dynamics (DESIGN §3): a `Pose` maps object-local points
/// (metres) to world points, world = orientation · local + position.
///
/// Everything here is inline, noexcept and allocation-free, for the 1 kHz frame.
/// Quaternions are GLM's (w, x, y, z); q and −q are the same rotation, and the
/// helpers that compare or interpolate rotations take the shortest way.

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

namespace voxhap {

/// Quaternion w + xi + yj + zk, built by name whatever GLM's constructor order.
inline glm::dquat quatWxyz(double w, double x, double y, double z) noexcept {
  glm::dquat q;
  q.w = w;
  q.x = x;
  q.y = y;
  q.z = z;
  return q;
}

/// The identity rotation.
inline glm::dquat identityQuat() noexcept {
  return quatWxyz(1.0, 0.0, 0.0, 0.0);
}

/// A rigid transform from an object's local frame to the world frame.
struct Pose {
  glm::dvec3 position{0.0};                 ///< world position of the local origin, m
  glm::dquat orientation = identityQuat();  ///< unit; rotates local axes to world axes
};

/// Whether every component is finite (no NaN, no infinity).
inline bool isFinite(const glm::dvec3& v) noexcept {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
inline bool isFinite(const glm::dquat& q) noexcept {
  return std::isfinite(q.w) && std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z);
}
inline bool isFinite(const Pose& pose) noexcept {
  return isFinite(pose.position) && isFinite(pose.orientation);
}

/// `pose` applied to a local point: world point, m.
inline glm::dvec3 apply(const Pose& pose, const glm::dvec3& pointLocal) noexcept {
  return pose.orientation * pointLocal + pose.position;
}

/// `pose` applied to a local direction (rotation only).
inline glm::dvec3 applyRotation(const Pose& pose, const glm::dvec3& directionLocal) noexcept {
  return pose.orientation * directionLocal;
}

/// The inverse transform (world → local).
inline Pose inverse(const Pose& pose) noexcept {
  const glm::dquat inv = glm::conjugate(pose.orientation);
  return Pose{-(inv * pose.position), inv};
}

/// `outer` after `inner`: apply(compose(outer, inner), p) == apply(outer, apply(inner, p)).
inline Pose compose(const Pose& outer, const Pose& inner) noexcept {
  return Pose{outer.orientation * inner.position + outer.position,
              glm::normalize(outer.orientation * inner.orientation)};
}

/// Rotation vector (axis · angle, rad, angle in [0, π]) of a unit quaternion, taking the
/// shortest way (q and −q give the same vector). Accurate for small and large angles.
inline glm::dvec3 rotationVector(const glm::dquat& q) noexcept {
  const double sign = q.w < 0.0 ? -1.0 : 1.0;
  const glm::dvec3 v(sign * q.x, sign * q.y, sign * q.z);
  const double s = glm::length(v);
  if (s == 0.0) return glm::dvec3(0.0);
  const double angle = 2.0 * std::atan2(s, sign * q.w);
  return v * (angle / s);
}

/// Unit quaternion of the rotation by `rotationVectorRad` (axis · angle, rad): the
/// exponential map. Accurate for small angles (series near zero).
inline glm::dquat quatFromRotationVector(const glm::dvec3& rotationVectorRad) noexcept {
  const double angle = glm::length(rotationVectorRad);
  const double half = 0.5 * angle;
  // sin(half)/angle, by its Taylor series when the angle is tiny
  const double k = angle < 1e-4 ? 0.5 - angle * angle / 48.0 : std::sin(half) / angle;
  return quatWxyz(std::cos(half), k * rotationVectorRad.x, k * rotationVectorRad.y, k * rotationVectorRad.z);
}

/// Spherical linear interpolation along the shorter arc between unit quaternions:
/// `a` at t = 0, `b` (or −b, whichever is nearer to `a`) at t = 1, unit length.
inline glm::dquat slerpShortest(const glm::dquat& a, const glm::dquat& b, double t) noexcept {
  glm::dquat c = b;
  if (glm::dot(a, b) < 0.0) c = -b;
  // half the angle between a and c on the unit 4-sphere, robust near 0 (unlike acos)
  const double theta = 2.0 * std::atan2(glm::length(c - a), glm::length(c + a));
  const double sinTheta = std::sin(theta);
  double wa = 1.0 - t;
  double wc = t;
  if (sinTheta > 1e-9) {
    wa = std::sin((1.0 - t) * theta) / sinTheta;
    wc = std::sin(t * theta) / sinTheta;
  }
  return glm::normalize(a * wa + c * wc);
}

/// Interpolated pose: slerp of the orientation (shortest arc), lerp of the position;
/// `a` at t = 0 and `b` at t = 1 exactly (up to the sign of the quaternion).
inline Pose interpolate(const Pose& a, const Pose& b, double t) noexcept {
  if (t <= 0.0) return a;
  if (t >= 1.0) return b;
  return Pose{a.position + (b.position - a.position) * t, slerpShortest(a.orientation, b.orientation, t)};
}

}  // namespace voxhap
