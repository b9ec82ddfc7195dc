// `voxhap bench latency`: how long a handle motion takes to come back to a front end as a
// pose. A controller runs in this process (the same runController as `voxhap controller`)
// on a loopback port; a client of the front-end protocol grabs an object with its own
// handle, subscribes at 1 kHz and moves the handle to a new place again and again, timing
// each move from just before it is sent to the first frame update that shows the handle
// there. That path is the device's: a mailbox into the haptic thread (at most one frame),
// the frame's snapshot, the comms thread's 1 kHz update timer, TCP over loopback.

#include <algorithm>
#include <chrono>
#include <thread>

#include <CLI/CLI.hpp>

#include "app/bench/benchmark.h"
#include "app/cli/number_format.h"
#include "app/controller/inprocess_controller.h"
#include "app/sim_options.h"
#include "haptics/core/error.h"
#include "net/frontend/frontend_client.h"

namespace voxhap::cli {
namespace {

namespace pb = net::pb;
using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

struct LatencyBenchArgs {
  // not the ball-and-socket: at 1 mm its seated ball is a press fit whose frames overrun
  // 1 ms (its pose then lags by the overrun, which is the engine's cost, not the path's)
  std::string scene = "peg-in-hole";
  std::string move = "peg";
  std::uint64_t samples = 2000;
  bool realtime = true;
  SimOptions sim;
};

double percentileUs(std::vector<double> sortedUs, double q) {
  if (sortedUs.empty()) return 0.0;
  const auto i = static_cast<std::size_t>(q * static_cast<double>(sortedUs.size() - 1) + 0.5);
  return sortedUs[std::min(i, sortedUs.size() - 1)];
}

BenchTable runLatencyBench(const LatencyBenchArgs& args, Console& console) {
  if (args.samples < 10) throw UsageError("--samples wants at least 10 moves");
  ControllerOptions options;
  options.scene = args.scene;
  options.moving = {args.move};
  options.model = sceneModelOptions(args.sim, console, 1e-3, std::nullopt);
  options.realtime = args.realtime;
  InProcessController controller(options, console);

  std::vector<double> latenciesUs;
  std::uint64_t lost = 0;
  {
    net::FrontendClient client("127.0.0.1", controller.port(), 5000ms);
    client.hello("bench latency");
    pb::ClientMessage grab;
    grab.mutable_grab()->set_object(args.move);
    grab.mutable_grab()->set_device("client");
    if (const pb::ServerMessage r = client.request(grab); r.has_error())
      throw Error("grab " + args.move + ": " + r.error().message());
    pb::ClientMessage subscribe;
    subscribe.mutable_subscribe()->set_rate_hz(1000.0);
    client.request(subscribe);

    const ProgressFn progress = console.progress("moving the handle");
    for (std::uint64_t i = 1; i <= args.samples; ++i) {
      // a new place each time, within 0.1 mm of the start: x in steps of 0.1 µm
      pb::ClientMessage move;
      move.mutable_move_handle()->set_object(args.move);
      const double xM = 1e-7 * static_cast<double>(i % 1000 + 1);
      move.mutable_move_handle()->mutable_handle()->mutable_position_m()->set_x(xM);
      move.mutable_move_handle()->mutable_handle()->mutable_orientation()->set_w(1.0);
      const Clock::time_point sent = Clock::now();
      client.request(move);
      bool seen = false;
      while (!seen && Clock::now() - sent < 1s) {
        const auto event = client.nextEvent(100ms);
        if (!event || !event->has_frame_update() || event->frame_update().objects_size() == 0) continue;
        const pb::ObjectState& o = event->frame_update().objects(0);
        seen = o.has_handle() && o.handle().position_m().x() == xM;
      }
      if (seen) {
        latenciesUs.push_back(std::chrono::duration<double, std::micro>(Clock::now() - sent).count());
      } else {
        ++lost;
      }
      // the next move at another phase of the 1 ms frame: 0 to 0.97 ms later, in steps of 31 µs
      std::this_thread::sleep_for(std::chrono::microseconds((i * 31) % 1000));
      if (progress) progress(static_cast<double>(i) / static_cast<double>(args.samples));
    }
  }
  const std::string summary = controller.stopAndWait();

  std::sort(latenciesUs.begin(), latenciesUs.end());
  const nlohmann::json run = nlohmann::json::parse(summary);
  BenchTable table("latency", {
                                  {"samples", "moves", BenchStyle::Count},
                                  {"lost", "lost", BenchStyle::Count},
                                  {"latency_p50_us", "p50 us", BenchStyle::Fixed, 0},
                                  {"latency_p90_us", "p90 us", BenchStyle::Fixed, 0},
                                  {"latency_p99_us", "p99 us", BenchStyle::Fixed, 0},
                                  {"latency_max_us", "max us", BenchStyle::Fixed, 0},
                                  {"period_p50_us", "period p50", BenchStyle::Fixed, 0},
                                  {"period_p99_us", "period p99", BenchStyle::Fixed, 0},
                                  {"period_max_us", "period max", BenchStyle::Fixed, 0},
                                  {"sched_fifo", "FIFO", BenchStyle::Text},
                              });
  const std::size_t r = table.addRow();
  table.set(r, "samples", static_cast<std::int64_t>(args.samples));
  table.set(r, "lost", static_cast<std::int64_t>(lost));
  table.set(r, "latency_p50_us", percentileUs(latenciesUs, 0.5));
  table.set(r, "latency_p90_us", percentileUs(latenciesUs, 0.9));
  table.set(r, "latency_p99_us", percentileUs(latenciesUs, 0.99));
  table.set(r, "latency_max_us", latenciesUs.empty() ? 0.0 : latenciesUs.back());
  table.set(r, "period_p50_us", run.at("period").at("p50_us").get<double>());
  table.set(r, "period_p99_us", run.at("period").at("p99_us").get<double>());
  table.set(r, "period_max_us", run.at("period").at("max_us").get<double>());
  table.set(r, "sched_fifo", std::string(run.at("sched_fifo").get<bool>() ? "yes" : "no"));
  table.extra["scene"] = run.at("scene");
  table.extra["object"] = args.move;
  table.extra["subscription_hz"] = 1000;
  return table;
}

}  // namespace

Benchmark latencyBenchmark() {
  Benchmark b;
  b.name = "latency";
  b.summary = "Handle motion to pose at a front end, through a controller on loopback.";
  b.usage = "[--samples N] [--scene SCENE --move NAME] [--voxel-size LENGTH] [--no-realtime]";
  b.description =
      "Starts a haptic controller in this process on a free loopback port, as `voxhap controller`\n"
      "runs it, and a front-end client that grabs the object with its own handle (device\n"
      "'client', the path a mouse or any device report takes: a mailbox into the haptic thread),\n"
      "subscribes to frame updates at 1 kHz and moves the handle N times, each to a new place.\n"
      "A move's latency is from just before its request is sent to the first frame update that\n"
      "shows the handle there: at most a frame to reach the haptic thread, then the frame, the\n"
      "comms thread's 1 kHz update timer and loopback TCP. Moves are spread over the phase of\n"
      "the 1 ms frame. Reports the latency's p50/p90/p99/max and the haptic period over the run;\n"
      "a move not seen within 1 s is counted lost.\n\n"
      "Examples:\n"
      "  voxhap bench latency\n"
      "  voxhap bench latency --samples 10000 --no-realtime --json";
  b.addOptions = [](CLI::App& command) {
    auto args = std::make_shared<LatencyBenchArgs>();
    command.add_option("--samples", args->samples, "handle moves to time (default 2000)")->type_name("N");
    command.add_option("--scene", args->scene, "scene to load (default peg-in-hole)")->type_name("SCENE");
    command.add_option("--move", args->move, "the object the client's handle holds (default peg)")
        ->type_name("NAME");
    command.add_flag(
        "--no-realtime", [args](std::int64_t) { args->realtime = false; },
        "do not ask for SCHED_FIFO and mlockall");
    addSimOptions(command, args->sim, {SimOption::VoxelSize, SimOption::Cache});
    return [args](Console& console) { return runLatencyBench(*args, console); };
  };
  return b;
}

}  // namespace voxhap::cli
