#pragma once
/// A UDP forwarder with a seeded bad network in between (impairment.h), for testing peers
/// on one machine (issue 12, item 6). It listens at one address and forwards what it
/// receives to a target; what the target sends back to it goes to the last address that
/// sent to the listening side. Each direction has its own Impairment (the reply path
/// seeded with seed + 1). It runs on the caller's io_context, on one thread: its counts
/// are read on that thread or once the context has stopped.

#include <chrono>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <asio/io_context.hpp>
#include <asio/ip/udp.hpp>
#include <asio/steady_timer.hpp>

#include "net/peer/impairment.h"

namespace voxhap::net {

struct UdpRelayOptions {
  std::string listenHost = "127.0.0.1";
  std::uint16_t listenPort = 0;  ///< 0: any free port (port() says which)
  std::string targetHost = "127.0.0.1";
  std::uint16_t targetPort = 0;
  ImpairmentSettings impairment;  ///< both directions
  std::size_t maxQueued = 4096;   ///< datagrams held back at once; more are dropped and counted
};

/// What happened to the datagrams of one direction.
struct RelayDirectionCounts {
  std::uint64_t received = 0;
  std::uint64_t lost = 0;        ///< dropped by the impairment
  std::uint64_t duplicated = 0;  ///< sent twice by the impairment
  std::uint64_t sent = 0;        ///< copies sent on, duplicates included
  std::uint64_t dropped = 0;     ///< queue full, send failed, or a reply with nobody to go to
};

struct UdpRelayCounts {
  RelayDirectionCounts toTarget;
  RelayDirectionCounts fromTarget;
};

class UdpRelay {
public:
  /// Binds both sockets and starts receiving; throws Error naming the address that fails
  /// or the setting that is wrong.
  UdpRelay(asio::io_context& io, const UdpRelayOptions& options);

  /// The listening port.
  std::uint16_t port() const { return front_.local_endpoint().port(); }
  const UdpRelayCounts& counts() const { return counts_; }

private:
  using Clock = std::chrono::steady_clock;
  struct Held {
    bool toTarget = true;
    std::vector<std::uint8_t> bytes;
  };

  void receive(bool fromFront);
  void hold(bool toTarget, const std::uint8_t* data, std::size_t size);
  void armTimer();
  void sendDue();

  asio::ip::udp::socket front_;  ///< where clients send
  asio::ip::udp::socket back_;   ///< talks to the target
  asio::ip::udp::endpoint target_;
  asio::ip::udp::endpoint client_;  ///< the last sender on the front side
  bool haveClient_ = false;
  asio::steady_timer timer_;
  Impairment toTarget_;
  Impairment fromTarget_;
  std::size_t maxQueued_;
  std::map<std::pair<Clock::time_point, std::uint64_t>, Held> held_;  ///< by due time, then arrival
  std::uint64_t arrivals_ = 0;
  std::vector<std::uint8_t> frontBuffer_;
  std::vector<std::uint8_t> backBuffer_;
  asio::ip::udp::endpoint frontSender_;
  asio::ip::udp::endpoint backSender_;
  UdpRelayCounts counts_;
};

}  // namespace voxhap::net
