#pragma once
/// Test support: a bounded read of one datagram from an Asio UDP socket. (Asio's own
/// blocking receive polls again on EAGAIN, so SO_RCVTIMEO cannot bound it.)

#include <chrono>
#include <cstdint>
#include <optional>

#include <asio/ip/udp.hpp>
#include <poll.h>

namespace voxhap::test {

/// The 4-byte number in the next datagram to reach `socket` within `timeout`, and its
/// sender in `from`; none when nothing came or the datagram is not 4 bytes.
inline std::optional<std::uint32_t> receiveNumber(asio::ip::udp::socket& socket,
                                                  std::chrono::milliseconds timeout,
                                                  asio::ip::udp::endpoint* from = nullptr) {
  pollfd waitFor{socket.native_handle(), POLLIN, 0};
  if (::poll(&waitFor, 1, static_cast<int>(timeout.count())) != 1) return std::nullopt;
  std::uint32_t n = 0;
  asio::ip::udp::endpoint sender;
  asio::error_code ec;
  const std::size_t size = socket.receive_from(asio::buffer(&n, sizeof n), sender, 0, ec);
  if (ec || size != sizeof n) return std::nullopt;
  if (from) *from = sender;
  return n;
}

}  // namespace voxhap::test
