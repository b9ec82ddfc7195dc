#include "net/frontend/frontend_server.h"

#include <array>
#include <chrono>
#include <deque>
#include <map>
#include <optional>

#include <asio/steady_timer.hpp>
#include <asio/write.hpp>
#include <sodium.h>

namespace voxhap::net {

using asio::ip::tcp;

struct FrontendServer::State {
  State(asio::io_context& ioIn, const tcp::endpoint& endpoint, FrontendHandler& handlerIn,
        FrontendServerOptions optionsIn, LogFn logIn)
      : io(ioIn),
        acceptor(ioIn, endpoint),
        handler(handlerIn),
        options(std::move(optionsIn)),
        log(std::move(logIn)) {}

  asio::io_context& io;
  tcp::acceptor acceptor;
  FrontendHandler& handler;
  FrontendServerOptions options;
  LogFn log;
  FrontendServerCounters counters;
  std::map<std::uint64_t, std::shared_ptr<Session>> sessions;
  std::uint64_t nextClient = 1;
  bool closed = false;
};

class FrontendServer::Session : public std::enable_shared_from_this<Session> {
public:
  Session(std::shared_ptr<State> state, tcp::socket socket, std::uint64_t client)
      : state_(std::move(state)),
        socket_(std::move(socket)),
        client_(client),
        decoder_(state_->options.maxFrameBytes),
        updateTimer_(state_->io) {
    asio::error_code ignored;
    const tcp::endpoint remote = socket_.remote_endpoint(ignored);
    peer_ = remote.address().to_string() + ":" + std::to_string(remote.port());
  }

  void start() { readMore(); }

  /// Queues `message` unless the connection is closing; whether it did.
  bool push(const pb::ServerMessage& message) {
    if (closing_) return false;
    send(message);
    return true;
  }

  /// Sends `error` (unless empty) and closes once everything queued is written.
  void closeAfter(const std::string& reason, std::uint64_t id, bool violation) {
    if (closing_) return;
    if (violation) {
      ++state_->counters.violations;
      state_->log("client " + std::to_string(client_) + " (" + peer_ + ") closed: " + reason);
      pb::ServerMessage error;
      error.set_id(id);
      error.mutable_error()->set_message(reason);
      send(error);
    }
    closing_ = true;
    updateTimer_.cancel();
    if (!writing_) finish();
  }

private:
  void readMore() {
    auto self = shared_from_this();
    socket_.async_read_some(asio::buffer(readBuffer_), [this, self](asio::error_code ec, std::size_t n) {
      if (closing_ || state_->closed) return;
      if (ec) {
        if (decoder_.buffered() > 0) {
          closeAfter("connection ended inside a frame (" + std::to_string(decoder_.buffered()) +
                         " bytes of it received)",
                     0, true);
        } else {
          closeAfter("", 0, false);
        }
        return;
      }
      decoder_.feed(std::string_view(readBuffer_.data(), n));
      std::string payload;
      for (;;) {
        const FrameDecoder::Result r = decoder_.next(payload);
        if (r == FrameDecoder::Result::NeedMore) break;
        if (r == FrameDecoder::Result::Oversized) {
          closeAfter("frame of " + std::to_string(decoder_.announcedBytes()) + " bytes, over the limit of " +
                         std::to_string(state_->options.maxFrameBytes),
                     0, true);
          return;
        }
        onFrame(payload);
        if (closing_) return;
      }
      readMore();
    });
  }

