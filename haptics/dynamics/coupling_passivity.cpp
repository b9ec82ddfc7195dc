#include "haptics/dynamics/coupling_passivity.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "haptics/dynamics/pose.h"

namespace voxhap {

CouplingWrench CouplingPassivity::passive(const CouplingWrench& onLocal, const RigidBodyModel& model,
                                          const RigidBodyState& local, double othersInJ, std::size_t ports,
                                          double dtS) noexcept {
  if (!charged_) {
    // the last frame's work, as the step did it
    const double workJ = glm::dot(last_.forceWorld, local.comWorld - lastStart_.comWorld) +
                         glm::dot(last_.torqueWorld,
                                  rotationVector(local.orientation * glm::conjugate(lastStart_.orientation)));
    if (std::isfinite(workJ)) (workJ > 0.0 ? outJ_ : inJ_) += std::abs(workJ);
    charged_ = true;
  }
  if (ports < 2 || !(dtS > 0.0) || !std::isfinite(othersInJ)) return onLocal;
  const double shareJ = (inJ_ + std::max(othersInJ, 0.0)) / static_cast<double>(ports);
  // what is left of the share fades: energy put in long ago is not given back now
  forgottenJ_ += std::max(shareJ - outJ_ - forgottenJ_, 0.0) * std::min(1.0, dtS / kForgetS);
  observedJ_ = shareJ - outJ_ - forgottenJ_;

  // the work this frame's wrench would do, c·a + c²·b when scaled by c
  const glm::dvec3 turnPerImpulse = inverseInertiaWorld(model, local.orientation) * onLocal.torqueWorld;
  const double a = dtS * (glm::dot(onLocal.forceWorld, local.linearVelocityWorld) +
                          glm::dot(onLocal.torqueWorld, local.angularVelocityWorld));
  const double b = dtS * dtS *
                   (glm::dot(onLocal.forceWorld, onLocal.forceWorld) * model.inverseMassPerKg +
                    glm::dot(onLocal.torqueWorld, turnPerImpulse));
  const double allowedJ = std::max(observedJ_, 0.0);
  CouplingWrench out = onLocal;
  if (std::isfinite(a) && std::isfinite(b) && a + b > allowedJ && b > 0.0) {
    const double c = std::clamp((-a + std::sqrt(a * a + 4.0 * b * allowedJ)) / (2.0 * b), 0.0, 1.0);
    out.forceWorld *= c;
    out.torqueWorld *= c;
    dissipatedJ_ += (a + b) - (c * a + c * c * b);
  }
  last_ = out;
  lastStart_ = local;
  charged_ = false;
  return out;
}

}  // namespace voxhap
