#pragma once
/// The C++ client of the front-end protocol (docs/protocol.md): connects to a haptic
/// controller, says hello, sends requests and waits for their replies, and hands over
/// the events (FrameUpdate) that arrive in between. Blocking calls with time-outs, for
/// one thread; used by the tests and the renderer.

#include <chrono>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <string_view>

#include <asio/io_context.hpp>
#include <asio/ip/tcp.hpp>

#include "net/frontend/frame_codec.h"
#include "net/proto/frontend.pb.h"

namespace voxhap::net {

namespace pb = voxhap::frontend::v1;

class FrontendClient {
public:
  using Duration = std::chrono::milliseconds;

  /// Connects to `host:port`. Throws voxhap::Error when it cannot within `timeout`.
  FrontendClient(const std::string& host, std::uint16_t port, Duration timeout = Duration(5000));

  /// Says hello; returns the controller's reply. Throws voxhap::Error when the controller
  /// refuses (wrong version or token: the message says why) or does not answer.
  pb::HelloReply hello(const std::string& clientName, const std::string& token = {});

  /// Sends `request` under the next id and waits for its reply (an Error body when the
  /// request failed). Events that arrive first are kept for nextEvent(). Throws
  /// voxhap::Error when the connection closes or nothing comes within the time-out.
  pb::ServerMessage request(pb::ClientMessage request);

  /// The next event (id 0), waiting up to `timeout`; none when it does not come or the
  /// connection is closed.
  std::optional<pb::ServerMessage> nextEvent(Duration timeout);

  /// Sends `request` under the next id without waiting; returns the id. For a client that
  /// takes replies and events as they come (nextMessage), e.g. a window's network thread.
  std::uint64_t send(pb::ClientMessage request);
  /// The oldest message received and not taken yet, reply or event, waiting up to
  /// `timeout`; none when none comes or the connection is closed.
  std::optional<pb::ServerMessage> nextMessage(Duration timeout);

  /// Writes raw bytes to the stream (tests of the controller's handling of bad input).
  void sendRaw(std::string_view bytes);
  /// Waits up to `timeout` for the controller to close the connection; true when it did.
  /// Messages received meanwhile are kept.
  bool waitClosed(Duration timeout);

  /// The newest frame update of a subscribed client by now: a request's reply comes after
  /// every update sent before it, so the updates kept while waiting for it reach up to now
  /// (reading until a quiet gap would return a backlog's first). Waits up to `patience`
  /// for the first update after a subscription; none when it does not come.
  std::optional<pb::FrameUpdate> newestUpdate(Duration patience = Duration(10000));

  bool isOpen() const { return open_; }
  /// Time-out of hello() and request().
  void setTimeout(Duration timeout) { timeout_ = timeout; }

private:
  /// Takes the first received message of `id` (0: an event), reading up to `timeout` for
  /// it; none when it does not come or the connection is closed.
  std::optional<pb::ServerMessage> waitFor(std::uint64_t id, Duration timeout);
  /// Reads until a message arrives, the time-out or the end; false when none came.
  bool readMessage(Duration timeout);

  asio::io_context io_;
  asio::ip::tcp::socket socket_;
  FrameDecoder decoder_;
  std::deque<pb::ServerMessage> received_;
  std::uint64_t lastId_ = 0;
  Duration timeout_;
  bool open_ = false;
};

}  // namespace voxhap::net
