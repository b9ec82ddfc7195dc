#include "net/frontend/frontend_client.h"

#include <array>
#include <thread>

#include <asio/connect.hpp>
#include <asio/write.hpp>
#include <google/protobuf/descriptor.h>

#include "haptics/core/error.h"

namespace voxhap::net {

using asio::ip::tcp;

FrontendClient::FrontendClient(const std::string& host, std::uint16_t port, Duration timeout)
    : socket_(io_), timeout_(timeout) {
  tcp::resolver resolver(io_);
  asio::error_code ec;
  const auto endpoints = resolver.resolve(host, std::to_string(port), ec);
  if (ec) throw Error("cannot resolve " + host + ": " + ec.message());
  asio::error_code connectError;
  bool done = false;
  asio::async_connect(socket_, endpoints, [&](asio::error_code e, const tcp::endpoint&) {
    connectError = e;
    done = true;
  });
  io_.run_for(timeout);
  if (!done) {
    socket_.close();
    io_.restart();
    io_.run();
    connectError = asio::error::timed_out;
  }
  if (connectError) {
    throw Error("cannot connect to " + host + ":" + std::to_string(port) + ": " + connectError.message());
  }
  socket_.set_option(tcp::no_delay(true));
  open_ = true;
}

pb::HelloReply FrontendClient::hello(const std::string& clientName, const std::string& token) {
  pb::ClientMessage message;
  pb::Hello& hello = *message.mutable_hello();
  hello.set_protocol_version(kProtocolVersion);
  hello.set_client_name(clientName);
  hello.set_token(token);
  const pb::ServerMessage reply = request(std::move(message));
  if (reply.has_error()) throw Error("the controller refused the hello: " + reply.error().message());
  if (!reply.has_hello_reply()) throw Error("the controller answered the hello with something else");
  return reply.hello_reply();
}

std::uint64_t FrontendClient::send(pb::ClientMessage request) {
  if (!open_) throw Error("the connection to the controller is closed");
  const std::uint64_t id = ++lastId_;
  request.set_id(id);
  std::string frame;
  appendFrame(frame, request.SerializeAsString());
  sendRaw(frame);
  return id;
}

std::optional<pb::ServerMessage> FrontendClient::nextMessage(Duration timeout) {
  if (received_.empty() && !readMessage(timeout)) return std::nullopt;
  pb::ServerMessage message = std::move(received_.front());
  received_.pop_front();
  return message;
}

pb::ServerMessage FrontendClient::request(pb::ClientMessage request) {
  const google::protobuf::FieldDescriptor* kind =
      pb::ClientMessage::descriptor()->FindFieldByNumber(request.request_case());
  const std::string what = kind ? kind->name() : std::string("request");
  const std::uint64_t id = send(std::move(request));
  std::optional<pb::ServerMessage> reply = waitFor(id, timeout_);
  if (!reply) {
    throw Error(open_ ? "no reply to " + what + " from the controller within " +
                            std::to_string(timeout_.count()) + " ms"
                      : "the controller closed the connection before it replied to " + what);
  }
  return std::move(*reply);
}

std::optional<pb::ServerMessage> FrontendClient::nextEvent(Duration timeout) {
  return waitFor(0, timeout);
}

std::optional<pb::ServerMessage> FrontendClient::waitFor(std::uint64_t id, Duration timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    for (auto it = received_.begin(); it != received_.end(); ++it) {
      if (it->id() == id) {
        pb::ServerMessage message = std::move(*it);
        received_.erase(it);
        return message;
      }
    }
    const auto left = std::chrono::duration_cast<Duration>(deadline - std::chrono::steady_clock::now());
    if (left <= Duration(0) || !readMessage(left)) return std::nullopt;
  }
}

void FrontendClient::sendRaw(std::string_view bytes) {
  asio::error_code ec;
  asio::write(socket_, asio::buffer(bytes.data(), bytes.size()), ec);
  if (ec) {
    open_ = false;
    throw Error("cannot write to the controller: " + ec.message());
  }
}

bool FrontendClient::waitClosed(Duration timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (open_) {
    const auto left = std::chrono::duration_cast<Duration>(deadline - std::chrono::steady_clock::now());
    if (left <= Duration(0)) return false;
    readMessage(left);
  }
  return true;
}

bool FrontendClient::readMessage(Duration timeout) {
  std::string payload;
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (open_) {
    const FrameDecoder::Result r = decoder_.next(payload);
    if (r == FrameDecoder::Result::Oversized) {
      open_ = false;
      throw Error("the controller sent a frame of " + std::to_string(decoder_.announcedBytes()) + " bytes");
    }
    if (r == FrameDecoder::Result::Frame) {
      pb::ServerMessage message;
      if (!message.ParseFromString(payload))
        throw Error("the controller sent a frame that is not a ServerMessage");
      received_.push_back(std::move(message));
      return true;
    }
    std::array<char, 64 * 1024> buffer;
    std::size_t got = 0;
    bool done = false;
    asio::error_code readError;
    socket_.async_read_some(asio::buffer(buffer), [&](asio::error_code e, std::size_t n) {
      readError = e;
      got = n;
      done = true;
    });
    io_.restart();
    const auto left = deadline - std::chrono::steady_clock::now();
    io_.run_for(left > std::chrono::steady_clock::duration(0) ? left
                                                              : std::chrono::steady_clock::duration(0));
    if (!done) {
      // time is up: cancel the read and let its handler run before `buffer` goes
      socket_.cancel();
      io_.restart();
      io_.run();
    }
    if (readError == asio::error::operation_aborted) return false;
    if (readError) {
      open_ = false;
      return false;
    }
    decoder_.feed(std::string_view(buffer.data(), got));
  }
  return false;
}

std::optional<pb::FrameUpdate> FrontendClient::newestUpdate(Duration patience) {
  std::optional<pb::FrameUpdate> last;
  const auto giveUp = std::chrono::steady_clock::now() + patience;
  for (bool first = true; !last && (first || std::chrono::steady_clock::now() < giveUp); first = false) {
    if (!first) std::this_thread::sleep_for(Duration(20));
    pb::ClientMessage ask;
    ask.mutable_get_statistics();
    if (!request(ask).has_statistics()) return std::nullopt;
    while (const auto event = nextEvent(Duration(0))) {
      if (event->has_frame_update()) last = event->frame_update();
    }
  }
  return last;
}

}  // namespace voxhap::net