  void onFrame(const std::string& payload) {
    pb::ClientMessage request;
    if (!request.ParseFromString(payload)) {
      closeAfter("a frame that is not a ClientMessage", 0, true);
      return;
    }
    if (request.id() <= lastId_) {
      closeAfter("request id " + std::to_string(request.id()) + " after " + std::to_string(lastId_) +
                     " (ids must be non-zero and increase)",
                 request.id(), true);
      return;
    }
    lastId_ = request.id();
    if (!helloDone_) {
      onHello(request);
      return;
    }
    ++state_->counters.requests;
    pb::ServerMessage reply;
    reply.set_id(request.id());
    switch (request.request_case()) {
      case pb::ClientMessage::kHello:
        closeAfter("a second hello", request.id(), true);
        return;
      case pb::ClientMessage::kSubscribe:
        subscribe(request.subscribe(), reply);
        break;
      case pb::ClientMessage::REQUEST_NOT_SET:
        reply.mutable_error()->set_message("unknown request (a newer protocol?)");
        break;
      default:
        state_->handler.handle(client_, request, reply);
        break;
    }
    if (reply.body_case() != pb::ServerMessage::BODY_NOT_SET) send(reply);  // else the handler replies later
  }

  void onHello(const pb::ClientMessage& request) {
    if (request.request_case() != pb::ClientMessage::kHello) {
      closeAfter("a request before the hello", request.id(), true);
      return;
    }
    const pb::Hello& hello = request.hello();
    if (hello.protocol_version() != kProtocolVersion) {
      closeAfter("protocol version " + std::to_string(hello.protocol_version()) +
                     " (this controller speaks " + std::to_string(kProtocolVersion) + ")",
                 request.id(), true);
      return;
    }
    const std::string& expected = state_->options.token;
    if (!expected.empty() && (hello.token().size() != expected.size() ||
                              sodium_memcmp(hello.token().data(), expected.data(), expected.size()) != 0)) {
      closeAfter("wrong token", request.id(), true);
      return;
    }
    helloDone_ = true;
    state_->log("client " + std::to_string(client_) + " (" + peer_ + ") is '" + hello.client_name() + "'");
    pb::ServerMessage reply;
    reply.set_id(request.id());
    reply.mutable_hello_reply()->set_protocol_version(kProtocolVersion);
    state_->handler.hello(*reply.mutable_hello_reply());
    send(reply);
  }

  void subscribe(const pb::Subscribe& request, pb::ServerMessage& reply) {
    const double rateHz = request.rate_hz();
    if (!(rateHz == 0.0 || (rateHz >= 1.0 && rateHz <= 1000.0))) {
      reply.mutable_error()->set_message("rate_hz wants 1 to 1000 Hz, or 0 to stop");
      reply.mutable_error()->set_field("rate_hz");
      return;
    }
    reply.mutable_done();
    rateHz_ = rateHz;
    updateTimer_.cancel();
    if (rateHz_ > 0.0) {
      nextUpdate_ = std::chrono::steady_clock::now();
      scheduleUpdate();
    }
  }

  void scheduleUpdate() {
    const auto period = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(1.0 / rateHz_));
    nextUpdate_ += period;
    const auto now = std::chrono::steady_clock::now();
    if (nextUpdate_ < now) nextUpdate_ = now + period;  // fell behind: no burst to catch up
    updateTimer_.expires_at(nextUpdate_);
    auto self = shared_from_this();
    updateTimer_.async_wait([this, self](asio::error_code ec) {
      if (ec || closing_ || state_->closed || rateHz_ <= 0.0) return;
      if (writeQueue_.size() >= state_->options.maxQueuedFrames) {
        ++state_->counters.updatesSkipped;
      } else {
        pb::ServerMessage event;
        state_->handler.frameUpdate(*event.mutable_frame_update());
        const std::uint64_t frame = event.frame_update().frame();
        if (lastFrameSent_ == frame) {
          ++state_->counters.updatesUnchanged;  // the loop has not stepped since: nothing new
        } else {
          lastFrameSent_ = frame;
          ++state_->counters.updatesSent;
          send(event);
        }
      }
      scheduleUpdate();
    });
  }

  void send(const pb::ServerMessage& message) {
    std::string frame;
    appendFrame(frame, message.SerializeAsString());
    writeQueue_.push_back(std::move(frame));
    if (!writing_) writeNext();
  }

