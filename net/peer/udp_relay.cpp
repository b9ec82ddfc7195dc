#include "net/peer/udp_relay.h"

#include "haptics/core/error.h"

namespace voxhap::net {
namespace {

constexpr std::size_t kLargestUdpPayload = 65507;

asio::ip::udp::endpoint endpointOf(const std::string& host, std::uint16_t port, const char* what) {
  asio::error_code ec;
  const asio::ip::address address = asio::ip::make_address(host, ec);
  if (ec) throw Error(std::string(what) + " '" + host + "' is not an IP address");
  return {address, port};
}

ImpairmentSettings replySettings(ImpairmentSettings s) {
  s.seed += 1;
  return s;
}

}  // namespace

UdpRelay::UdpRelay(asio::io_context& io, const UdpRelayOptions& options)
    : io_(io),
      front_(io),
      maxClients_(options.maxClients),
      timer_(io),
      toTarget_(options.impairment),
      fromTarget_(replySettings(options.impairment)),
      maxQueued_(options.maxQueued),
      frontBuffer_(kLargestUdpPayload) {
  const asio::ip::udp::endpoint listen =
      endpointOf(options.listenHost, options.listenPort, "the relay's address");
  target_ = endpointOf(options.targetHost, options.targetPort, "the relay's target");
  if (options.targetPort == 0) throw Error("the relay's target needs a port");
  asio::error_code ec;
  front_.open(listen.protocol());
  front_.bind(listen, ec);
  if (ec) {
    throw Error("the relay cannot listen on " + options.listenHost + ":" +
                std::to_string(options.listenPort) + ": " + ec.message());
  }
  receiveFront();
}

UdpRelay::Client* UdpRelay::clientOf(const asio::ip::udp::endpoint& front) {
  if (const auto it = clients_.find(front); it != clients_.end()) return it->second.get();
  if (clients_.size() >= maxClients_) return nullptr;
  auto client = std::unique_ptr<Client>(
      new Client{front,
                 asio::ip::udp::socket(io_, asio::ip::udp::endpoint(target_.protocol(), 0)),
                 std::vector<std::uint8_t>(kLargestUdpPayload),
                 {}});
  Client& c = *client;
  clients_.emplace(front, std::move(client));
  receiveBack(c);
  return &c;
}

void UdpRelay::receiveFront() {
  front_.async_receive_from(asio::buffer(frontBuffer_), frontSender_,
                            [this](asio::error_code ec, std::size_t n) {
                              if (ec == asio::error::operation_aborted) return;
                              if (!ec) {
                                if (Client* client = clientOf(frontSender_)) {
                                  hold(true, *client, frontBuffer_.data(), n);
                                } else {
                                  ++counts_.toTarget.received;
                                  ++counts_.toTarget.dropped;
                                }
                              }
                              receiveFront();
                            });
}

void UdpRelay::receiveBack(Client& client) {
  client.back.async_receive_from(asio::buffer(client.buffer), client.sender,
                                 [this, &client](asio::error_code ec, std::size_t n) {
                                   if (ec == asio::error::operation_aborted) return;
                                   if (!ec) hold(false, client, client.buffer.data(), n);
                                   receiveBack(client);
                                 });
}

void UdpRelay::hold(bool toTarget, Client& client, const std::uint8_t* data, std::size_t size) {
  RelayDirectionCounts& c = toTarget ? counts_.toTarget : counts_.fromTarget;
  ++c.received;
  const DatagramFate fate = (toTarget ? toTarget_ : fromTarget_).next();
  if (fate.copies == 0) {
    ++c.lost;
    return;
  }
  if (fate.copies == 2) ++c.duplicated;
  const Clock::time_point now = Clock::now();
  for (int i = 0; i < fate.copies; ++i) {
    if (held_.size() >= maxQueued_) {
      ++c.dropped;
      continue;
    }
    const auto due =
        now + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(fate.delayS[i]));
    held_.emplace(std::make_pair(due, arrivals_++),
                  Held{toTarget, &client, std::vector<std::uint8_t>(data, data + size)});
  }
  armTimer();
}

void UdpRelay::armTimer() {
  if (held_.empty()) return;
  timer_.expires_at(held_.begin()->first.first);
  timer_.async_wait([this](asio::error_code ec) {
    if (ec == asio::error::operation_aborted) return;
    sendDue();
    armTimer();
  });
}

void UdpRelay::sendDue() {
  const Clock::time_point now = Clock::now();
  while (!held_.empty() && held_.begin()->first.first <= now) {
    const Held& h = held_.begin()->second;
    RelayDirectionCounts& c = h.toTarget ? counts_.toTarget : counts_.fromTarget;
    asio::error_code ec;
    if (h.toTarget) {
      h.client->back.send_to(asio::buffer(h.bytes), target_, 0, ec);
    } else {
      front_.send_to(asio::buffer(h.bytes), h.client->front, 0, ec);
    }
    ++(ec ? c.dropped : c.sent);
    held_.erase(held_.begin());
  }
}

}  // namespace voxhap::net
