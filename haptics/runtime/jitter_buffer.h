#pragma once
/// The jitter buffer of one remote object (DESIGN §8, type-1): the states its owner
/// streams, 100 Hz to 1 kHz, arriving late, unevenly, out of order or not at all, played
/// out at 1 kHz on the local timeline a fixed delay behind the newest.
///
/// Timeline. Each sample carries its owner's clock (µs) when the owner's frame ended; its
/// arrival is read on the local clock. The smallest arrival − send of the samples held
/// (the least delayed one, clock offset included) maps the owner's clock onto ours: a
/// sample sent at s is due locally at s + that offset + the playout delay. The delay
/// covers the jitter (a sample later than the least delayed one by more than it arrives
/// after its time and is interpolated towards instead). The window of samples follows a
/// drifting clock, since the offset is taken afresh over the samples held.
///
/// Play-out at local time t: between the two samples around t (positions and velocities
/// linearly, orientations by the shortest slerp); past the newest, extrapolated with its
/// velocities for at most kMaxExtrapolationUs, then held; before the oldest, the oldest.
///
/// Haptic thread only: fixed capacity, noexcept, no allocation after construction.

#include <array>
#include <cstddef>
#include <cstdint>

#include "haptics/dynamics/rigid_body.h"

namespace voxhap {

/// One state of a remote object as its owner sent it.
struct RemoteSample {
  std::int64_t sentUs = 0;  ///< the owner's clock at its frame's end, µs
  RigidBodyState body;      ///< world frame
};

class JitterBuffer {
public:
  static constexpr std::size_t kCapacity = 32;
  /// The longest a play-out runs ahead of the newest sample on its velocities, µs.
  static constexpr std::int64_t kMaxExtrapolationUs = 50'000;

  /// Samples played `playoutDelayUs` after their least delayed arrival.
  explicit JitterBuffer(std::int64_t playoutDelayUs = 30'000) noexcept : delayUs_(playoutDelayUs) {}

  /// Takes `sample`, arrived at `arrivalUs` on the local clock. A sample no newer than the
  /// newest held is a duplicate or overtaken and is dropped (false): the stream is latest-
  /// wins, and its neighbours interpolate over it. The oldest goes when full.
  bool push(const RemoteSample& sample, std::int64_t arrivalUs) noexcept;

  /// The state due at local time `nowUs` into `out`; false (out untouched) while empty.
  bool playOut(std::int64_t nowUs, RigidBodyState& out) const noexcept;

  /// Forgets every sample (the owner changed, or left).
  void clear() noexcept { count_ = 0; }

  std::size_t size() const noexcept { return count_; }
  /// How far behind its least delayed arrival a sample is played, s.
  double playoutDelayS() const noexcept { return 1e-6 * static_cast<double>(delayUs_); }
  /// Local time minus the owner's clock of the least delayed sample held, µs.
  std::int64_t offsetUs() const noexcept { return offsetUs_; }

private:
  struct Entry {
    RemoteSample sample;
    std::int64_t transitUs = 0;  ///< arrival − sent
  };
  const Entry& at(std::size_t i) const noexcept { return ring_[(first_ + i) % kCapacity]; }

  std::array<Entry, kCapacity> ring_{};  ///< in order of sent time, oldest at first_
  std::size_t first_ = 0;
  std::size_t count_ = 0;
  std::int64_t offsetUs_ = 0;
  std::int64_t delayUs_;
};

}  // namespace voxhap
