#pragma once
/// Joins a controller's haptic loop to its peer session (DESIGN §8): at the stream rate it
/// hands the session the newest local frame (the bodies this peer owns, what its users
/// hold), and from the session it queues the remote owners' states and the changes of
/// ownership for the haptic thread. Comms thread only, like the service it wraps.
///
/// A shared object (type-2): the link first follows its owner's instance like any remote
/// object, and begins sharing (its own instance, coupled to the others') once that
/// instance has been followed for kFollowBeforeSharing, or at once when nobody else
/// shares it. So a peer that joins a shared object starts at the others' instance, at
/// their velocity. It then hands the haptic thread the other sharers' instances and
/// delays, and who stops sharing.

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <set>
#include <string>

#include <asio/io_context.hpp>
#include <asio/steady_timer.hpp>

#include "app/controller/controller_service.h"
#include "net/peer/peer_session.h"

namespace voxhap::controller {

struct PeerLinkOptions {
  double streamHz = 200.0;  ///< heartbeats and states per second to every member
  std::string take;         ///< an object to ask for at once (empty: none)
  std::string takeDevice;   ///< a Grab device that holds `take` once it is this peer's
  std::string share;        ///< an object to share (type-2; empty: none); takeDevice holds it
  bool passivity = true;    ///< the shared object's coupling through the passivity controller
};

/// The shared object's coupling as the link saw it at its ticks.
struct SharedLinkStats {
  std::uint64_t ticks = 0;           ///< ticks while sharing
  std::uint64_t coupledTicks = 0;    ///< of them, with another instance counted
  std::uint64_t divergentTicks = 0;  ///< of them, divergent here
  double sumApartM = 0.0;            ///< over the coupled ticks
  double maxApartM = 0.0;
  double maxStiffnessShare = 0.0;  ///< of the handle's stiffness (SharedCoupling::stiffnessShare)
  double minObservedJ = 0.0;       ///< the passivity observer's least
  double inJ = 0.0;                ///< at the last tick
  double dissipatedJ = 0.0;
  double largestForceStepN = 0.0;  ///< of the coupling's force from one frame to the next
  std::uint64_t sharedStates = 0;  ///< other instances' states queued
};

/// What the link counted.
struct PeerLinkCounts {
  std::uint64_t remoteStates = 0;         ///< remote bodies queued for the haptic thread
  std::uint64_t remoteStatesDropped = 0;  ///< its queue was full
  std::uint64_t ownerChanges = 0;
  std::uint64_t ticks = 0;
};

class PeerLink {
public:
  using LogFn = std::function<void(const std::string&)>;

  /// Starts `session` on the state `service`'s loop runs and ticks it on `io` until stop().
  /// Throws Error for a `take` that is no moving object.
  PeerLink(asio::io_context& io, net::PeerSession& session, ControllerService& service,
           PeerLinkOptions options, LogFn log);
  /// Sends the session's leaving heartbeat and stops ticking.
  void stop();
  const PeerLinkCounts& counts() const { return counts_; }
  /// -1: this peer shares no object.
  int sharedObject() const { return sharing_ ? shareObject_ : -1; }
  const SharedLinkStats& sharedStats() const { return shared_; }

  static constexpr std::chrono::milliseconds kFollowBeforeSharing{300};

private:
  void tick();
  net::LocalFrame localFrame();
  void ownerChanged(std::uint32_t object, PeerId owner);
  /// Begins sharing when it may (see the file comment); then passes on the sharers' changes.
  void tickShared(const FrameSnapshot& s);
  void grab(const std::string& object);

  asio::steady_timer timer_;
  net::PeerSession& session_;
  ControllerService& service_;
  PeerLinkOptions options_;
  LogFn log_;
  std::chrono::steady_clock::duration period_;
  std::chrono::steady_clock::time_point next_;
  int takeObject_ = -1;
  bool takeGrabbed_ = false;
  int shareObject_ = -1;
  bool sharing_ = false;
  std::optional<std::chrono::steady_clock::time_point> followedSince_;
  std::set<PeerId> sharers_;  ///< the other sharers as last passed on
  SharedLinkStats shared_;
  bool stopped_ = false;
  PeerLinkCounts counts_;
};

}  // namespace voxhap::controller