  void writeNext() {
    writing_ = true;
    auto self = shared_from_this();
    asio::async_write(socket_, asio::buffer(writeQueue_.front()),
                      [this, self](asio::error_code ec, std::size_t) {
                        writeQueue_.pop_front();
                        if (ec) {
                          writeQueue_.clear();
                          writing_ = false;
                          closing_ = true;
                          finish();
                          return;
                        }
                        if (!writeQueue_.empty()) {
                          writeNext();
                          return;
                        }
                        writing_ = false;
                        if (closing_) finish();
                      });
  }

  void finish() {
    if (finished_) return;
    finished_ = true;
    asio::error_code ignored;
    socket_.shutdown(tcp::socket::shutdown_both, ignored);
    socket_.close(ignored);
    updateTimer_.cancel();
    if (!state_->closed) state_->handler.disconnected(client_);
    state_->sessions.erase(client_);  // may drop the last reference but self's
  }

  std::shared_ptr<State> state_;
  tcp::socket socket_;
  std::uint64_t client_;
  std::string peer_;
  std::array<char, 64 * 1024> readBuffer_{};
  FrameDecoder decoder_;
  std::deque<std::string> writeQueue_;
  bool writing_ = false;
  bool closing_ = false;
  bool finished_ = false;
  bool helloDone_ = false;
  std::uint64_t lastId_ = 0;
  asio::steady_timer updateTimer_;
  double rateHz_ = 0.0;
  std::optional<std::uint64_t> lastFrameSent_;  ///< none before the first update
  std::chrono::steady_clock::time_point nextUpdate_;
};

FrontendServer::FrontendServer(asio::io_context& io, const tcp::endpoint& endpoint, FrontendHandler& handler,
                               FrontendServerOptions options, LogFn log)
    : state_(std::make_shared<State>(io, endpoint, handler, std::move(options), std::move(log))),
      counters_(state_->counters) {
  if (sodium_init() < 0) throw std::runtime_error("libsodium failed to initialize");
  accept();
}

FrontendServer::~FrontendServer() {
  state_->closed = true;  // no handler call from here on: the handler may be going too
  close();
  // A session still writing stays until its write ends, which it may never do once the
  // io_context stops: the map lets go of it, so that only its pending handlers hold it
  // (the session holds the state; the state must not hold it back).
  state_->sessions.clear();
}

tcp::endpoint FrontendServer::endpoint() const {
  return state_->acceptor.local_endpoint();
}

std::size_t FrontendServer::clients() const {
  return state_->sessions.size();
}

bool FrontendServer::send(std::uint64_t client, const pb::ServerMessage& message) {
  const auto it = state_->sessions.find(client);
  return it != state_->sessions.end() && it->second->push(message);
}

void FrontendServer::close() {
  asio::error_code ignored;
  state_->acceptor.close(ignored);
  const auto sessions = state_->sessions;  // closing one erases it from the map
  for (const auto& [client, session] : sessions) session->closeAfter("", 0, false);
}

void FrontendServer::accept() {
  std::shared_ptr<State> state = state_;
  state->acceptor.async_accept([this, state](asio::error_code ec, tcp::socket socket) {
    if (ec || state->closed) return;
    ++state->counters.connections;
    const std::uint64_t client = state->nextClient++;
    if (state->sessions.size() >= state->options.maxClients) {
      ++state->counters.refused;
      state->log("client " + std::to_string(client) + " refused: already " +
                 std::to_string(state->options.maxClients) + " clients");
      asio::error_code ignored;
      socket.close(ignored);
    } else {
      // small frames go out at once: Nagle's wait for an ACK the client delays (40 ms on
      // Linux) would hold every frame update behind the one before
      asio::error_code ignored;
      socket.set_option(tcp::no_delay(true), ignored);
      auto session = std::make_shared<Session>(state, std::move(socket), client);
      state->sessions.emplace(client, session);
      session->start();
    }
    accept();
  });
}

}  // namespace voxhap::net
