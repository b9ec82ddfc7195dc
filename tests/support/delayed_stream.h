#pragma once
/// Test support for shared objects: one peer's stream of its instance to another, sent at
/// 100 Hz (every tenth 1 kHz frame) and delivered a whole number of frames later.

#include <deque>

#include "haptics/dynamics/rigid_body.h"

namespace voxhap::test {

class DelayedStream {
public:
  struct Sent {
    int frame = 0;
    RigidBodyState state;
    double inJ = 0.0;  ///< the sender's energy into its coupling port so far, J
  };

  explicit DelayedStream(int delayFrames) : delayFrames_(delayFrames) {}

  /// Sends `state` at `frame` when the stream's rate says so.
  void send(int frame, const RigidBodyState& state, double inJ = 0.0) {
    if (frame % 10 == 0) sent_.push_back({frame, state, inJ});
  }
  /// The newest state delivered by `frame`; nullptr before the first.
  const Sent* newest(int frame) const {
    const Sent* found = nullptr;
    for (const Sent& s : sent_)
      if (s.frame + delayFrames_ <= frame) found = &s;
    return found;
  }

private:
  int delayFrames_;
  std::deque<Sent> sent_;
};

}  // namespace voxhap::test
