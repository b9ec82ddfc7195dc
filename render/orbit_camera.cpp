#include "render/orbit_camera.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace voxhap::render {
namespace {

constexpr glm::dvec3 kUpWorld{0.0, 0.0, 1.0};

/// Centre and radius of the bounding sphere of a box; radius 0 for an empty box.
std::pair<glm::dvec3, double> sphereOf(const Bounds& b) {
  if (b.empty()) return {glm::dvec3(0.0), 0.0};
  return {0.5 * (b.min + b.max), 0.5 * glm::length(b.max - b.min)};
}

}  // namespace

glm::dvec3 OrbitCamera::forwardWorld() const {
  return -glm::dvec3(std::cos(pitchRad_) * std::cos(yawRad_), std::cos(pitchRad_) * std::sin(yawRad_),
                     std::sin(pitchRad_));
}

glm::dvec3 OrbitCamera::eyeWorld() const {
  return targetWorld_ - distanceM_ * forwardWorld();
}

glm::dvec3 OrbitCamera::rightWorld() const {
  return glm::normalize(glm::cross(forwardWorld(), kUpWorld));
}

glm::dvec3 OrbitCamera::upWorld() const {
  return glm::cross(rightWorld(), forwardWorld());
}

void OrbitCamera::setTarget(const glm::dvec3& targetWorld) {
  targetWorld_ = targetWorld;
  changed();
}

void OrbitCamera::setAngles(double yawRad, double pitchRad) {
  yawRad_ = std::remainder(yawRad, 2.0 * std::numbers::pi);
  pitchRad_ = std::clamp(pitchRad, -kPitchLimitRad, kPitchLimitRad);
  changed();
}

void OrbitCamera::setDistance(double distanceM) {
  distanceM_ = std::max(distanceM, 1e-6);
  changed();
}

void OrbitCamera::setSceneBounds(const Bounds& boundsWorld) {
  sceneBoundsWorld_ = boundsWorld;
  changed();
}

void OrbitCamera::orbit(double dxPx, double dyPx) {
  setAngles(yawRad_ - dxPx * kOrbitRadPerPx, pitchRad_ + dyPx * kOrbitRadPerPx);
}

void OrbitCamera::pan(double dxPx, double dyPx, const glm::ivec2& viewportPx) {
  const double metresPerPx = 2.0 * distanceM_ * std::tan(0.5 * kFovYRad) / std::max(viewportPx.y, 1);
  setTarget(targetWorld_ - rightWorld() * (dxPx * metresPerPx) + upWorld() * (dyPx * metresPerPx));
}

void OrbitCamera::zoom(double factor) {
  if (factor > 0.0 && std::isfinite(factor)) setDistance(distanceM_ * factor);
}

void OrbitCamera::frame(const Bounds& boundsWorld, double minAspect) {
  const auto [centre, radius] = sphereOf(boundsWorld);
  const double halfFovY = 0.5 * kFovYRad;
  const double halfFovX = std::atan(std::tan(halfFovY) * std::max(minAspect, 1e-3));
  const double halfFov = std::min(halfFovY, halfFovX);
  targetWorld_ = centre;
  distanceM_ = std::max(1.05 * radius / std::sin(halfFov), 1e-3);
  sceneBoundsWorld_ = boundsWorld;
  changed();
}

double OrbitCamera::farM() const {
  auto [centre, radius] = sphereOf(sceneBoundsWorld_);
  if (radius == 0.0) return 2.0 * distanceM_;
  // twice the radius: moving objects may leave the scene's bounds a little
  return glm::length(eyeWorld() - centre) + 2.0 * radius;
}

double OrbitCamera::nearM() const {
  auto [centre, radius] = sphereOf(sceneBoundsWorld_);
  const double far = farM();
  const double nearest = radius == 0.0 ? 0.0 : glm::length(eyeWorld() - centre) - 2.0 * radius;
  // a near/far ratio of at most 1:2000 keeps 24-bit depth fine enough
  return std::max(nearest, far / 2000.0);
}

glm::dmat4 OrbitCamera::viewMatrix() const {
  return glm::lookAt(eyeWorld(), targetWorld_, kUpWorld);
}

glm::dmat4 OrbitCamera::projectionMatrix(double aspect) const {
  return glm::perspective(kFovYRad, aspect > 0.0 ? aspect : 1.0, nearM(), farM());
}

glm::dmat4 OrbitCamera::viewProjection(const glm::ivec2& viewportPx) const {
  const double aspect = static_cast<double>(std::max(viewportPx.x, 1)) / std::max(viewportPx.y, 1);
  return projectionMatrix(aspect) * viewMatrix();
}

RayWorld OrbitCamera::rayThroughPixel(const glm::dvec2& pixelPx, const glm::ivec2& viewportPx) const {
  const double w = std::max(viewportPx.x, 1);
  const double h = std::max(viewportPx.y, 1);
  const double ndcX = 2.0 * pixelPx.x / w - 1.0;
  const double ndcY = 1.0 - 2.0 * pixelPx.y / h;
  const double tanHalf = std::tan(0.5 * kFovYRad);
  const glm::dvec3 direction =
      forwardWorld() + rightWorld() * (ndcX * tanHalf * w / h) + upWorld() * (ndcY * tanHalf);
  return RayWorld{eyeWorld(), glm::normalize(direction)};
}

ScreenPoint OrbitCamera::project(const glm::dvec3& pointWorld, const glm::ivec2& viewportPx) const {
  const glm::dvec4 clip = viewProjection(viewportPx) * glm::dvec4(pointWorld, 1.0);
  ScreenPoint s;
  s.inFront = clip.w > 0.0;
  if (clip.w == 0.0) return s;
  const glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
  s.pixelPx = {(ndc.x + 1.0) * 0.5 * viewportPx.x, (1.0 - ndc.y) * 0.5 * viewportPx.y};
  s.depthNdc = ndc.z;
  return s;
}

}  // namespace voxhap::render
