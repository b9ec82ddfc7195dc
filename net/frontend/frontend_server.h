#pragma once
/// The controller's side of the front-end protocol (docs/protocol.md): accepts TCP
/// connections, checks each one's hello (protocol version, token), decodes framed
/// requests, hands them to a FrontendHandler and sends its replies, and pushes
/// FrameUpdate events to subscribers at the rate each asked for.
///
/// Threads: everything here, the handler's calls included, runs on the thread that runs
/// the io_context (the controller's comms thread). A connection that breaks the protocol
/// (oversized, truncated or unparsable frames, ids that do not increase, a request before
/// the hello, a wrong version or token) is closed with the reason passed to the log
/// function; the server and its other connections go on.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include <asio/io_context.hpp>
#include <asio/ip/tcp.hpp>

#include "net/frontend/frame_codec.h"
#include "net/proto/frontend.pb.h"

namespace voxhap::net {

namespace pb = voxhap::frontend::v1;

/// What the controller does with requests. Called on the comms thread only.
class FrontendHandler {
public:
  virtual ~FrontendHandler() = default;
  /// Fills the reply to a hello that passed the version and token checks.
  virtual void hello(pb::HelloReply& reply) = 0;
  /// Fills `reply`'s body for any request but Hello and Subscribe (an Error when it fails).
  /// A body left empty defers the reply: the handler sends it later with
  /// FrontendServer::send (a long load, say).
  virtual void handle(std::uint64_t client, const pb::ClientMessage& request, pb::ServerMessage& reply) = 0;
  /// Fills the newest frame for a subscriber.
  virtual void frameUpdate(pb::FrameUpdate& update) = 0;
  /// The connection is gone (closed by either side).
  virtual void disconnected(std::uint64_t client) = 0;
};

struct FrontendServerOptions {
  std::string token;  ///< required in every hello when not empty
  std::size_t maxClients = 16;
  std::uint32_t maxFrameBytes = kMaxFrameBytes;
  /// Frames a client may leave unread before its FrameUpdates are skipped (latest wins).
  std::size_t maxQueuedFrames = 64;
};

/// Counts of what the server saw, for the controller's statistics.
struct FrontendServerCounters {
  std::uint64_t connections = 0;       ///< accepted
  std::uint64_t refused = 0;           ///< over maxClients
  std::uint64_t violations = 0;        ///< connections closed for breaking the protocol
  std::uint64_t requests = 0;          ///< requests handled
  std::uint64_t updatesSent = 0;       ///< FrameUpdate events
  std::uint64_t updatesSkipped = 0;    ///< FrameUpdates not sent to a client that read too slowly
  std::uint64_t updatesUnchanged = 0;  ///< FrameUpdates not sent: the frame had not advanced
};

class FrontendServer {
public:
  using LogFn = std::function<void(const std::string&)>;

  /// Listens on `endpoint` (port 0: any free port). Throws std::system_error when it
  /// cannot bind.
  FrontendServer(asio::io_context& io, const asio::ip::tcp::endpoint& endpoint, FrontendHandler& handler,
                 FrontendServerOptions options, LogFn log);
  ~FrontendServer();
  FrontendServer(const FrontendServer&) = delete;
  FrontendServer& operator=(const FrontendServer&) = delete;

  /// The address it listens on (the port chosen when 0 was asked for).
  asio::ip::tcp::endpoint endpoint() const;
  /// Stops accepting and closes every connection once what it was sent is written.
  void close();
  const FrontendServerCounters& counters() const { return counters_; }
  std::size_t clients() const;
  /// Queues `message` (a deferred reply, an event) for `client`; false when that client is
  /// gone or closing. Comms thread only.
  bool send(std::uint64_t client, const pb::ServerMessage& message);

private:
  class Session;
  struct State;
  void accept();
  std::shared_ptr<State> state_;
  FrontendServerCounters& counters_;
};

}  // namespace voxhap::net
