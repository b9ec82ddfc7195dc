#include "haptics/runtime/jitter_buffer.h"

#include <algorithm>
#include <limits>

#include "haptics/dynamics/pose.h"

namespace voxhap {

bool JitterBuffer::push(const RemoteSample& sample, std::int64_t arrivalUs) noexcept {
  if (count_ > 0 && sample.sentUs <= at(count_ - 1).sample.sentUs) return false;
  if (count_ == kCapacity) {
    first_ = (first_ + 1) % kCapacity;
    --count_;
  }
  ring_[(first_ + count_) % kCapacity] = Entry{sample, arrivalUs - sample.sentUs};
  ++count_;
  offsetUs_ = std::numeric_limits<std::int64_t>::max();
  for (std::size_t i = 0; i < count_; ++i) offsetUs_ = std::min(offsetUs_, at(i).transitUs);
  return true;
}

bool JitterBuffer::playOut(std::int64_t nowUs, RigidBodyState& out) const noexcept {
  if (count_ == 0) return false;
  const std::int64_t dueUs = nowUs - offsetUs_ - delayUs_;  // on the owner's clock
  const RemoteSample& oldest = at(0).sample;
  const RemoteSample& newest = at(count_ - 1).sample;
  if (dueUs <= oldest.sentUs) {
    out = oldest.body;
    return true;
  }
  if (dueUs >= newest.sentUs) {
    const double aheadS = 1e-6 * static_cast<double>(std::min(dueUs - newest.sentUs, kMaxExtrapolationUs));
    out = newest.body;
    out.comWorld += newest.body.linearVelocityWorld * aheadS;
    out.orientation = glm::normalize(quatFromRotationVector(newest.body.angularVelocityWorld * aheadS) *
                                     newest.body.orientation);
    return true;
  }
  std::size_t next = 1;
  while (at(next).sample.sentUs < dueUs) ++next;
  const RemoteSample& a = at(next - 1).sample;
  const RemoteSample& b = at(next).sample;
  const double t = static_cast<double>(dueUs - a.sentUs) / static_cast<double>(b.sentUs - a.sentUs);
  out = a.body;
  out.comWorld = a.body.comWorld + (b.body.comWorld - a.body.comWorld) * t;
  out.orientation = slerpShortest(a.body.orientation, b.body.orientation, t);
  out.linearVelocityWorld =
      a.body.linearVelocityWorld + (b.body.linearVelocityWorld - a.body.linearVelocityWorld) * t;
  out.angularVelocityWorld =
      a.body.angularVelocityWorld + (b.body.angularVelocityWorld - a.body.angularVelocityWorld) * t;
  return true;
}

}  // namespace voxhap
