#pragma once
/// A UDP forwarder with a seeded bad network in between (impairment.h), for testing peers
/// on one machine (issue 12, item 6). It listens at one address and forwards what it
/// receives to a target, from a socket of its own for each client (as a NAT would), so
/// that what the target sends back to that socket goes to that client: several peers can
/// share one relay in front of another. Each direction has its own Impairment (the reply
/// path seeded with seed + 1). It runs on the caller's io_context, on one thread: its counts
/// are read on that thread or once the context has stopped.

#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
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
  std::size_t maxClients = 64;    ///< senders it keeps a socket for; others' datagrams are dropped
};

/// What happened to the datagrams of one direction.
struct RelayDirectionCounts {
  std::uint64_t received = 0;
  std::uint64_t lost = 0;        ///< dropped by the impairment
  std::uint64_t duplicated = 0;  ///< sent twice by the impairment
  std::uint64_t sent = 0;        ///< copies sent on, duplicates included
  std::uint64_t dropped = 0;     ///< queue full, send failed, or a client too many
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
  /// A sender on the front side, and the socket that talks to the target for it.
  struct Client {
    asio::ip::udp::endpoint front;
    asio::ip::udp::socket back;
    std::vector<std::uint8_t> buffer;
    asio::ip::udp::endpoint sender;
  };
  struct Held {
    bool toTarget = true;
    Client* client = nullptr;
    std::vector<std::uint8_t> bytes;
  };

  void receiveFront();
  void receiveBack(Client& client);
  /// The client that sent from `front`, made on first use; null beyond maxClients.
  Client* clientOf(const asio::ip::udp::endpoint& front);
  void hold(bool toTarget, Client& client, const std::uint8_t* data, std::size_t size);
  void armTimer();
  void sendDue();

  asio::io_context& io_;
  asio::ip::udp::socket front_;  ///< where clients send
  asio::ip::udp::endpoint target_;
  std::map<asio::ip::udp::endpoint, std::unique_ptr<Client>> clients_;
  std::size_t maxClients_;
  asio::steady_timer timer_;
  Impairment toTarget_;
  Impairment fromTarget_;
  std::size_t maxQueued_;
  std::map<std::pair<Clock::time_point, std::uint64_t>, Held> held_;  ///< by due time, then arrival
  std::uint64_t arrivals_ = 0;
  std::vector<std::uint8_t> frontBuffer_;
  asio::ip::udp::endpoint frontSender_;
  UdpRelayCounts counts_;
};

}  // namespace voxhap::net
