#pragma once
/// Joins a controller's haptic loop to its peer session (DESIGN §8): at the stream rate it
/// hands the session the newest local frame (the bodies this peer owns, what its users
/// hold), and from the session it queues the remote owners' states and the changes of
/// ownership for the haptic thread. Comms thread only, like the service it wraps.

#include <chrono>
#include <cstdint>
#include <functional>
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

private:
  void tick();
  net::LocalFrame localFrame();
  void ownerChanged(std::uint32_t object, PeerId owner);

  asio::steady_timer timer_;
  net::PeerSession& session_;
  ControllerService& service_;
  PeerLinkOptions options_;
  LogFn log_;
  std::chrono::steady_clock::duration period_;
  std::chrono::steady_clock::time_point next_;
  int takeObject_ = -1;
  bool takeGrabbed_ = false;
  bool stopped_ = false;
  PeerLinkCounts counts_;
};

}  // namespace voxhap::controller
