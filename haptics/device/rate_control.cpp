#include "haptics/device/rate_control.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "haptics/core/error.h"

namespace voxhap {
namespace {

void require(bool ok, const std::string& owner, const char* field, double value, const char* range) {
  if (ok) return;
  std::ostringstream s;
  s << owner << ": rate control " << field << " must be " << range << ", got " << value;
  throw Error(s.str());
}

}  // namespace

void validateRateControlParams(const RateControlParams& params, const std::string& owner) {
  require(params.deadZone >= 0.0 && params.deadZone < 1.0, owner, "deadZone", params.deadZone, "in [0, 1)");
  require(params.linearGainMPerS >= 0.0 && std::isfinite(params.linearGainMPerS), owner, "linearGainMPerS",
          params.linearGainMPerS, "a finite number >= 0");
  require(params.angularGainRadPerS >= 0.0 && std::isfinite(params.angularGainRadPerS), owner,
          "angularGainRadPerS", params.angularGainRadPerS, "a finite number >= 0");
  require(params.cubicShaping >= 0.0 && params.cubicShaping <= 1.0, owner, "cubicShaping",
          params.cubicShaping, "in [0, 1]");
  const double norm = glm::length(params.viewToWorld);
  require(isFinite(params.viewToWorld) && std::abs(norm - 1.0) < 1e-6, owner, "viewToWorld (its norm)", norm,
          "a unit quaternion");
}

double shapeDeflection(double deflection, const RateControlParams& params) noexcept {
  if (!std::isfinite(deflection)) return 0.0;
  const double magnitude = std::min(std::abs(deflection), 1.0);
  if (magnitude <= params.deadZone) return 0.0;
  const double u = (magnitude - params.deadZone) / (1.0 - params.deadZone);
  const double shaped = (1.0 - params.cubicShaping) * u + params.cubicShaping * u * u * u;
  return deflection < 0.0 ? -shaped : shaped;
}

HandleVelocity pivotVelocityWorld(const std::array<double, kAxisCount>& deflectionView,
                                  const RateControlParams& params) noexcept {
  const glm::dvec3 linearView(shapeDeflection(deflectionView[kAxisTx], params),
                              shapeDeflection(deflectionView[kAxisTy], params),
                              shapeDeflection(deflectionView[kAxisTz], params));
  const glm::dvec3 angularView(shapeDeflection(deflectionView[kAxisRx], params),
                               shapeDeflection(deflectionView[kAxisRy], params),
                               shapeDeflection(deflectionView[kAxisRz], params));
  HandleVelocity v;
  v.linearWorld = params.viewToWorld * (linearView * params.linearGainMPerS);
  v.angularWorld = params.viewToWorld * (angularView * params.angularGainRadPerS);
  return v;
}

RateController::RateController(const RateControlParams& params, const Pose& startWorld,
                               const glm::dvec3& pivotLocal)
    : params_(params), pivotLocal_(pivotLocal), handle_(startWorld) {
  validateRateControlParams(params_, "rate controller");
  if (!isFinite(startWorld) || !isFinite(pivotLocal))
    throw Error("rate controller: the start pose and the pivot must be finite");
  handle_.orientation = glm::normalize(handle_.orientation);
}

void RateController::reset(const Pose& startWorld) noexcept {
  handle_ = startWorld;
  handle_.orientation = glm::normalize(handle_.orientation);
  velocity_ = {};
}

void RateController::step(const std::array<double, kAxisCount>& deflectionView, double dtS) noexcept {
  if (!(dtS >= 0.0) || !std::isfinite(dtS)) dtS = 0.0;
  const HandleVelocity pivot = pivotVelocityWorld(deflectionView, params_);
  const glm::dvec3 pivotWorld = apply(handle_, pivotLocal_);
  const glm::dquat turn = quatFromRotationVector(pivot.angularWorld * dtS);
  // the origin swings about the pivot, which itself moves by v·dt
  const glm::dvec3 pivotToOrigin = handle_.position - pivotWorld;
  handle_.position = pivotWorld + pivot.linearWorld * dtS + turn * pivotToOrigin;
  handle_.orientation = glm::normalize(turn * handle_.orientation);
  velocity_.linearWorld = pivot.linearWorld + glm::cross(pivot.angularWorld, pivotToOrigin);
  velocity_.angularWorld = pivot.angularWorld;
}

}  // namespace voxhap
