// `voxhap relay` as the real executable on loopback: datagrams from a test socket go
// through it to another and back; usage mistakes exit 2. Every wait is bounded.

#include <csignal>

#include <asio/io_context.hpp>
#include <asio/ip/udp.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/child_process.h"
#include "support/cli_runner.h"
#include "support/udp_receive.h"

namespace voxhap::test {
namespace {

using asio::ip::udp;
using namespace std::chrono_literals;

class RelayCommand : public CliTest {};

TEST_F(RelayCommand, UsageErrorsExitTwo) {
  for (const std::vector<std::string>& args : {std::vector<std::string>{"relay"},
                                               {"relay", "--to", "127.0.0.1"},
                                               {"relay", "--to", "127.0.0.1:0"},
                                               {"relay", "--to", "127.0.0.1:9", "--loss", "150%"},
                                               {"relay", "--to", "127.0.0.1:9", "--delay", "-1ms"},
                                               {"relay", "--to", "127.0.0.1:9", "--seed", "x"}}) {
    const CliRun r = voxhap(args);
    EXPECT_EQ(r.exitCode, 2) << args.back() << "\n" << r.err;
    EXPECT_NE(r.err.find("see --help"), std::string::npos) << r.err;
  }
  const CliRun help = voxhap({"relay", "--help"});
  EXPECT_EQ(help.exitCode, 0);
  EXPECT_NE(help.out.find("--jitter"), std::string::npos);
}

TEST_F(RelayCommand, ForwardsBothWaysLosesWhatItIsToldAndCountsIt) {
  asio::io_context io;
  const auto loopback = asio::ip::make_address("127.0.0.1");
  udp::socket target(io, udp::endpoint(loopback, 0));
  udp::socket client(io, udp::endpoint(loopback, 0));
  ChildProcess relay(VOXHAP_EXE,
                     {"relay", "--to", "127.0.0.1:" + std::to_string(target.local_endpoint().port()),
                      "--delay", "1ms", "--loss", "50%", "--seed", "3", "--json"},
                     dir_);
  const auto port = relay.waitForStderr("relaying 127.0.0.1:", 30s);
  ASSERT_TRUE(port) << relay.err();
  const udp::endpoint relayAt(loopback, static_cast<std::uint16_t>(std::stoi(*port)));

  const int sent = 200;
  for (std::uint32_t i = 0; i < sent; ++i) client.send_to(asio::buffer(&i, sizeof i), relayAt);
  int arrived = 0;
  udp::endpoint relayBack;
  while (receiveNumber(target, 500ms, &relayBack)) ++arrived;
  EXPECT_GT(arrived, sent / 4);  // half are lost: 100 ± 7
  EXPECT_LT(arrived, sent * 3 / 4);
  // an answer goes back through the relay to the client, or is lost on the way
  for (std::uint32_t i = 0; i < 20; ++i) target.send_to(asio::buffer(&i, sizeof i), relayBack);
  int answers = 0;
  while (receiveNumber(client, 500ms)) ++answers;
  EXPECT_GT(answers, 0);

  relay.signal(SIGINT);
  const auto status = relay.wait(10s);
  ASSERT_TRUE(status) << relay.err();
  EXPECT_EQ(*status, 0) << relay.err();
  const nlohmann::json summary = nlohmann::json::parse(relay.out());
  EXPECT_EQ(summary.at("stopped_by"), "SIGINT");
  EXPECT_EQ(summary.at("to_target").at("received").get<int>(), sent);
  EXPECT_EQ(summary.at("to_target").at("sent").get<int>(), arrived);
  EXPECT_EQ(summary.at("to_target").at("lost").get<int>(), sent - arrived);
  EXPECT_EQ(summary.at("from_target").at("received").get<int>(), 20);
  EXPECT_EQ(summary.at("from_target").at("sent").get<int>(), answers);
}

}  // namespace
}  // namespace voxhap::test
