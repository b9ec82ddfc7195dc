#pragma once
/// A free UDP port on loopback, for a peer whose port others need before it starts (the
/// first of an in-process session, a peer behind a relay). Bound and let go: another
/// program may take it in between, as with any port chosen ahead.

#include <cstdint>

#include <asio/io_context.hpp>
#include <asio/ip/udp.hpp>

namespace voxhap::net {

inline std::uint16_t freeLoopbackUdpPort() {
  asio::io_context io;
  asio::ip::udp::socket socket(io, asio::ip::udp::endpoint(asio::ip::make_address("127.0.0.1"), 0));
  return socket.local_endpoint().port();
}

}  // namespace voxhap::net
