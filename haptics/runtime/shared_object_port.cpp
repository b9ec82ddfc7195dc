#include "haptics/runtime/shared_object_port.h"

#include <algorithm>
#include <span>

#include <glm/geometric.hpp>

namespace voxhap {

SharedObjectPort::Remote* SharedObjectPort::find(PeerId peer) noexcept {
  for (Remote& r : remotes_)
    if (r.peer == peer && peer != kNoPeer) return &r;
  return nullptr;
}

bool SharedObjectPort::take(PeerId peer, const RemoteSample& sample, double inJ,
                            std::int64_t arrivalUs) noexcept {
  if (peer == kNoPeer) return false;
  Remote* r = find(peer);
  if (r == nullptr) {
    for (Remote& slot : remotes_) {
      if (slot.peer != kNoPeer) continue;
      r = &slot;
      break;
    }
    if (r == nullptr) return false;
    *r = Remote{};
    r->peer = peer;
  }
  if (!r->buffer.push(sample, arrivalUs)) return false;
  r->inJ = std::max(r->inJ, inJ);  // cumulative: an overtaken one is older
  r->newestArrivalUs = arrivalUs;
  return true;
}

void SharedObjectPort::setDelay(PeerId peer, double oneWayS) noexcept {
  if (Remote* r = find(peer)) r->oneWayS = oneWayS;
}

void SharedObjectPort::drop(PeerId peer) noexcept {
  if (Remote* r = find(peer)) r->dropped = true;
}

const SharedObjectPort::Frame& SharedObjectPort::step(std::int64_t nowUs, const RigidBodyModel& model,
                                                      const RigidBodyState& local,
                                                      const CouplingGains& stiffest, bool passivity,
                                                      double dtS) noexcept {
  std::size_t n = 0;
  double othersInJ = 0.0;
  frame_.counted = 0;
  for (Remote& r : remotes_) {
    if (r.peer == kNoPeer) continue;
    RigidBodyState state;
    if (!(r.oneWayS >= 0.0) || !r.buffer.playOut(nowUs, state)) continue;
    if (r.rampStartUs < 0) r.rampStartUs = nowUs;
    const double silentS =
        1e-6 * static_cast<double>(std::max<std::int64_t>(nowUs - r.newestArrivalUs - kSilentUs, 0));
    const double ramp =
        std::clamp(static_cast<double>(nowUs - r.rampStartUs) / static_cast<double>(kJoinRampUs), 0.0, 1.0);
    const double weight = delayWeight(r.oneWayS + silentS) * ramp;
    if (r.dropped && weight == 0.0 && ramp == 1.0) {
      r = Remote{};  // faded out: the slot is free
      continue;
    }
    // the delay whose weight is `weight` (shared_coupling.h)
    instances_[n++] = {state, kSharedCouplingFadeDelayS * (1.0 - weight),
                       r.oneWayS + r.buffer.playoutDelayS(), r.buffer.playoutDelayS()};
    if (weight > 0.0) ++frame_.counted;
    othersInJ += r.inJ;
  }
  frame_.coupling =
      sharedCouplingWrench(stiffest, model, local, std::span(instances_.data(), n), {}, divergent_);
  divergent_ = frame_.coupling.divergent;
  const CouplingWrench w =
      passivity ? passivity_.passive(frame_.coupling.onLocal, model, local, othersInJ, n + 1, dtS)
                : frame_.coupling.onLocal;
  frame_.largestForceStepN =
      std::max(frame_.largestForceStepN, glm::length(w.forceWorld - frame_.wrench.forceWorld));
  frame_.wrench = {w.forceWorld, w.torqueWorld};
  frame_.inJ = passivity_.inJ();
  frame_.observedJ = passivity ? passivity_.observedJ() : 0.0;
  frame_.dissipatedJ = passivity_.dissipatedJ();
  return frame_;
}

}  // namespace voxhap
