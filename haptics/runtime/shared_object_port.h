#pragma once
/// One shared object's coupling as the haptic thread runs it (type-2, DESIGN §8; issue
/// 14): the other sharing peers' instances as their streams arrive (a jitter buffer
/// each), their one-way delays and the energy each has put into its port; each frame, the
/// external wrench on the local instance (shared_coupling.h), made passive when asked
/// (coupling_passivity.h).
///
/// A remote instance's delay for its weight is its one-way delay, plus how long its stream
/// has been silent beyond kSilentUs (a 100 Hz stream's gaps do not ripple the weight; one
/// that stops fades out within a second of it). An instance counts only once its delay has
/// been measured (before, the safe weight is none: it may be a second old), and its weight
/// then ramps in over kJoinRampUs; a dropped one is kept until its weight has faded: no one
/// who joins, leaves or dies changes any force by a step.
///
/// Haptic thread only: fixed capacity, noexcept, no allocation.

#include <array>
#include <cstddef>
#include <cstdint>

#include "haptics/dynamics/coupling_passivity.h"
#include "haptics/dynamics/shared_coupling.h"
#include "haptics/runtime/jitter_buffer.h"
#include "haptics/sim/frame_io.h"
#include "haptics/sim/sim_state.h"

namespace voxhap {

class SharedObjectPort {
public:
  /// The most other sharing peers one object can have.
  static constexpr std::size_t kMaxRemotes = 7;
  /// A stream silent for longer than this begins to age, µs.
  static constexpr std::int64_t kSilentUs = 50'000;
  /// A new instance's weight grows from 0 to its delay's over this, µs.
  static constexpr std::int64_t kJoinRampUs = 500'000;

  /// The port's figures after a frame.
  struct Frame {
    ExternalWrench wrench;           ///< on the local instance
    SharedCoupling coupling;         ///< before passivity
    std::size_t counted = 0;         ///< remote instances with a weight above zero
    double inJ = 0.0;                ///< energy in at this port so far (0 when passivity is off)
    double observedJ = 0.0;          ///< the passivity observer (0 when off)
    double dissipatedJ = 0.0;        ///< by the passivity controller so far
    double largestForceStepN = 0.0;  ///< of the wrench's force from one frame to the next so far
  };

  /// Takes `peer`'s instance as sent, with the energy it has put into its port so far,
  /// arrived at `arrivalUs` (local clock). A peer not seen before takes a free slot; with
  /// none free its samples are dropped (false).
  bool take(PeerId peer, const RemoteSample& sample, double inJ, std::int64_t arrivalUs) noexcept;
  /// `peer`'s measured one-way delay, s (< 0: not measured; its instance does not count).
  void setDelay(PeerId peer, double oneWayS) noexcept;
  /// `peer` left or died: its stream ages from its last sample and its slot is freed once
  /// its weight has faded.
  void drop(PeerId peer) noexcept;

  /// This frame's wrench on `local` (an instance of `model`) at local time `nowUs`, with
  /// the gains `stiffest`; `passivity`: through the port's passivity controller.
  const Frame& step(std::int64_t nowUs, const RigidBodyModel& model, const RigidBodyState& local,
                    const CouplingGains& stiffest, bool passivity, double dtS) noexcept;

  const Frame& last() const noexcept { return frame_; }

private:
  struct Remote {
    PeerId peer = kNoPeer;  ///< kNoPeer: a free slot
    JitterBuffer buffer = JitterBuffer();
    double oneWayS = -1.0;  ///< < 0: not measured
    double inJ = 0.0;
    std::int64_t rampStartUs = -1;  ///< the first frame it counted in (< 0: not yet)
    std::int64_t newestArrivalUs = 0;
    bool dropped = false;
  };
  Remote* find(PeerId peer) noexcept;

  std::array<Remote, kMaxRemotes> remotes_{};
  std::array<RemoteInstance, kMaxRemotes> instances_{};
  CouplingPassivity passivity_;
  bool divergent_ = false;
  Frame frame_;
};

}  // namespace voxhap
