// `voxhap relay`: a UDP forwarder with a seeded bad network in between (net/peer/udp_relay.h),
// for trying peers on one machine at a delay, with jitter, loss and duplicates.

#include <csignal>
#include <optional>

#include <CLI/CLI.hpp>
#include <asio/io_context.hpp>
#include <asio/signal_set.hpp>
#include <asio/steady_timer.hpp>
#include <nlohmann/json.hpp>

#include "app/cli/command.h"
#include "app/cli/endpoint_options.h"
#include "app/cli/number_format.h"
#include "app/cli/option_values.h"
#include "app/commands/commands.h"
#include "haptics/core/error.h"
#include "net/peer/udp_relay.h"

namespace voxhap::cli {
namespace {

/// What `voxhap relay` was given.
struct RelayArgs {
  std::string to;
  std::string listen = "127.0.0.1:0";
  net::ImpairmentSettings impairment;
  std::optional<double> durationS;
  bool json = false;
};

nlohmann::json countsJson(const net::RelayDirectionCounts& c) {
  return {{"received", c.received},
          {"lost", c.lost},
          {"duplicated", c.duplicated},
          {"sent", c.sent},
          {"dropped", c.dropped}};
}

std::string countsLine(const char* direction, const net::RelayDirectionCounts& c) {
  return std::string(direction) + ": " + std::to_string(c.received) + " received, " + std::to_string(c.lost) +
         " lost, " + std::to_string(c.duplicated) + " duplicated, " + std::to_string(c.sent) + " sent, " +
         std::to_string(c.dropped) + " dropped";
}

int runRelayCommand(const RelayArgs& args, const CommandContext& c) {
  if (args.to.empty()) throw UsageError("--to HOST:PORT is required (where the relay forwards to)");
  const HostPort target = parseHostPort(args.to, "--to");
  if (target.port == 0) throw UsageError("--to wants a port other than 0");
  const HostPort listen = parseHostPort(args.listen, "--listen");
  net::UdpRelayOptions options;
  options.listenHost = listen.host;
  options.listenPort = listen.port;
  options.targetHost = target.host;
  options.targetPort = target.port;
  options.impairment = args.impairment;

  asio::io_context io;
  net::UdpRelay relay(io, options);
  const auto& s = args.impairment;
  c.console.info("relaying " + listen.host + ":" + std::to_string(relay.port()) + " to " + args.to +
                 ": delay " + fixed(s.delayS * 1e3, 1) + " ms ± " + fixed(s.jitterS * 1e3, 1) + " ms, loss " +
                 fixed(s.lossRate * 100, 1) + " %, duplicates " + fixed(s.duplicateRate * 100, 1) +
                 " %, seed " + std::to_string(s.seed));
  std::string stoppedBy = "the duration ran out";
  asio::signal_set signals(io, SIGINT, SIGTERM);
  signals.async_wait([&](const asio::error_code& e, int signal) {
    if (e) return;
    stoppedBy = signal == SIGINT ? "SIGINT" : "SIGTERM";
    io.stop();
  });
  asio::steady_timer duration(io);
  if (args.durationS) {
    duration.expires_after(std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(*args.durationS)));
    duration.async_wait([&](const asio::error_code& e) {
      if (!e) io.stop();
    });
  }
  io.run();

  const net::UdpRelayCounts& counts = relay.counts();
  if (args.json) {
    c.out << nlohmann::json{{"stopped_by", stoppedBy},
                            {"port", relay.port()},
                            {"to_target", countsJson(counts.toTarget)},
                            {"from_target", countsJson(counts.fromTarget)}}
                 .dump(2)
          << "\n";
  } else {
    c.out << "stopped by " << stoppedBy << "\n"
          << countsLine("to the target", counts.toTarget) << "\n"
          << countsLine("back from it", counts.fromTarget) << "\n";
  }
  return kExitOk;
}

}  // namespace

void addRelayCommand(CommandTree& tree) {
  CommandHelp help;
  help.summary = "A UDP relay that delays, spreads, loses and duplicates datagrams, as a bad network would.";
  help.usage =
      "voxhap relay --to HOST:PORT [--listen HOST:PORT] [--delay TIME] [--jitter TIME] [--loss SHARE]\n"
      "       [--duplicate SHARE] [--seed N] [--duration TIME] [--json]";
  help.description =
      "Forwards the UDP datagrams it receives at --listen to --to, from a socket of its own for\n"
      "each sender (as a NAT would), and what --to sends back to that socket on to that sender:\n"
      "put one in front of a peer on one machine (the others send to it) to give its path a delay (each "
      "datagram held for a time drawn from [delay − jitter,\n"
      "delay + jitter], so that jitter reorders them), loss and duplicates, as `tc netem` would.\n"
      "The same seed gives the same fates to the same datagrams in the same order, in both\n"
      "directions (the reply path takes seed + 1). It listens on 127.0.0.1 at any free port by\n"
      "default and says where on stderr; it runs until SIGINT, SIGTERM or --duration, then\n"
      "prints what it received, lost, duplicated, sent on and dropped in each direction.\n\n"
      "Examples:\n"
      "  voxhap relay --listen 127.0.0.1:7501 --to 127.0.0.1:7500 --delay 100ms --jitter 10ms --loss 5%\n"
      "  voxhap relay --to 127.0.0.1:7500 --delay 300ms --loss 0.05 --duplicate 1% --seed 7 --duration 60 "
      "--json";
  auto args = std::make_shared<RelayArgs>();
  CLI::App& command = tree.add(tree.root(), "relay", std::move(help),
                               [args](const CommandContext& c) { return runRelayCommand(*args, c); });
  command.add_option("--to", args->to, "where datagrams go (required)")->type_name("HOST:PORT");
  command
      .add_option("--listen", args->listen, "where the relay receives (default 127.0.0.1:0, any free port)")
      ->type_name("HOST:PORT");
  net::ImpairmentSettings& s = args->impairment;
  addParsedOption(command, "--delay", "TIME", "mean delay added each way, e.g. 100ms (default 0)",
                  [&s](const std::string& text) { s.delayS = parseSeconds(text, "delay"); });
  addParsedOption(command, "--jitter", "TIME", "half-width of the delay's uniform spread (default 0)",
                  [&s](const std::string& text) { s.jitterS = parseSeconds(text, "jitter"); });
  addParsedOption(command, "--loss", "SHARE", "share of datagrams lost, e.g. 5% or 0.05 (default 0)",
                  [&s](const std::string& text) { s.lossRate = parseFraction(text, "loss"); });
  addParsedOption(command, "--duplicate", "SHARE", "share of datagrams delivered twice (default 0)",
                  [&s](const std::string& text) { s.duplicateRate = parseFraction(text, "duplicate"); });
  addUnsignedOption(command, "--seed", s.seed, "seed of the draws (default 1)");
  addParsedOption(command, "--duration", "TIME", "stop after this much wall time (default: run until told)",
                  [&d = args->durationS](const std::string& text) { d = parseSeconds(text, "duration"); });
  command.add_flag("--json", args->json, "print the counts as one JSON document on stdout");
}

}  // namespace voxhap::cli
