#include "haptics/device/scripted_device.h"

#include <cmath>
#include <sstream>
#include <utility>

#include "haptics/core/error.h"

namespace voxhap {

ScriptedDevice::ScriptedDevice(MotionScript script, const DeviceLimits& limits, double periodS)
    : script_(std::move(script)), limits_(limits), periodS_(periodS) {
  const std::string name = "scripted device (" + script_.sourceName() + ")";
  if (!(periodS_ > 0.0) || !std::isfinite(periodS_)) {
    std::ostringstream s;
    s << name << ": period must be a positive number of seconds, got " << periodS_;
    throw Error(s.str());
  }
  validateDeviceLimits(limits_, name);
}

Pose ScriptedDevice::handlePose(double tS) noexcept {
  return script_.sample(tS);
}

HandleVelocity ScriptedDevice::handleVelocity(double tS) noexcept {
  const Pose now = script_.sample(tS);
  const Pose before = script_.sample(tS - periodS_);
  HandleVelocity v;
  v.linearWorld = (now.position - before.position) / periodS_;
  v.angularWorld = rotationVector(now.orientation * glm::conjugate(before.orientation)) / periodS_;
  return v;
}

void ScriptedDevice::setFeedback(const CouplingWrench& feedbackWorld) noexcept {
  lastFeedback_ = feedbackWorld;
  ++feedbackCount_;
}

}  // namespace voxhap
