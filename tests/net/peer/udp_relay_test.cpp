// The relay on loopback with real sockets: a client sends numbered datagrams through it to
// an echo target and reads what comes back. Every wait is bounded.
#include "net/peer/udp_relay.h"

#include <cstring>
#include <future>
#include <set>
#include <thread>

#include <asio/ip/udp.hpp>
#include <gtest/gtest.h>

#include "haptics/core/error.h"
#include "support/udp_receive.h"

namespace voxhap::net {
namespace {

using asio::ip::udp;
using namespace std::chrono_literals;

/// A relay in front of a target socket, both on loopback, the relay's io_context on its
/// own thread; a client socket that sends to the relay.
struct RelayFixture {
  explicit RelayFixture(ImpairmentSettings impairment) : target_(targetIo_, udp::endpoint(loopback(), 0)) {
    UdpRelayOptions options;
    options.targetPort = target_.local_endpoint().port();
    options.impairment = impairment;
    relay_ = std::make_unique<UdpRelay>(io_, options);
    client_.open(udp::v4());
    client_.bind(udp::endpoint(loopback(), 0));
    thread_ = std::thread([this] { io_.run(); });
  }
  ~RelayFixture() { stop(); }
  void stop() {
    io_.stop();
    if (thread_.joinable()) thread_.join();
  }
  static asio::ip::address loopback() { return asio::ip::make_address("127.0.0.1"); }

  void send(std::uint32_t n) {
    client_.send_to(asio::buffer(&n, sizeof n), udp::endpoint(loopback(), relay_->port()));
  }
  /// The numbers that reach `socket` until nothing comes for `quiet`, in arrival order,
  /// read on another thread while the test sends (a socket's buffer holds only a few
  /// hundred small datagrams).
  static std::future<std::vector<std::uint32_t>> receiveAll(udp::socket& socket,
                                                            std::chrono::milliseconds quiet,
                                                            udp::endpoint* from = nullptr) {
    return std::async(std::launch::async, [&socket, quiet, from] {
      std::vector<std::uint32_t> got;
      while (const auto n = test::receiveNumber(socket, quiet, from)) got.push_back(*n);
      return got;
    });
  }
  /// The relay's counts, read once its thread has stopped.
  const UdpRelayCounts& counts() {
    stop();
    return relay_->counts();
  }

  asio::io_context io_;
  asio::io_context targetIo_;
  asio::io_context clientIo_;
  udp::socket target_;
  udp::socket client_{clientIo_};
  std::unique_ptr<UdpRelay> relay_;
  std::thread thread_;
};

TEST(UdpRelay, ACleanRelayPassesEverythingInOrderAndRepliesGoBackToTheSender) {
  RelayFixture f({});
  udp::endpoint relayBack;
  auto arriving = RelayFixture::receiveAll(f.target_, 1000ms, &relayBack);
  for (std::uint32_t i = 0; i < 200; ++i) f.send(i);
  const std::vector<std::uint32_t> got = arriving.get();
  ASSERT_EQ(got.size(), 200u);
  for (std::uint32_t i = 0; i < 200; ++i) EXPECT_EQ(got[i], i);
  // the target answers the relay; the answer reaches the client
  auto replying = RelayFixture::receiveAll(f.client_, 1000ms);
  for (std::uint32_t i = 1000; i < 1010; ++i) f.target_.send_to(asio::buffer(&i, sizeof i), relayBack);
  const std::vector<std::uint32_t> replies = replying.get();
  EXPECT_EQ(replies.size(), 10u);
  const UdpRelayCounts& c = f.counts();
  EXPECT_EQ(c.toTarget.received, 200u);
  EXPECT_EQ(c.toTarget.sent, 200u);
  EXPECT_EQ(c.fromTarget.sent, 10u);
}

TEST(UdpRelay, EachClientHasItsOwnSocketSoRepliesGoToTheirOwnClient) {
  RelayFixture f({});
  udp::socket second(f.clientIo_, udp::endpoint(RelayFixture::loopback(), 0));
  const udp::endpoint relay(RelayFixture::loopback(), f.relay_->port());
  // each client's datagram reaches the target from its own relay socket; the target
  // answers each at that socket, and each answer reaches its own client
  udp::endpoint firstVia, secondVia;
  f.send(1);
  ASSERT_EQ(test::receiveNumber(f.target_, 1000ms, &firstVia), 1u);
  const std::uint32_t two = 2;
  second.send_to(asio::buffer(&two, sizeof two), relay);
  ASSERT_EQ(test::receiveNumber(f.target_, 1000ms, &secondVia), 2u);
  EXPECT_NE(firstVia, secondVia);
  for (const auto& [via, n] : {std::pair{secondVia, 20u}, std::pair{firstVia, 10u}})
    f.target_.send_to(asio::buffer(&n, sizeof n), via);
  EXPECT_EQ(test::receiveNumber(f.client_, 1000ms), 10u);
  EXPECT_EQ(test::receiveNumber(second, 1000ms), 20u);
}

TEST(UdpRelay, LossDuplicationAndJitterShowInWhatArrivesAndInTheCounts) {
  // 5 ms ± 5 ms, sent every 0.2 ms (or more on a loaded machine): overtaking is common
  RelayFixture f({0.005, 0.005, 0.2, 0.2, 99});
  const std::uint32_t n = 500;
  auto arriving = RelayFixture::receiveAll(f.target_, 1000ms);
  for (std::uint32_t i = 0; i < n; ++i) {
    f.send(i);
    std::this_thread::sleep_for(200us);
  }
  const std::vector<std::uint32_t> got = arriving.get();
  const UdpRelayCounts& c = f.counts();
  EXPECT_EQ(c.toTarget.received, n);
  EXPECT_EQ(got.size(), c.toTarget.sent);
  EXPECT_EQ(c.toTarget.sent, n - c.toTarget.lost + c.toTarget.duplicated);
  EXPECT_EQ(c.toTarget.dropped, 0u);
  EXPECT_GT(c.toTarget.lost, n / 10);  // 20 %: about 100
  EXPECT_LT(c.toTarget.lost, n * 3 / 10);
  EXPECT_GT(c.toTarget.duplicated, n / 20);
  const std::set<std::uint32_t> distinct(got.begin(), got.end());
  EXPECT_EQ(got.size() - distinct.size(), c.toTarget.duplicated);
  int overtaken = 0;
  for (std::size_t i = 1; i < got.size(); ++i) overtaken += got[i] < got[i - 1];
  EXPECT_GT(overtaken, 10);
}

TEST(UdpRelay, ADelayHoldsDatagramsBackAtLeastThatLong) {
  RelayFixture f({0.05, 0.0, 0.0, 0.0, 1});
  const auto sent = std::chrono::steady_clock::now();
  f.send(1);
  ASSERT_EQ(test::receiveNumber(f.target_, 5000ms), 1u);
  const auto took = std::chrono::steady_clock::now() - sent;
  EXPECT_GE(took, 50ms);  // a lower bound only: a loaded machine may take longer
}

TEST(UdpRelay, BadAddressesAreClearErrors) {
  asio::io_context io;
  UdpRelayOptions options;
  options.targetPort = 9;
  options.listenHost = "not-an-address";
  EXPECT_THROW(UdpRelay(io, options), Error);
  options.listenHost = "127.0.0.1";
  options.targetPort = 0;
  EXPECT_THROW(UdpRelay(io, options), Error);
}

}  // namespace
}  // namespace voxhap::net
